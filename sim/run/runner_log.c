/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A run as flight logs ([run] log; runner_parts.h, docs/csv-format.md): the
 * CSV Betaflight's blackbox_decode writes, the CSVs PX4's ulog2csv writes
 * (one per topic) and a generic CSV in SI units, one line per control tick
 * once the controller has acted. The normalised command is the achieved
 * torque over sim_setup_authority_Nm, the throttle the thrust asked over the
 * full thrust, a motor its w^2 command over a rotor's full w^2
 * (sim_setup_full_w2_rad2_s2).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plant/rotation.h"
#include "runner_parts.h"
#include "scenario/setup.h"

/* Each file's stdio buffer: up to ten files a run, a run's CSV has 1 MiB. */
#define LOG_BUFFER_BYTES (1 << 16)
/* A line: at most 35 fields of at most 26 characters (%.17g), and the room
 * sim_fmt_g asks for after the last. */
#define LINE_BYTES (35 * 28 + SIM_NUMFMT_MAX)
#define TWO_PI 6.283185307179586476925286766559
#define RAD_S_TO_RPM (60.0 / TWO_PI)
/* Betaflight: the DShot motor outputs 48..2047, and eRPM / 100 of 14-pole
 * motors (7 pole pairs: eRPM = 7 rpm). */
#define BF_MOTOR_MIN 48.0
#define BF_MOTOR_MAX 2047.0
#define BF_ERPM100_PER_RPM (7.0 / 100.0)
/* Integers written are within +-9e15, where a double holds every integer. */
#define INT_LIMIT 9e15

enum { FILE_BETAFLIGHT = 0, FILE_GENERIC = 1, FILE_PX4 = 2 };
enum {
    PX4_ANGULAR_VELOCITY = 0,
    PX4_SENSOR_COMBINED,
    PX4_ATTITUDE,
    PX4_ATTITUDE_SETPOINT,
    PX4_RATES_SETPOINT,
    PX4_TORQUE_SETPOINT,
    PX4_ACTUATOR_MOTORS,
    PX4_ESC_STATUS
};

static const char BETAFLIGHT_HEADER[] =
    "loopIteration, time (us), axisP[0], axisP[1], axisP[2], axisI[0], axisI[1], axisI[2], axisD[0], axisD[1], "
    "axisF[0], axisF[1], axisF[2], rcCommand[0], rcCommand[1], rcCommand[2], rcCommand[3], setpoint[0], "
    "setpoint[1], setpoint[2], setpoint[3], gyroADC[0], gyroADC[1], gyroADC[2], gyroUnfilt[0], gyroUnfilt[1], "
    "gyroUnfilt[2], motor[0], motor[1], motor[2], motor[3], eRPM[0], eRPM[1], eRPM[2], eRPM[3]\n";

static const char GENERIC_HEADER[] =
    "time,gyro[0],gyro[1],gyro[2],gyro_raw[0],gyro_raw[1],gyro_raw[2],angle[0],angle[1],angle[2],"
    "quat[0],quat[1],quat[2],quat[3],ref_angle[0],ref_angle[1],ref_angle[2],ref_rate[0],ref_rate[1],ref_rate[2],"
    "command[0],command[1],command[2],throttle\n";

static const char *const PX4_TOPIC[RUNNER_PX4_TOPICS] = {
    "vehicle_angular_velocity", "sensor_combined",         "vehicle_attitude", "vehicle_attitude_setpoint",
    "vehicle_rates_setpoint",   "vehicle_torque_setpoint", "actuator_motors",  "esc_status"};

static const char *const PX4_HEADER[RUNNER_PX4_TOPICS] = {
    "timestamp,timestamp_sample,xyz[0],xyz[1],xyz[2]\n",
    ("timestamp,gyro_rad[0],gyro_rad[1],gyro_rad[2],accelerometer_m_s2[0],accelerometer_m_s2[1],"
     "accelerometer_m_s2[2]\n"),
    "timestamp,q[0],q[1],q[2],q[3]\n",
    "timestamp,q_d[0],q_d[1],q_d[2],q_d[3],thrust_body[0],thrust_body[1],thrust_body[2]\n",
    "timestamp,roll,pitch,yaw,thrust_body[0],thrust_body[1],thrust_body[2]\n",
    "timestamp,xyz[0],xyz[1],xyz[2]\n",
    "timestamp,control[0],control[1],control[2],control[3]\n",
    "timestamp,esc[0].esc_rpm,esc[1].esc_rpm,esc[2].esc_rpm,esc[3].esc_rpm\n"};

