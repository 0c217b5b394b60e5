/* SPDX-License-Identifier: BSD-3-Clause */
/* A command line's number argument (cli_number.h). */
#include "cli_number.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int sim_cli_number(const char *tool, const char *flag, const char *text, double *v)
{
    char *end = NULL;
    errno = 0;
    *v = strtod(text, &end);
    if (end == text || *end != '\0' || errno != 0 || !isfinite(*v) || *v < 0.0) {
        fprintf(stderr, "%s: %s: expected a number >= 0, got '%s'\n", tool, flag, text);
        return -1;
    }
    return 0;
}
