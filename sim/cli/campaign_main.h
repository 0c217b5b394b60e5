/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ladrc_sil --campaign FILE [--list] [--shard K/N] [--jobs N] [--out DIR]
 * [--csv] [--quiet]: a campaign's runs (campaign.h), validated all before
 * anything is written, then flown in batches (fly.h).
 */
#ifndef LADRC_SIM_CAMPAIGN_MAIN_H
#define LADRC_SIM_CAMPAIGN_MAIN_H

/* The command line of campaign mode (argv holds --campaign). Returns the
 * exit status: 0 every run of the shard flew and wrote its files (diverged
 * runs included), 1 a run failed to run or write, 2 bad input. */
int sim_campaign_main(int argc, char **argv);

#endif