/* The form a file belongs to. */
static int form_of(int file)
{
    return file == FILE_BETAFLIGHT ? SIM_RUN_LOG_BETAFLIGHT
           : file == FILE_GENERIC  ? SIM_RUN_LOG_GENERIC
                                   : SIM_RUN_LOG_PX4;
}

static const char *header_of(int file)
{
    return file == FILE_BETAFLIGHT ? BETAFLIGHT_HEADER
           : file == FILE_GENERIC  ? GENERIC_HEADER
                                   : PX4_HEADER[file - FILE_PX4];
}

int sim_run_log_name(const char *stem, int file, char *out, size_t len)
{
    int n;
    if (file == FILE_BETAFLIGHT) {
        n = snprintf(out, len, "%s_betaflight.csv", stem);
    } else if (file == FILE_GENERIC) {
        n = snprintf(out, len, "%s_log.csv", stem);
    } else if (file >= FILE_PX4 && file < RUNNER_LOG_FILES) {
        n = snprintf(out, len, "%s_px4_%s_0.csv", stem, PX4_TOPIC[file - FILE_PX4]);
    } else {
        return 0;
    }
    return (n >= 0 && (size_t)n < len) ? form_of(file) : 0;
}

/* The file's path: the stem and the form's suffix; 0, or -1 when too long. */
static int file_path(const flight_log_t *log, int file, char *out, size_t len)
{
    return sim_run_log_name(log->stem, file, out, len) != 0 ? 0 : -1;
}

static void close_all(flight_log_t *log)
{
    for (int f = 0; f < RUNNER_LOG_FILES; ++f) {
        if (log->file[f] != NULL) {
            fclose(log->file[f]);
            log->file[f] = NULL;
        }
    }
    log->forms = 0;
}

int runner_log_open(flight_log_t *log, const sim_scenario_t *sc, const char *csv_path, char *err, size_t err_len)
{
    memset(log, 0, sizeof *log);
    if (csv_path == NULL || sc->log_forms == 0) {
        return 0;
    }
    size_t stem_len = strlen(csv_path);
    if (stem_len >= 4 && strcmp(csv_path + stem_len - 4, ".csv") == 0) {
        stem_len -= 4;
    }
    if (stem_len >= sizeof log->stem) {
        snprintf(err, err_len, "%s: the path is too long for its flight logs", csv_path);
        return -1;
    }
    memcpy(log->stem, csv_path, stem_len);
    log->stem[stem_len] = '\0';
    for (int f = 0; f < RUNNER_LOG_FILES; ++f) {
        if ((sc->log_forms & form_of(f)) == 0) {
            continue;
        }
        char path[sizeof log->stem + 64];
        if (file_path(log, f, path, sizeof path) != 0) {
            snprintf(err, err_len, "%s: the path is too long for its flight logs", csv_path);
            close_all(log);
            return -1;
        }
        log->file[f] = runner_open_csv_buffered(path, header_of(f), LOG_BUFFER_BYTES, err, err_len);
        if (log->file[f] == NULL) {
            close_all(log);
            return -1;
        }
    }
    log->forms = sc->log_forms;
    for (int i = 0; i < 3; ++i) {
        log->authority_Nm[i] = sim_setup_authority_Nm(sc, i);
    }
    log->full_w2_rad2_s2 = sim_setup_full_w2_rad2_s2(sc);
    log->full_thrust_N = 4.0 * sc->thrust_coeff_N_s2 * log->full_w2_rad2_s2;
    return 0;
}

int runner_log_close(flight_log_t *log, char *err, size_t err_len)
{
    int rc = 0;
    for (int f = 0; f < RUNNER_LOG_FILES; ++f) {
        if (log->file[f] == NULL) {
            continue;
        }
        const int failed = ferror(log->file[f]) != 0;
        if ((fclose(log->file[f]) != 0 || failed) && rc == 0) {
            char path[sizeof log->stem + 64];
            (void)file_path(log, f, path, sizeof path);
            snprintf(err, err_len, "%s: write failed", path);
            rc = -1;
        }
        log->file[f] = NULL;
    }
    log->forms = 0;
    return rc;
}

/* ---- lines ------------------------------------------------------------------- */

/* One line in memory, its fields separated by sep. */
typedef struct {
    char text[LINE_BYTES];
    int len;
    int fields;
    const char *sep;
} line_t;

static void line_start(line_t *l, const char *sep)
{
    l->len = 0;
    l->fields = 0;
    l->sep = sep;
}

