/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Flight logs in: a log exported to CSV, read as a stream and resampled to a
 * fixed control period, one sim_log_sample_t per control tick. The reader
 * holds a few rows per file whatever the log's length (bounded memory).
 *
 * Forms (docs/flight-logs.md has the column tables):
 * - SIM_LOG_BETAFLIGHT: one CSV as blackbox_decode writes it (`time (us)`,
 *   `gyroADC[0..2]` deg/s, `setpoint[0..3]`, `axisP/I/D/F[0..2]`, `motor[i]`,
 *   `eRPM[i]`, `gyroUnfilt[0..2]` where logged).
 * - SIM_LOG_PX4: the CSVs ulog2csv writes, one per topic, named
 *   BASE_<topic>_<instance>.csv; the path given is BASE or any one of them.
 * - SIM_LOG_ARDUPILOT: the CSVs sim_log_dataflash_to_csv writes from a
 *   DataFlash .bin, one per message type and instance, named
 *   BASE_<TYPE>_<instance>.csv (log_dataflash.h); the path given is BASE,
 *   BASE.bin or any one of them. Commands from RATE, or from PIDR/PIDP/PIDY
 *   in logs without RATE (Copter before 3.6).
 * - SIM_LOG_GENERIC: one CSV with a header row whose columns are named as
 *   the fields below (`time`, `gyro[0]`, ...: each field optional under its
 *   own name but the time, in SI units), or mapped by the caller.
 *
 * A mapping item is "FIELD=SOURCE", SOURCE one column or a sum of columns
 * `A+B+C`, optionally times a scale: `...*0.001`, `...*deg` (pi/180),
 * `...*us` (1e-6), `...*ms` (1e-3), `...*-1` (a sign). A column name may be
 * prefixed with `?`: optional, 0 when the log lacks it or reads `nan` in its
 * first row (ulog2csv's unused array entries). PX4 and ArduPilot sources
 * name their topic: `vehicle_torque_setpoint.xyz[0]`, `RATE.ROut`,
 * `ESC[1].RPM` (instance 1); each topic's time is its `timestamp` (PX4) or
 * `TimeUS` (ArduPilot), in us. Items given by the caller
 * replace the preset's item of the same FIELD. FIELDs, in SI units:
 *   time (s), gyro[0..2] (rad/s, what the log's controller used),
 *   gyro_raw[0..2] (rad/s, before its filters), angle[0..2] (rad, roll pitch
 *   yaw ZYX), quat[0..3] (w x y z), ref_angle[0..2] (rad), ref_quat[0..3],
 *   ref_rate[0..2] (rad/s), command[0..2] (the controller's output per axis,
 *   normalised: 1 is the log's full differential authority), throttle
 *   (0..1), motor[0..7] (the log's units), rotor_hz[0..7] (Hz).
 *
 * Resampling: ticks at t_k = t_first + k dt_s (integer microseconds when
 * dt_s is a whole number of them, so a log at the control rate is read back
 * exactly: a tick on a row's time takes that row's values bit for bit),
 * t_first the latest first time of the files read, up to the earliest last
 * time. Between rows each field is linear in time; quaternions are
 * interpolated component-wise and normalised. Attitude: angle from quat
 * when only quat is mapped (and the reverse); without either, the angles
 * are the integral of gyro from 0 at the first tick given (trapezoid, yaw
 * not wrapped; has & SIM_LOG_HAS_ANGLE is then clear and
 * SIM_LOG_HAS_ANGLE_INTEGRATED set). The same for the reference:
 * ref_angle from ref_quat, or the integral of ref_rate.
 *
 * Errors are `path:line:column: message` (1-based; the header's line for a
 * missing column, the cell for a bad value, the row's end for a short row).
 * Refused: a required column missing, time not strictly increasing, a row
 * short, long or unreadable, a value in a mapped column that is not a
 * finite number (nan, inf, text, empty) or is beyond 1e15 once scaled, a
 * time beyond 2^53 us, fewer than 2 rows, no overlap between the files.
 * Not refused but counted (sim_log_stats_t): gaps in time longer than
 * SIM_LOG_GAP_FACTOR times the file's median row period, interpolated over
 * when no longer than SIM_LOG_GAP_SKIP_FACTOR times it (a few dropped
 * frames) or when another file's rows go on through it (a topic that
 * pauses), else skipped: the ticks jump to the first tick at or after the
 * earliest row after the gap, which is marked (after_gap) for what spans it
 * to restart. Every tick given then lies between two rows of a file at most
 * SIM_LOG_GAP_SKIP_FACTOR of its row periods apart: the ticks given are
 * bounded by the rows read (times SIM_LOG_GAP_SKIP_FACTOR * row period /
 * dt_s + 1), never by the log's time span.
 */
#ifndef LADRC_SIM_LOG_H
#define LADRC_SIM_LOG_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define SIM_LOG_PATH_LEN 512
#define SIM_LOG_MAX_MAP 64 /* mapping items given by the caller */
#define SIM_LOG_MAX_MOTORS 8
#define SIM_LOG_GAP_FACTOR 5.0 /* a gap: a row period this many times the median */
/* A gap longer than this many median row periods is skipped, not interpolated:
 * a tenth of a second at 1 kHz. Beyond the dropouts of the committed real
 * logs (the longest: 66 periods, 0.164 s in a PX4 topic at 404 Hz; the
 * Betaflight ones have none), which are interpolated as they were; the
 * ticks between two rows stay within this times the row period over dt. */
#define SIM_LOG_GAP_SKIP_FACTOR 100.0

typedef enum {
    SIM_LOG_BETAFLIGHT = 0,
    SIM_LOG_PX4 = 1,
    SIM_LOG_GENERIC = 2,
    SIM_LOG_ARDUPILOT = 3,
    SIM_LOG_FORMAT_COUNT
} sim_log_format_t;

/* A form of one CSV per topic, each with its own time column (PX4, ArduPilot). */
static inline int sim_log_format_has_topics(sim_log_format_t f)
{
    return f == SIM_LOG_PX4 || f == SIM_LOG_ARDUPILOT;
}

/* Which fields of sim_log_sample_t hold values (the others are NaN). */
enum {
    SIM_LOG_HAS_GYRO = 1u << 0,
    SIM_LOG_HAS_GYRO_RAW = 1u << 1,
    SIM_LOG_HAS_ANGLE = 1u << 2,            /* angle and quat from the log's attitude */
    SIM_LOG_HAS_ANGLE_INTEGRATED = 1u << 3, /* angle: the integral of gyro (quat NaN) */
    SIM_LOG_HAS_REF_ANGLE = 1u << 4,        /* ref_angle and ref_quat from the log */
    SIM_LOG_HAS_REF_INTEGRATED = 1u << 5,   /* ref_angle: the integral of ref_rate */
    SIM_LOG_HAS_REF_RATE = 1u << 6,
    SIM_LOG_HAS_COMMAND = 1u << 7,
    SIM_LOG_HAS_THROTTLE = 1u << 8,
    SIM_LOG_HAS_MOTOR = 1u << 9,
    SIM_LOG_HAS_ROTOR_HZ = 1u << 10
};

typedef struct {
    double t_s;           /* from the first tick (0) */
    double gyro_rad_s[3]; /* roll, pitch, yaw body rates */
    double gyro_raw_rad_s[3];
    double angle_rad[3]; /* roll, pitch, yaw (ZYX) */
    double quat[4];      /* w x y z */
    double ref_angle_rad[3];
    double ref_quat[4];
    double ref_rate_rad_s[3];
    double command[3]; /* normalised per axis */
    double throttle;   /* 0..1 */
    double motor[SIM_LOG_MAX_MOTORS];
    double rotor_hz[SIM_LOG_MAX_MOTORS];
    int n_motors;  /* motor and rotor_hz entries mapped */
    int after_gap; /* 1: the first tick after a skipped gap (SIM_LOG_GAP_SKIP_FACTOR): restart what spans it */
} sim_log_sample_t;

typedef struct {
    sim_log_format_t format;
    char path[SIM_LOG_PATH_LEN];      /* BF / generic: the CSV; PX4, ArduPilot: BASE or one topic file */
    double dt_s;                      /* control period; 0: the median row period of the first file read */
    const char *map[SIM_LOG_MAX_MAP]; /* mapping items (above), replacing the preset's */
    int n_map;
    double t_from_s, t_to_s; /* window of the log to read, from its first tick; to <= 0: the end */
} sim_log_options_t;

typedef struct {
    char path[SIM_LOG_PATH_LEN];
    int line, column; /* 0 when the file could not be opened */
    char message[256];
} sim_log_error_t;

typedef struct {
    long long rows;  /* rows read over every file */
    long long ticks; /* samples given */
    long long gaps;  /* the files' gaps (SIM_LOG_GAP_FACTOR), the skipped ones among them */
    double longest_gap_s;
    long long skipped_gaps;      /* gaps skipped (SIM_LOG_GAP_SKIP_FACTOR): not interpolated, no ticks in them */
    double skipped_s;            /* their total length */
    long long skipped_file_gaps; /* the files' gaps among `gaps` they are (each is one in every file) */
    double row_period_s;         /* median row period of the first file */
    unsigned has;                /* SIM_LOG_HAS_* */
    int n_files;
} sim_log_stats_t;

typedef struct sim_log sim_log_t; /* the open reader (heap; host only) */

/* The options' defaults: format BETAFLIGHT, dt 0, no map, the whole log. */
void sim_log_options_default(sim_log_options_t *o);

/* "betaflight", "px4", "generic", "ardupilot" -> format; -1 for anything else. */
int sim_log_format_parse(const char *name);
const char *sim_log_format_name(sim_log_format_t f);

/* Opens the log and reads its header(s) and first rows. Returns the reader,
 * or NULL with *err set (nothing held). */
sim_log_t *sim_log_open(const sim_log_options_t *opt, sim_log_error_t *err);

/* The same from an open stream (a single-CSV form: BETAFLIGHT or GENERIC;
 * `name` is used in messages). The stream is the caller's: not closed. */
sim_log_t *sim_log_open_stream(FILE *stream, const char *name, const sim_log_options_t *opt, sim_log_error_t *err);

/* The next tick: 1 with *s filled, 0 at the end, -1 with *err set (a bad row:
 * the reader is then finished). */
int sim_log_next(sim_log_t *log, sim_log_sample_t *s, sim_log_error_t *err);

/* The control period the ticks are at (s), and the fields present (before the
 * first sim_log_next: those the mapping found). */
double sim_log_dt_s(const sim_log_t *log);
unsigned sim_log_has(const sim_log_t *log);

/* Bytes read so far and the files' total (0 when unknown: a stream). */
void sim_log_progress(const sim_log_t *log, long long *done, long long *total);

void sim_log_stats(const sim_log_t *log, sim_log_stats_t *st);

/* The warning for the skipped gaps of st ("N gap(s) ... skipped ..."):
 * 1 with it in buf, 0 (buf "") when none was skipped. */
int sim_log_gap_warning(const sim_log_stats_t *st, char *buf, size_t len);

void sim_log_close(sim_log_t *log);

/* "path:line:column: message" (or "path: message" when line is 0). */
void sim_log_error_format(const sim_log_error_t *err, char *buf, size_t len);

#endif
