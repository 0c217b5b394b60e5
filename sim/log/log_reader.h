/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The open reader (log.h's sim_log_t), shared by its opening (log.c) and
 * its ticks (log_tick.c).
 */
#ifndef LADRC_SIM_LOG_READER_H
#define LADRC_SIM_LOG_READER_H

#include "log.h"
#include "log_file.h"
#include "log_map.h"

struct sim_log {
    sim_log_format_t format;
    char path[SIM_LOG_PATH_LEN];
    sim_log_map_t map;
    sim_log_item_t topic_time;  /* each topic's time column (timestamp, TimeUS), us */
    sim_log_item_t sample_time; /* ArduPilot's raw sensor messages (GYR): SampleUS, us */
    sim_log_file_t *files;
    int n_files;
    int slot_file[SIM_LOG_N_SLOTS]; /* -1: the slot has no value */
    int slot_index[SIM_LOG_N_SLOTS];
    unsigned has;
    int n_motors;
    int group_has[SIM_LOG_G_COUNT]; /* a slot of the group has a value */
    /* the grid: tick k at t_first + k dt */
    double t_first_us, dt_us;
    int whole;
    long long t_first_whole, dt_whole;
    long long k, k_end, ticks;
    int after_gap;               /* the next tick given follows a skipped gap */
    long long skipped_gaps;      /* gaps the ticks jumped over */
    long long skipped_file_gaps; /* the files' gaps they are: every file's, each */
    double skipped_us;           /* their total length */
    double t_from_s;
    /* integrated attitude, from the first tick given */
    double angle[3], ref_angle[3], prev_gyro[3], prev_ref_rate[3];
    int done, failed;
    sim_log_error_t err;
};

#endif
