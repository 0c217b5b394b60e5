/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Campaign files (docs/campaign-format.md): a base scenario and the keys to
 * vary over its runs, on a grid ([grid]: lists and ranges) and at random
 * ([draw]: uniform, normal, log-uniform), with lines applied to every run
 * ([set]) in which the run's values of named variables are substituted.
 *
 * Runs are numbered 1..R, R = (product of the grid sizes) x samples; run r
 * is grid point (r - 1) / samples in row-major order (first [grid] key
 * slowest), sample (r - 1) % samples. Draws are counter-based: run r's value
 * of the k-th [draw] key comes from a SplitMix64 stream keyed by (seed, r, k)
 * alone, so a run is the same scenario in any order, shard or machine.
 */
#ifndef LADRC_SIM_CAMPAIGN_H
#define LADRC_SIM_CAMPAIGN_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "scenario/scenario.h"

#define SIM_CAMPAIGN_MAX_VARIED 16      /* [grid] and [draw] keys together */
#define SIM_CAMPAIGN_MAX_SETS 48        /* [set] lines */
#define SIM_CAMPAIGN_MAX_VALUES 100000  /* values of one [grid] key */
#define SIM_CAMPAIGN_MAX_RUNS 10000000L /* runs of a campaign */
#define SIM_CAMPAIGN_KEY_LEN 96         /* a varied name, NUL included */
#define SIM_CAMPAIGN_VALUE_LEN 32       /* the text of a value, NUL included */
#define SIM_CAMPAIGN_RUN_TEXT 16384     /* a run's settings, all together */

typedef enum { SIM_DRAW_UNIFORM = 0, SIM_DRAW_NORMAL, SIM_DRAW_LOG_UNIFORM } sim_draw_kind_t;

/* A varied name: a variable ({name} in [set]) or a scenario key SECTION.KEY. */
typedef struct {
    char name[SIM_CAMPAIGN_KEY_LEN];
    int is_variable;  /* no '.' in the name */
    int is_draw;      /* 0: [grid] */
    int line, column; /* of the name in the campaign file */
    double *values;   /* [grid]: n_values values, owned */
    long n_values;
    sim_draw_kind_t dist; /* [draw] */
    double a, b;          /* uniform, log_uniform: bounds; normal: mean, std */
    int draw_index;       /* [draw]: k, its position there from 1 */
} sim_campaign_key_t;

/* A [set] line KEY = VALUE, as the setting "KEY=VALUE". */
typedef struct {
    const char *key; /* into the campaign's text */
    const char *value;
    int line, value_column;
} sim_campaign_set_t;

typedef struct {
    char path[SIM_PATH_LEN]; /* the campaign file */
    char name[SIM_NAME_LEN];
    char base_path[SIM_PATH_LEN]; /* the base scenario, relative to the current directory */
    uint64_t seed;
    long samples;
    char output_dir[SIM_PATH_LEN];
    int n_keys; /* [grid] keys, then [draw] keys, each in file order */
    int n_grid;
    sim_campaign_key_t keys[SIM_CAMPAIGN_MAX_VARIED];
    int n_sets;
    sim_campaign_set_t sets[SIM_CAMPAIGN_MAX_SETS];
    int sets_seed; /* run.seed is in [set] or varied: no derived seed */
    long n_runs;
    char *text;      /* the file, cut up; owned */
    char *base_text; /* the base scenario's bytes; owned */
    size_t base_len;
} sim_campaign_t;

/* Where a campaign file is wrong: path:line:column: message (line 0: the
 * file as a whole). */
typedef sim_parse_error_t sim_campaign_error_t;

/* Reads a campaign file and its base scenario's bytes. Returns 0, or -1 with
 * *err set (c then holds nothing to free). */
int sim_campaign_load(sim_campaign_t *c, const char *path, sim_campaign_error_t *err);

/* The same from text in memory (path for messages and for the base). */
int sim_campaign_parse(sim_campaign_t *c, const char *text, const char *path, sim_campaign_error_t *err);

void sim_campaign_free(sim_campaign_t *c);

/* One run, expanded: its varied values and its settings for
 * sim_scenario_parse_buffer_with. */
typedef struct {
    long run;
    double values[SIM_CAMPAIGN_MAX_VARIED];                     /* in key order */
    char text[SIM_CAMPAIGN_MAX_VARIED][SIM_CAMPAIGN_VALUE_LEN]; /* shortest round-trip text */
    const char *settings[SIM_CAMPAIGN_MAX_SETS + SIM_CAMPAIGN_MAX_VARIED + 1];
    int setting_line[SIM_CAMPAIGN_MAX_SETS + SIM_CAMPAIGN_MAX_VARIED + 1]; /* campaign line; 0: run.seed */
    int n_settings;
    uint64_t run_seed; /* the derived run.seed (applied unless sets_seed) */
    char buf[SIM_CAMPAIGN_RUN_TEXT];
} sim_campaign_run_t;

/* Expands run r (1..n_runs): the derived run.seed first (unless the
 * campaign sets run.seed), then the [set] lines with {name} replaced, then
 * KEY=VALUE of each varied scenario key. Returns 0, or -1 with a message in
 * msg when the settings do not fit. */
int sim_campaign_expand(const sim_campaign_t *c, long r, sim_campaign_run_t *out, char *msg, size_t msg_len);

/* Loads run r's scenario (expanded in *run): the base scenario with its
 * settings, named and placed as the run (name = r zero-padded to at least
 * 5 digits, output_dir = out_dir/runs/<name>). Returns 0, or -1 with the
 * scenario's error in *err. */
int sim_campaign_load_run(const sim_campaign_t *c, const sim_campaign_run_t *run, const char *out_dir,
                          sim_scenario_t *sc, sim_parse_error_t *err);

/* "00017": r zero-padded to at least 5 digits. */
void sim_campaign_run_name(char *buf, size_t n, long r);

/* The plan: header run,<name>... then one row per run r with
 * (r - 1) % shard_n == shard_k - 1 (shard 1/1: every run). Returns 0, or -1
 * on a write error or when a run does not expand. */
int sim_campaign_write_plan(FILE *f, const sim_campaign_t *c, long shard_k, long shard_n);

/* Counter-based draws: the i-th 64-bit output (i from 1) of the stream
 * keyed by (seed, r, k), and the i-th uniform in (0, 1) of it. k = 0 is
 * the stream of the run's derived run.seed (its first output). */
uint64_t sim_campaign_stream(uint64_t seed, long r, int k, int i);
double sim_campaign_uniform(uint64_t seed, long r, int k, int i);

/* Run r's value of the draw key (its draw_index k). */
double sim_campaign_draw(const sim_campaign_t *c, const sim_campaign_key_t *key, long r);

/* x (finite) as the shortest decimal text that reads back to x with
 * strtod: the shortest of printf's "%.Pg", P = 1..17, that does ("100", not
 * "1e+02"; "0.1"; "1e-05"). buf holds SIM_CAMPAIGN_VALUE_LEN chars.
 * Returns its length. */
int sim_campaign_format_value(char *buf, double x);

/* Parses "K/N" (1 <= K <= N, N <= SIM_CAMPAIGN_MAX_RUNS). Returns 0, or -1
 * with a message in msg. */
int sim_campaign_parse_shard(const char *text, long *k, long *n, char *msg, size_t msg_len);

#endif