static void put_sep(line_t *l)
{
    if (l->fields++ > 0) {
        for (const char *s = l->sep; *s != '\0'; ++s) {
            l->text[l->len++] = *s;
        }
    }
}

/* x rounded to the nearest integer (halves away from 0), as a whole number;
 * 0 for NaN, +-INT_LIMIT beyond it. */
static void put_int(line_t *l, double x)
{
    put_sep(l);
    const double r = x != x ? 0.0 : round(x < -INT_LIMIT ? -INT_LIMIT : (x > INT_LIMIT ? INT_LIMIT : x));
    l->len += snprintf(l->text + l->len, sizeof l->text - (size_t)l->len, "%.0f", r == 0.0 ? 0.0 : r);
}

/* Digits that read back as the same ladrc_real_t: 9 for a float, 17 for a double. */
#ifdef LADRC_REAL_DOUBLE
#define REAL_DIGITS 17
#else
#define REAL_DIGITS 9
#endif

/* x with REAL_DIGITS: a value the controller got reads back as itself
 * (sim_fmt_g, the fast form, writes up to 15 digits). */
static void put_real(line_t *l, double x)
{
    put_sep(l);
    l->len += REAL_DIGITS <= 15 ? sim_fmt_g(l->text + l->len, x, REAL_DIGITS)
                                : snprintf(l->text + l->len, sizeof l->text - (size_t)l->len, "%.17g", x);
}

/* x as %.17g: a double's value that reads back as the same double. */
static void put_g17(line_t *l, double x)
{
    put_sep(l);
    l->len += snprintf(l->text + l->len, sizeof l->text - (size_t)l->len, "%.17g", x);
}

static void line_write(line_t *l, FILE *f)
{
    l->text[l->len++] = '\n';
    fwrite(l->text, 1, (size_t)l->len, f);
}

/* ---- one tick ------------------------------------------------------------------ */

/* What the forms write of a tick, in the simulator's units. */
typedef struct {
    double t_s, timestamp_us;
    double command[3]; /* achieved torque / authority */
    double ref_rate_rad_s[3];
    double throttle;     /* thrust asked / full thrust, 0..1 */
    double motor[4];     /* w^2 command / full w^2, 0..1 */
    double rotor_rpm[4]; /* from the plant's w^2 */
    double quat[4];      /* the attitude the controller got */
} values_t;

static double clamp01(double x)
{
    return x > 1.0 ? 1.0 : (x >= 0.0 ? x : 0.0); /* NaN: 0 */
}

static void betaflight_line(const flight_log_t *log, const tick_t *tk, const values_t *v, line_t *l)
{
    line_start(l, ", ");
    put_int(l, (double)log->ticks);
    put_int(l, v->timestamp_us);
    for (int i = 0; i < 3; ++i)
        put_int(l, 1000.0 * v->command[i]); /* axisP */
    for (int k = 0; k < 3 + 2 + 3; ++k)
        put_int(l, 0.0); /* axisI[0..2], axisD[0..1], axisF[0..2] */
    const double throttle_1000 = 1000.0 * v->throttle;
    for (int k = 0; k < 3; ++k)
        put_int(l, 0.0); /* rcCommand[0..2] */
    put_int(l, throttle_1000);
    for (int i = 0; i < 3; ++i)
        put_int(l, v->ref_rate_rad_s[i] * RAD2DEG); /* setpoint, deg/s */
    put_int(l, throttle_1000);
    for (int i = 0; i < 3; ++i)
        put_int(l, tk->ctrl_rate[i] * RAD2DEG); /* gyroADC, deg/s */
    for (int i = 0; i < 3; ++i)
        put_int(l, tk->meas_rate[i] * RAD2DEG); /* gyroUnfilt */
    for (int q = 0; q < 4; ++q)
        put_int(l, BF_MOTOR_MIN + (BF_MOTOR_MAX - BF_MOTOR_MIN) * v->motor[q]);
    for (int q = 0; q < 4; ++q)
        put_int(l, v->rotor_rpm[q] * BF_ERPM100_PER_RPM);
}

static void generic_line(const tick_t *tk, const values_t *v, line_t *l)
{
    line_start(l, ",");
    put_g17(l, v->t_s);
    for (int i = 0; i < 3; ++i)
        put_real(l, tk->ctrl_rate[i]);
    for (int i = 0; i < 3; ++i)
        put_g17(l, tk->meas_rate[i]);
    for (int i = 0; i < 3; ++i)
        put_real(l, tk->ctrl_angle[i]);
    for (int k = 0; k < 4; ++k)
        put_g17(l, v->quat[k]);
    for (int i = 0; i < 3; ++i)
        put_real(l, (double)tk->ref[i]);
    for (int i = 0; i < 3; ++i)
        put_g17(l, v->ref_rate_rad_s[i]);
    for (int i = 0; i < 3; ++i)
        put_g17(l, v->command[i]);
    put_g17(l, v->throttle);
}

