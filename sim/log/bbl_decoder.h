/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The blackbox decoder's state, shared by its header reader (bbl_header.c)
 * and its frame decoder and CSV writer (log_bbl.c); not a public interface.
 */
#ifndef LADRC_SIM_LOG_BBL_DECODER_H
#define LADRC_SIM_LOG_BBL_DECODER_H

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "bbl_stream.h"
#include "log_bbl.h"

#define MAX_FIELDS 128                /* fields of one frame */
#define HEADER_LINE_MAX 2048          /* bytes of one header line */
#define INTERVAL_MAX 32768            /* of the I interval and P ratio: the skip count loops over it */
#define ROW_MAX (2 * MAX_FIELDS * 24) /* a row's text: fields of 21 characters and their ", " */

enum {
    PRED_NONE,
    PRED_PREVIOUS,
    PRED_STRAIGHT_LINE,
    PRED_AVERAGE_2,
    PRED_MINTHROTTLE,
    PRED_MOTOR_0,
    PRED_INC,
    PRED_HOME_COORD,
    PRED_1500,
    PRED_VBATREF,
    PRED_LAST_MAIN_FRAME_TIME,
    PRED_MINMOTOR,
    PRED_COUNT,
    PRED_HOME_COORD_1 = 256 /* the second of a pair of home coordinates */
};

/* Frame types, in the order of the statistics. */
enum { T_I, T_P, T_S, T_G, T_H, T_E, T_COUNT };
static const char TYPES[T_COUNT + 1] = "IPSGHE";

typedef struct {
    int n;
    char names[HEADER_LINE_MAX]; /* the name line, its commas made NULs */
    int name_at[MAX_FIELDS];
    int is_signed[MAX_FIELDS];
    int predictor[MAX_FIELDS];
    int encoding[MAX_FIELDS];
} frame_def_t;

typedef struct {
    const char *name;
    bbl_stream_t in;
    frame_def_t def[T_COUNT]; /* E: none */
    int data_version;
    long minthrottle, motor_low, vbatref;
    long i_interval, p_num, p_denom;
    int baseflight; /* the header's firmware type: gyro_scale in rad/us */
    int has_gyro_scale;
    double gyro_scale;   /* deg/s (or rad/us) per logged unit */
    int motor0, gyro[3]; /* main fields by name, -1 absent */
    int home[2];         /* H fields GPS_home[0..1] */
    /* main frames: the current one and the last two valid ones */
    int64_t hist[3][MAX_FIELDS];
    int cur, prev, prev2; /* indices into hist; prev -1: none (the stream invalid) */
    int stream_valid;
    uint32_t last_iteration; /* UINT32_MAX: none yet */
    int64_t last_time_us;    /* -1: none yet */
    int64_t rollover_us;     /* 2^32 us per wrap of the logger's clock */
    int64_t last_row_us;     /* the last row written */
    int resumed, end_read;   /* the event frame just read: logging resumed, the log's end */
    uint32_t resume_iteration, resume_time_us;
    int64_t slow[MAX_FIELDS], gps[MAX_FIELDS], home_now[MAX_FIELDS], home_valid[MAX_FIELDS];
    int convert_gyro;
    double gyro_deg_s_per_unit;
    FILE *out;
    char row[ROW_MAX];
    sim_log_bbl_stats_t st;
    sim_log_convert_progress_fn progress;
    void *progress_ctx;
    long long file_bytes, next_progress;
} decoder_t;

static inline int bbl_type_of(int c)
{
    const char *p = c > 0 ? strchr(TYPES, c) : NULL;
    return p != NULL ? (int)(p - TYPES) : -1;
}

static inline int bbl_is_group(int encoding)
{
    return encoding == BBL_ENC_TAG8_8SVB || encoding == BBL_ENC_TAG2_3S32 || encoding == BBL_ENC_TAG8_4S16 ||
           encoding == BBL_ENC_TAG2_3SVARIABLE;
}

/* err set to `name: offset N: message`; -1. */
int bbl_fail_at(sim_log_error_t *err, const decoder_t *d, long long offset, const char *message);

/* Reads the header lines from the log's start into d: 0, or -1 with err set. */
int bbl_read_header(decoder_t *d, sim_log_error_t *err);

#endif
