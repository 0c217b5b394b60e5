/* SPDX-License-Identifier: BSD-3-Clause */
/* A log's attitude setpoints as a recorded series (log_reference.h). */
#define _POSIX_C_SOURCE 200809L
#include "log_reference.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

int sim_log_reference_write(const sim_log_options_t *log, double max_s, const char *path, double *written_s, char *err,
                            size_t len)
{
    sim_log_error_t lerr;
    sim_log_t *reader = sim_log_open(log, &lerr);
    if (reader == NULL) {
        sim_log_error_format(&lerr, err, len);
        return -1;
    }
    if (!(sim_log_has(reader) & (SIM_LOG_HAS_REF_ANGLE | SIM_LOG_HAS_REF_INTEGRATED))) {
        snprintf(err, len,
                 "%s: the log has no setpoint: no ref_angle, ref_quat or ref_rate (map one with --map, "
                 "e.g. ref_rate[0]=COLUMN*deg)",
                 log->path);
        sim_log_close(reader);
        return -1;
    }
    char tmp[SIM_LOG_PATH_LEN + 64];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (f == NULL) {
        snprintf(err, len, "%s: cannot write: %s", tmp, strerror(errno));
        sim_log_close(reader);
        return -1;
    }
    fprintf(f, "# the setpoints of %s\nt [s], roll [rad], pitch [rad], yaw [rad]\n", log->path);
    sim_log_sample_t s;
    int rc;
    *written_s = 0.0;
    /* after a skipped gap (log.h) the series goes on a tick after its latest
     * row, from this time at this tick: a series to fly, without the gap */
    const double dt_s = sim_log_dt_s(reader);
    double base_s = 0.0;
    long long tick = 0, base_tick = 0;
    int rebased = 0;
    while ((rc = sim_log_next(reader, &s, &lerr)) == 1) {
        if (s.after_gap) {
            rebased = 1;
            base_s = *written_s + dt_s;
            base_tick = tick;
        }
        const double t_s = rebased ? base_s + (double)(tick - base_tick) * dt_s : s.t_s;
        if (max_s > 0.0 && t_s > max_s) {
            break;
        }
        fprintf(f, "%.6f,%.9g,%.9g,%.9g\n", t_s, s.ref_angle_rad[0], s.ref_angle_rad[1], s.ref_angle_rad[2]);
        *written_s = t_s;
        ++tick;
    }
    if (rc < 0) {
        sim_log_error_format(&lerr, err, len);
    }
    sim_log_close(reader);
    const int bad_write = (ferror(f) | fclose(f)) != 0;
    if (rc >= 0 && bad_write) {
        snprintf(err, len, "%s: write failed", tmp);
    }
    if (rc < 0 || bad_write || rename(tmp, path) != 0) {
        if (rc >= 0 && !bad_write) {
            snprintf(err, len, "%s: cannot rename to %s: %s", tmp, path, strerror(errno));
        }
        remove(tmp);
        return -1;
    }
    return 0;
}
