/* SPDX-License-Identifier: BSD-3-Clause */
/* The identification's samples between its passes (ident_cache.h). */
#include "ident_cache.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define VALUES 9 /* gyro[3], command[3], setpoint[3] */

struct sim_ident_cache {
    FILE *f;
    double buf[SIM_IDENT_CACHE_TICKS * VALUES];
    int fill, at;          /* ticks in buf; the next one to read */
    long long total, done; /* ticks written; read since the rewind */
    int failed;
    int reading; /* after the first rewind: buf holds ticks read, not ticks to write */
};

sim_ident_cache_t *sim_ident_cache_new(void)
{
    sim_ident_cache_t *c = calloc(1, sizeof *c);
    if (c == NULL) {
        return NULL;
    }
    c->f = tmpfile();
    if (c->f == NULL) {
        free(c);
        return NULL;
    }
    return c;
}

void sim_ident_cache_free(sim_ident_cache_t *c)
{
    if (c != NULL) {
        fclose(c->f);
        free(c);
    }
}

static int flush(sim_ident_cache_t *c)
{
    if (c->fill > 0 && fwrite(c->buf, sizeof(double) * VALUES, (size_t)c->fill, c->f) != (size_t)c->fill) {
        c->failed = 1;
    }
    c->fill = 0;
    return c->failed ? -1 : 0;
}

int sim_ident_cache_put(sim_ident_cache_t *c, const double gyro_rad_s[3], const double command[3],
                        const double setpoint_rad_s[3])
{
    if (c->failed || c->reading) {
        return -1;
    }
    memcpy(&c->buf[c->fill * VALUES], gyro_rad_s, 3 * sizeof(double));
    memcpy(&c->buf[c->fill * VALUES + 3], command, 3 * sizeof(double));
    memcpy(&c->buf[c->fill * VALUES + 6], setpoint_rad_s, 3 * sizeof(double));
    c->total++;
    return ++c->fill == SIM_IDENT_CACHE_TICKS ? flush(c) : 0;
}

int sim_ident_cache_rewind(sim_ident_cache_t *c)
{
    if (!c->reading) {
        flush(c); /* the last writes */
        c->reading = 1;
    }
    if (c->failed || fflush(c->f) != 0 || fseek(c->f, 0L, SEEK_SET) != 0) {
        c->failed = 1;
        return -1;
    }
    c->fill = c->at = 0;
    c->done = 0;
    return 0;
}

int sim_ident_cache_get(sim_ident_cache_t *c, double gyro_rad_s[3], double command[3], double setpoint_rad_s[3])
{
    if (c->at == c->fill) {
        c->fill = (int)fread(c->buf, sizeof(double) * VALUES, SIM_IDENT_CACHE_TICKS, c->f);
        c->at = 0;
        if (c->fill == 0) {
            return ferror(c->f) ? -1 : 0;
        }
    }
    memcpy(gyro_rad_s, &c->buf[c->at * VALUES], 3 * sizeof(double));
    memcpy(command, &c->buf[c->at * VALUES + 3], 3 * sizeof(double));
    memcpy(setpoint_rad_s, &c->buf[c->at * VALUES + 6], 3 * sizeof(double));
    c->at++;
    c->done++;
    return 1;
}

void sim_ident_cache_progress(const sim_ident_cache_t *c, long long *done, long long *total)
{
    *done = c->done;
    *total = c->total;
}
