/* SPDX-License-Identifier: BSD-3-Clause */
/* A command line's number argument, read one way by every tool. */
#ifndef LADRC_SIM_CLI_NUMBER_H
#define LADRC_SIM_CLI_NUMBER_H

/* text as a finite number >= 0 into *v: 0, or -1 after printing
 * "TOOL: FLAG: expected a number >= 0, got 'TEXT'" on stderr. */
int sim_cli_number(const char *tool, const char *flag, const char *text, double *v);

#endif
