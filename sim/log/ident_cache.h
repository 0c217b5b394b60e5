/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The identification's samples between its passes: the first pass reads the
 * log (parsing the text, resampling) and writes each tick's gyro, command
 * and rate setpoint here, to an anonymous temporary file of doubles (72
 * bytes a tick: 259 MB for an hour at 1 kHz, on disk, not in memory); the later passes
 * read them back, bit for bit, at a fraction of the parse's cost. Memory:
 * one buffer of SIM_IDENT_CACHE_TICKS ticks.
 */
#ifndef LADRC_SIM_IDENT_CACHE_H
#define LADRC_SIM_IDENT_CACHE_H

#define SIM_IDENT_CACHE_TICKS 4096

typedef struct sim_ident_cache sim_ident_cache_t;

/* A new, empty cache (heap and a temporary file); NULL when either cannot be had. */
sim_ident_cache_t *sim_ident_cache_new(void);
void sim_ident_cache_free(sim_ident_cache_t *c);

/* One tick appended; 0, or -1 when the file cannot be written (the cache is then unusable). */
int sim_ident_cache_put(sim_ident_cache_t *c, const double gyro_rad_s[3], const double command[3],
                        const double setpoint_rad_s[3]);

/* From the first tick again (after the last put: the writes are flushed); 0 or -1. */
int sim_ident_cache_rewind(sim_ident_cache_t *c);

/* The next tick: 1, 0 at the end, -1 on a read error. */
int sim_ident_cache_get(sim_ident_cache_t *c, double gyro_rad_s[3], double command[3], double setpoint_rad_s[3]);

/* Ticks read since the rewind and ticks in all. */
void sim_ident_cache_progress(const sim_ident_cache_t *c, long long *done, long long *total);

#endif