/* Topic `topic`'s line of the tick. */
static void px4_line(int topic, const tick_t *tk, const values_t *v, line_t *l)
{
    line_start(l, ",");
    put_int(l, v->timestamp_us);
    double q_ref[4];
    switch (topic) {
    case PX4_ANGULAR_VELOCITY:
        put_int(l, v->timestamp_us); /* timestamp_sample */
        for (int i = 0; i < 3; ++i)
            put_real(l, tk->ctrl_rate[i]);
        break;
    case PX4_SENSOR_COMBINED:
        for (int i = 0; i < 3; ++i)
            put_real(l, tk->meas_rate[i]);
        for (int i = 0; i < 3; ++i)
            put_real(l, tk->accel_m_s2[i]);
        break;
    case PX4_ATTITUDE: /* 17 digits: the angles read back from it are the controller's floats */
        for (int k = 0; k < 4; ++k)
            put_g17(l, v->quat[k]);
        break;
    case PX4_ATTITUDE_SETPOINT:
        sim_quat_from_euler(tk->ref_rad, q_ref);
        for (int k = 0; k < 4; ++k)
            put_g17(l, q_ref[k]);
        put_real(l, 0.0);
        put_real(l, 0.0);
        put_real(l, -v->throttle); /* thrust_body: up is -z */
        break;
    case PX4_RATES_SETPOINT:
        for (int i = 0; i < 3; ++i)
            put_real(l, v->ref_rate_rad_s[i]);
        put_real(l, 0.0);
        put_real(l, 0.0);
        put_real(l, -v->throttle);
        break;
    case PX4_TORQUE_SETPOINT:
        for (int i = 0; i < 3; ++i)
            put_g17(l, v->command[i]);
        break;
    case PX4_ACTUATOR_MOTORS:
        for (int q = 0; q < 4; ++q)
            put_real(l, v->motor[q]);
        break;
    default: /* PX4_ESC_STATUS: esc_rpm is an integer */
        for (int q = 0; q < 4; ++q)
            put_int(l, v->rotor_rpm[q]);
        break;
    }
}

void runner_log_tick(flight_log_t *log, const sim_scenario_t *sc, const sim_plant_t *plant, const tick_t *tk,
                     const double w2_cmd[4])
{
    values_t v;
    v.t_s = tk->t;
    v.timestamp_us = round(tk->t * 1e6);
    for (int i = 0; i < 3; ++i) {
        v.command[i] = (double)tk->out.torque_Nm[i] / log->authority_Nm[i];
        v.ref_rate_rad_s[i] = log->ticks > 0 ? (tk->ref_rad[i] - log->last_ref_rad[i]) / sc->control_dt_s : 0.0;
        log->last_ref_rad[i] = tk->ref_rad[i];
    }
    v.throttle = clamp01((double)tk->thrust_N / log->full_thrust_N);
    for (int q = 0; q < 4; ++q) {
        v.motor[q] = clamp01(w2_cmd[q] / log->full_w2_rad2_s2);
        v.rotor_rpm[q] = sqrt(plant->w2_rad2_s2[q] > 0.0 ? plant->w2_rad2_s2[q] : 0.0) * RAD_S_TO_RPM;
    }
    if (sc->frame == LADRC_FRAME_QUATERNION) {
        memcpy(v.quat, tk->ctrl_quat, sizeof v.quat);
    } else {
        sim_quat_from_euler(tk->ctrl_angle, v.quat);
    }
    line_t l;
    if (log->file[FILE_BETAFLIGHT] != NULL) {
        betaflight_line(log, tk, &v, &l);
        line_write(&l, log->file[FILE_BETAFLIGHT]);
    }
    if (log->file[FILE_GENERIC] != NULL) {
        generic_line(tk, &v, &l);
        line_write(&l, log->file[FILE_GENERIC]);
    }
    for (int topic = 0; topic < RUNNER_PX4_TOPICS; ++topic) {
        if (log->file[FILE_PX4 + topic] != NULL) {
            px4_line(topic, tk, &v, &l);
            line_write(&l, log->file[FILE_PX4 + topic]);
        }
    }
    ++log->ticks;
}
