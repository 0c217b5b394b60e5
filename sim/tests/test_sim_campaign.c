/* SPDX-License-Identifier: BSD-3-Clause */
/* Campaign files: expansion (grid order, run count, samples), the
 * counter-based draws (a known answer, the same for a run in any shard, and
 * their distributions), the shortest round-trip value text, the plan and its
 * shards, the settings each run gets, and each malformed input with its
 * line, column and message. */
#define _POSIX_C_SOURCE 200809L
#include "unity.h"
#include "campaign/campaign.h"
#include "run/numfmt.h"
#include "scenario/scenario.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef SIM_SCENARIO_DIR
#error "SIM_SCENARIO_DIR must name the scenarios directory"
#endif

#define BASE "base = " SIM_SCENARIO_DIR "/paper.ini\n"

/* Sample size of the statistical checks, and their bound: 4 standard errors
 * of each statistic at this size. A correct generator fails a check with
 * probability about 6e-5; the draws are deterministic for the fixed seed,
 * so a check passes or fails on every run, while a wrong distribution (a
 * bound, a log, a missing factor) moves these statistics by many errors. */
#define N_DRAWS 20000
#define SIGMAS 4.0

static sim_campaign_t c;
static sim_campaign_error_t err;
static sim_campaign_run_t run;
static sim_scenario_t sc; /* large: kept off the stack */

void setUp(void)
{
    memset(&err, 0, sizeof err);
}
void tearDown(void)
{
    sim_campaign_free(&c);
}

static void parse_ok(const char *text)
{
    const int rc = sim_campaign_parse(&c, text, "dir/test.ini", &err);
    char message[800];
    snprintf(message, sizeof message, "%d:%d: %s", err.line, err.column, err.message);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, message);
}

static void expand_ok(long r)
{
    char msg[160] = "";
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_campaign_expand(&c, r, &run, msg, sizeof msg), msg);
}

static void test_grid_runs_in_row_major_order_first_key_slowest_with_samples_innermost(void)
{
    parse_ok("[campaign]\n" BASE "samples = 2\n"
             "[grid]\n"
             "a = 1, 2 3\n" /* commas, spaces or both */
             "rotors.motor_tau_s = range(0, 0.01, 2)\n"
             "[set]\n"
             "run.duration_s = {a}\n");
    TEST_ASSERT_EQUAL_INT(3 * 2 * 2, (int)c.n_runs);
    TEST_ASSERT_EQUAL_STRING("test", c.name);
    TEST_ASSERT_EQUAL_STRING("out/test", c.output_dir);
    static const double A[12] = {1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3};
    static const double TAU[12] = {0, 0, 0.01, 0.01, 0, 0, 0.01, 0.01, 0, 0, 0.01, 0.01};
    for (long r = 1; r <= 12; ++r) {
        expand_ok(r);
        TEST_ASSERT_TRUE(run.values[0] == A[r - 1]);
        TEST_ASSERT_TRUE(run.values[1] == TAU[r - 1]);
    }
    char msg[160];
    TEST_ASSERT_EQUAL_INT(-1, sim_campaign_expand(&c, 13, &run, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(-1, sim_campaign_expand(&c, 0, &run, msg, sizeof msg));
}

static void test_range_is_evenly_spaced_with_both_ends_exact(void)
{
    parse_ok("[campaign]\n" BASE "[grid]\nrotors.motor_tau_s = range(0, 0.04, 5)\n"
             "x = range(1, -1, 3)\n[set]\nrun.duration_s = {x}\n");
    static const char *const TEXT[5] = {"0", "0.01", "0.02", "0.03", "0.04"};
    for (long r = 1; r <= 5; ++r) {
        expand_ok(3 * r - 2);
        TEST_ASSERT_EQUAL_STRING(TEXT[r - 1], run.text[0]);
    }
    expand_ok(1);
    TEST_ASSERT_EQUAL_STRING("1", run.text[1]);
    expand_ok(2);
    TEST_ASSERT_EQUAL_STRING("0", run.text[1]);
    expand_ok(3);
    TEST_ASSERT_EQUAL_STRING("-1", run.text[1]);
}

/* The settings of a run: the derived run.seed, the [set] lines with the
 * variables substituted, then the varied scenario keys. */
static void test_a_run_gets_its_seed_then_the_set_lines_then_the_varied_keys(void)
{
    parse_ok("[campaign]\n" BASE "seed = 7\n"
             "[draw]\n"
             "sensors.angle_noise_std_deg = uniform(0, 0.1)\n"
             "w = log_uniform(0.5, 20)\n"
             "[grid]\n"
             "rotors.motor_tau_s = 0, 0.01\n"
             "[set]\n"
             "run.controllers = LADRC PID\n"
             "disturbance.roll = 2 .. 25 : 20*sin({w}*t) + {w}\n");
    /* [grid] keys first, then [draw] keys, whatever the sections' order */
    TEST_ASSERT_EQUAL_STRING("rotors.motor_tau_s", c.keys[0].name);
    TEST_ASSERT_EQUAL_STRING("sensors.angle_noise_std_deg", c.keys[1].name);
    TEST_ASSERT_EQUAL_STRING("w", c.keys[2].name);
    expand_ok(2);
    TEST_ASSERT_EQUAL_INT(5, run.n_settings);
    char want[256];
    snprintf(want, sizeof want, "run.seed=%llu", (unsigned long long)sim_campaign_stream(7, 2, 0, 1));
    TEST_ASSERT_EQUAL_STRING(want, run.settings[0]);
    TEST_ASSERT_EQUAL_INT(0, run.setting_line[0]);
    TEST_ASSERT_EQUAL_STRING("run.controllers=LADRC PID", run.settings[1]);
    TEST_ASSERT_EQUAL_INT(10, run.setting_line[1]);
    snprintf(want, sizeof want, "disturbance.roll=2 .. 25 : 20*sin(%s*t) + %s", run.text[2], run.text[2]);
    TEST_ASSERT_EQUAL_STRING(want, run.settings[2]);
    TEST_ASSERT_EQUAL_STRING("rotors.motor_tau_s=0.01", run.settings[3]);
    snprintf(want, sizeof want, "sensors.angle_noise_std_deg=%s", run.text[1]);
    TEST_ASSERT_EQUAL_STRING(want, run.settings[4]);
    TEST_ASSERT_EQUAL_INT(5, run.setting_line[4]);

    /* the scenario the run flies: the base with those settings, named and placed as the run */
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_campaign_load_run(&c, &run, "out/x", &sc, &perr), perr.message);
    TEST_ASSERT_EQUAL_STRING("00002", sc.name);
    TEST_ASSERT_EQUAL_STRING("out/x/runs/00002", sc.output_dir);
    TEST_ASSERT_TRUE(sc.seed == run.run_seed);
    TEST_ASSERT_TRUE(sc.motor_tau_s == 0.01);
    TEST_ASSERT_EQUAL_INT(2, sc.n_controllers);
    TEST_ASSERT_EQUAL_INT(1, sc.disturbance[0].n_pieces); /* the file's three pieces replaced */
    TEST_ASSERT_TRUE(fabs(sc.angle_noise_std_rad - run.values[1] * 3.14159265358979323846 / 180.0) <= 1e-15);
    const double t = 3.0;
    TEST_ASSERT_TRUE(sim_signal_eval(&sc.disturbance[0], t) == 20.0 * sin(run.values[2] * t) + run.values[2]);
}

static void test_a_campaign_that_sets_run_seed_gets_no_derived_seed(void)
{
    parse_ok("[campaign]\n" BASE "samples = 3\n[set]\nrun . seed = 5\n");
    expand_ok(2);
    TEST_ASSERT_EQUAL_INT(1, run.n_settings);
    TEST_ASSERT_EQUAL_STRING("run . seed=5", run.settings[0]);
    sim_campaign_free(&c);
    parse_ok("[campaign]\n" BASE "[grid]\nrun.seed = 11, 12\n");
    expand_ok(2);
    TEST_ASSERT_EQUAL_INT(1, run.n_settings);
    TEST_ASSERT_EQUAL_STRING("run.seed=12", run.settings[0]);
    sim_campaign_free(&c);
    /* no grid, no draw: repeated runs differ by their derived seeds alone */
    parse_ok("[campaign]\n" BASE "samples = 3\n");
    TEST_ASSERT_EQUAL_INT(3, (int)c.n_runs);
    TEST_ASSERT_EQUAL_INT(0, c.n_keys);
    expand_ok(1);
    const uint64_t s1 = run.run_seed;
    expand_ok(2);
    TEST_ASSERT_TRUE(s1 != run.run_seed);
}

/* The stream of (seed, r, k): its first output is mix(mix(mix(mix(seed) ^ r)
 * ^ k) + g), mix(x) the first SplitMix64 output from counter x and g its
 * increment. The value was computed independently of this code, from the
 * SplitMix64 definition (Steele, Lea and Flood, 2014). */
static void test_the_stream_of_seed_run_and_key_gives_the_documented_output(void)
{
    TEST_ASSERT_TRUE(sim_campaign_stream(7, 3, 0, 1) == UINT64_C(3827544751006511609));
    /* u = (top 53 bits + 1/2) 2^-53 */
    const uint64_t x = sim_campaign_stream(1, 5, 2, 2);
    TEST_ASSERT_TRUE(sim_campaign_uniform(1, 5, 2, 2) == ((double)(x >> 11) + 0.5) / 9007199254740992.0);
    /* the keys change the stream */
    TEST_ASSERT_TRUE(sim_campaign_stream(1, 5, 2, 1) != sim_campaign_stream(1, 5, 3, 1));
    TEST_ASSERT_TRUE(sim_campaign_stream(1, 5, 2, 1) != sim_campaign_stream(1, 6, 2, 1));
    TEST_ASSERT_TRUE(sim_campaign_stream(1, 5, 2, 1) != sim_campaign_stream(2, 5, 2, 1));
}

static const char STATS_CAMPAIGN[] = "[campaign]\n" BASE "seed = 3\nsamples = 20000\n"
                                     "[draw]\n"
                                     "u = uniform(2, 5)\n"
                                     "z = normal(1, 3)\n"
                                     "l = log_uniform(0.5, 20)\n"
                                     "[set]\n"
                                     "run.duration_s = {u}\n"
                                     "run.control_dt_s = {z} {l}\n";

static void test_draws_have_the_moments_of_their_distributions(void)
{
    parse_ok(STATS_CAMPAIGN);
    TEST_ASSERT_EQUAL_INT(N_DRAWS, (int)c.n_runs);
    double su = 0, su2 = 0, sz = 0, sz2 = 0, sl = 0, sl2 = 0, suz = 0, slag = 0, prev = 0;
    double umin = 1e9, umax = -1e9, lmin = 1e9, lmax = -1e9;
    for (long r = 1; r <= N_DRAWS; ++r) {
        const double u = sim_campaign_draw(&c, &c.keys[0], r);
        const double z = sim_campaign_draw(&c, &c.keys[1], r);
        const double l = sim_campaign_draw(&c, &c.keys[2], r);
        su += u;
        su2 += (u - 3.5) * (u - 3.5);
        sz += z;
        sz2 += (z - 1.0) * (z - 1.0);
        sl += log(l);
        sl2 += (log(l) - 0.5 * log(10.0)) * (log(l) - 0.5 * log(10.0));
        suz += (u - 3.5) * (z - 1.0);
        slag += (u - 3.5) * (prev - 3.5);
        prev = u;
        umin = fmin(umin, u);
        umax = fmax(umax, u);
        lmin = fmin(lmin, l);
        lmax = fmax(lmax, l);
    }
    const double n = N_DRAWS;
    /* uniform(2, 5): mean 3.5, variance 9/12 = 0.75; standard errors
     * sqrt(0.75/n) = 6.1e-3 and sqrt((81/80 - 0.75^2)/n) = 4.7e-3 */
    TEST_ASSERT_TRUE(fabs(su / n - 3.5) <= SIGMAS * sqrt(0.75 / n));
    TEST_ASSERT_TRUE(fabs(su2 / n - 0.75) <= SIGMAS * sqrt((81.0 / 80.0 - 0.5625) / n));
    TEST_ASSERT_TRUE(umin >= 2.0 && umax <= 5.0);
    /* both ends reached: the least of n uniforms exceeds A + 10 (B - A) / n
     * with probability (1 - 10/n)^n = e^-10 = 4.5e-5 (the greatest alike) */
    TEST_ASSERT_TRUE(umin < 2.0 + 3.0 * 10.0 / n && umax > 5.0 - 3.0 * 10.0 / n);
    /* normal(1, 3): standard error of the mean 3/sqrt(n) = 0.021, of the
     * variance 9 sqrt(2/n) = 0.090 */
    TEST_ASSERT_TRUE(fabs(sz / n - 1.0) <= SIGMAS * 3.0 / sqrt(n));
    TEST_ASSERT_TRUE(fabs(sz2 / n - 9.0) <= SIGMAS * 9.0 * sqrt(2.0 / n));
    /* log_uniform(0.5, 20): log l uniform over (ln 0.5, ln 20), mean ln(10)/2,
     * variance ln(40)^2/12 = 1.13; standard error of the log-mean 7.5e-3 */
    const double var_log = log(40.0) * log(40.0) / 12.0;
    TEST_ASSERT_TRUE(fabs(sl / n - 0.5 * log(10.0)) <= SIGMAS * sqrt(var_log / n));
    TEST_ASSERT_TRUE(fabs(sl2 / n - var_log) <= SIGMAS * sqrt((var_log * var_log * 1.8 - var_log * var_log) / n));
    TEST_ASSERT_TRUE(lmin >= 0.5 && lmax <= 20.0);
    /* keys of a run and consecutive runs uncorrelated: standard error of a
     * correlation of independent draws 1/sqrt(n) = 7.1e-3 */
    TEST_ASSERT_TRUE(fabs(suz / n / sqrt(0.75 * 9.0)) <= SIGMAS / sqrt(n));
    TEST_ASSERT_TRUE(fabs(slag / n / 0.75) <= SIGMAS / sqrt(n));
}

/* Run r's values are a function of (seed, r, key) alone: the same whatever
 * the order runs are expanded in, hence in any shard. */
static void test_a_runs_draws_do_not_depend_on_the_order_of_expansion(void)
{
    parse_ok(STATS_CAMPAIGN);
    char forward[3][SIM_CAMPAIGN_VALUE_LEN];
    expand_ok(17);
    memcpy(forward, run.text, sizeof forward);
    expand_ok(19999);
    expand_ok(3);
    expand_ok(17);
    for (int k = 0; k < 3; ++k) {
        TEST_ASSERT_EQUAL_STRING(forward[k], run.text[k]);
    }
}

static char *plan_of(long k, long n, size_t *len)
{
    FILE *f = tmpfile();
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_INT(0, sim_campaign_write_plan(f, &c, k, n));
    const long size = ftell(f);
    rewind(f);
    char *text = calloc((size_t)size + 1, 1);
    TEST_ASSERT_NOT_NULL(text);
    TEST_ASSERT_EQUAL_INT((int)size, (int)fread(text, 1, (size_t)size, f));
    fclose(f);
    *len = (size_t)size;
    return text;
}

/* The shards' plans: each row of the full plan in exactly one shard, with
 * the same text, in run order. */
static void test_shards_partition_the_runs_and_list_each_with_its_values(void)
{
    parse_ok("[campaign]\n" BASE "samples = 3\n[grid]\na = 1, 2\n[draw]\nsensors.angle_noise_std_deg = uniform(0, 5)\n"
             "[set]\nrun.duration_s = {a}\n");
    size_t len;
    char *full = plan_of(1, 1, &len);
    TEST_ASSERT_EQUAL_INT(0, strncmp(full, "run,a,sensors.angle_noise_std_deg\n", 26));
    for (long n = 1; n <= 8; ++n) {
        int hits[7] = {0}; /* shards that list run r */
        for (long k = 1; k <= n; ++k) {
            size_t l;
            char *plan = plan_of(k, n, &l);
            TEST_ASSERT_EQUAL_INT(0, strncmp(plan, "run,a,sensors.angle_noise_std_deg\n", 26));
            for (char *line = strchr(plan, '\n') + 1; *line != '\0'; line = strchr(line, '\n') + 1) {
                const long r = strtol(line, NULL, 10);
                TEST_ASSERT_TRUE(r >= 1 && r <= 6 && (r - 1) % n == k - 1);
                ++hits[r];
                *strchr(line, '\n') = '\0';
                char *in_full = strstr(full, line);
                TEST_ASSERT_NOT_NULL(in_full);
                TEST_ASSERT_TRUE(in_full[-1] == '\n' && in_full[strlen(line)] == '\n');
                *strchr(line, '\0') = '\n';
            }
            free(plan);
        }
        for (int r = 1; r <= 6; ++r) {
            TEST_ASSERT_EQUAL_INT(1, hits[r]);
        }
    }
    free(full);
}

static void test_values_are_the_shortest_text_that_reads_back(void)
{
    char buf[SIM_CAMPAIGN_VALUE_LEN];
    static const struct {
        double x;
        const char *text;
    } CASES[] = {{.x = 0.0, .text = "0"},
                 {.x = 0.1, .text = "0.1"},
                 {.x = 0.04, .text = "0.04"},
                 {.x = -2.5, .text = "-2.5"},
                 {.x = 100.0, .text = "100"},
                 {.x = 1e-5, .text = "1e-05"},
                 {.x = 1e21, .text = "1e+21"},
                 {.x = 1.0 / 3.0, .text = "0.3333333333333333"},
                 {.x = 0.1 + 0.2, .text = "0.30000000000000004"}};
    for (size_t i = 0; i < sizeof CASES / sizeof CASES[0]; ++i) {
        sim_campaign_format_value(buf, CASES[i].x);
        TEST_ASSERT_EQUAL_STRING(CASES[i].text, buf);
    }
    /* random doubles over many magnitudes: exact round trip, and the
     * shortest such text of printf */
    uint64_t state = 12345;
    for (int i = 0; i < 20000; ++i) {
        const double x =
            ldexp((double)(sim_campaign_stream(state, i, 1, 1) >> 11), (i % 200) - 100 - 53) * (i % 2 ? -1.0 : 1.0);
        const int len = sim_campaign_format_value(buf, x);
        TEST_ASSERT_TRUE(strtod(buf, NULL) == x);
        TEST_ASSERT_TRUE(len < SIM_CAMPAIGN_VALUE_LEN);
        /* no text of printf's %.Pg that reads back is shorter */
        for (int p = 1; p <= 17; ++p) {
            char other[SIM_NUMFMT_MAX];
            const int n = snprintf(other, sizeof other, "%.*g", p, x);
            TEST_ASSERT_TRUE(strtod(other, NULL) != x || n >= len);
        }
    }
}

static void test_shard_is_k_of_n(void)
{
    long k = 0, n = 0;
    char msg[160];
    TEST_ASSERT_EQUAL_INT(0, sim_campaign_parse_shard("3/4", &k, &n, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(3, (int)k);
    TEST_ASSERT_EQUAL_INT(4, (int)n);
    TEST_ASSERT_EQUAL_INT(0, sim_campaign_parse_shard("1/1", &k, &n, msg, sizeof msg));
    static const char *const BAD[] = {"0/4", "5/4", "a/b",   "1/0",  "2",    "",
                                      "/4",  "1/",  "1/2/3", "-1/4", "1/ 4", "99999999999999999999/1"};
    for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; ++i) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, sim_campaign_parse_shard(BAD[i], &k, &n, msg, sizeof msg), BAD[i]);
        TEST_ASSERT_TRUE(strlen(msg) > 0);
    }
}

/* A drawn or listed value the scenario refuses: the run's parse fails at
 * the setting, which names the campaign line it came from. */
static void test_a_run_the_scenario_refuses_fails_at_its_setting(void)
{
    parse_ok("[campaign]\n" BASE "[grid]\nrotors.motor_tau_s = 0.01, -1\n");
    sim_parse_error_t perr;
    expand_ok(1);
    TEST_ASSERT_EQUAL_INT(0, sim_campaign_load_run(&c, &run, "o", &sc, &perr));
    expand_ok(2);
    TEST_ASSERT_EQUAL_INT(-1, sim_campaign_load_run(&c, &run, "o", &sc, &perr));
    TEST_ASSERT_TRUE(perr.first_set_line > 0);
    const int k = perr.line - perr.first_set_line;
    TEST_ASSERT_TRUE(k >= 0 && k < run.n_settings);
    TEST_ASSERT_EQUAL_STRING("rotors.motor_tau_s=-1", run.settings[k]);
    TEST_ASSERT_EQUAL_INT(4, run.setting_line[k]);
    TEST_ASSERT_NOT_NULL(strstr(perr.message, "motor_tau_s must be >= 0"));
}

typedef struct {
    const char *text;
    int line, column;
    const char *message; /* a part of it */
} bad_case_t;

static void test_malformed_campaigns_are_refused_at_line_and_column(void)
{
    static const bad_case_t CASES[] = {
        {.text = "[campaign]\n" BASE "[grids]\n", .line = 3, .column = 2, .message = "unknown section [grids]"},
        {.text = "[campaign]\n" BASE "bass = 1\n",
         .line = 3,
         .column = 1,
         .message = "unknown key 'bass' in [campaign]"},
        {.text = "[campaign]\n" BASE "seed = 1\nseed = 2\n",
         .line = 4,
         .column = 1,
         .message = "duplicate key 'seed' (first given on line 3)"},
        {.text = "[campaign]\n" BASE "seed = -1\n", .line = 3, .column = 8, .message = "seed: expected a whole number"},
        {.text = "[campaign]\n" BASE "seed = 18446744073709551616\n",
         .line = 3,
         .column = 8,
         .message = "seed out of range"},
        {.text = "[campaign]\n" BASE "samples = 0\n", .line = 3, .column = 11, .message = "samples must be at least 1"},
        {.text = "[campaign]\n" BASE "name = a b\n", .line = 3, .column = 9, .message = "a campaign's name is made of"},
        {.text = "[campaign]\nseed = 3\n", .line = 1, .column = 1, .message = "missing base = SCENARIO in [campaign]"},
        {.text = "[grid]\na = 1\n[set]\nrun.duration_s = {a}\n", .line = 0, .column = 0, .message = "missing base"},
        {.text = "[campaign]\nbase = no/such/file.ini\n",
         .line = 2,
         .column = 8,
         .message = "cannot read the base scenario 'dir/no/such/file.ini'"},
        {.text = "seed = 1\n", .line = 1, .column = 1, .message = "key 'seed' before any [section]"},
        {.text = "[campaign]\n" BASE "[campaign]\n",
         .line = 3,
         .column = 1,
         .message = "section [campaign] already given on line 1"},
        {.text = "[campaign]\n" BASE "seed\n", .line = 3, .column = 5, .message = "expected KEY = VALUE"},
        {.text = "[campaign]\n" BASE "seed =\n", .line = 3, .column = 7, .message = "missing value for 'seed'"},
        {.text = "[campaign]\n" BASE "[draw]\nx = gauss(0, 1)\n[set]\na.b = {x}\n",
         .line = 4,
         .column = 5,
         .message = "unknown distribution 'gauss'"},
        {.text = "[campaign]\n" BASE "[draw]\nx = 3\n",
         .line = 4,
         .column = 5,
         .message = "expected a distribution, got '3'"},
        {.text = "[campaign]\n" BASE "[draw]\nx = log_uniform(0, 1)\n",
         .line = 4,
         .column = 5,
         .message = "log_uniform(A, B) needs 0 < A < B"},
        {.text = "[campaign]\n" BASE "[draw]\nx = uniform(2, 1)\n",
         .line = 4,
         .column = 5,
         .message = "uniform(A, B) needs A < B"},
        {.text = "[campaign]\n" BASE "[draw]\nx = normal(0, 0)\n",
         .line = 4,
         .column = 15,
         .message = "normal(MEAN, STD) needs STD > 0"},
        {.text = "[campaign]\n" BASE "[draw]\nx = uniform(0, 1, 2)\n",
         .line = 4,
         .column = 5,
         .message = "uniform takes 2 numbers"},
        {.text = "[campaign]\n" BASE "[draw]\nx = uniform(0, one)\n",
         .line = 4,
         .column = 16,
         .message = "expected a number, got 'one'"},
        {.text = "[campaign]\n" BASE "[draw]\nx = uniform(0, 1\n", .line = 4, .column = 17, .message = "expected ')'"},
        {.text = "[campaign]\n" BASE "[draw]\nx = uniform(0, 1) 2\n",
         .line = 4,
         .column = 19,
         .message = "trailing characters after ')'"},
        {.text = "[campaign]\n" BASE "[grid]\nx = range(0, 1, 1)\n",
         .line = 4,
         .column = 17,
         .message = "range COUNT must be a whole number from 2"},
        {.text = "[campaign]\n" BASE "[grid]\nx = range(0, 1, 2.5)\n",
         .line = 4,
         .column = 17,
         .message = "range COUNT must be a whole number"},
        {.text = "[campaign]\n" BASE "[grid]\nx = range(1, 1, 3)\n",
         .line = 4,
         .column = 14,
         .message = "range FROM and TO must differ"},
        {.text = "[campaign]\n" BASE "[grid]\nx = steps(0, 1, 3)\n",
         .line = 4,
         .column = 5,
         .message = "unknown function 'steps'"},
        {.text = "[campaign]\n" BASE "[grid]\nx = 1,, 2\n",
         .line = 4,
         .column = 7,
         .message = "empty value before ','"},
        {.text = "[campaign]\n" BASE "[grid]\nx = 1, 2,\n",
         .line = 4,
         .column = 10,
         .message = "empty value after ','"},
        {.text = "[campaign]\n" BASE "[grid]\nx = 1, two\n",
         .line = 4,
         .column = 8,
         .message = "expected a number, got 'two'"},
        {.text = "[campaign]\n" BASE "[grid]\n2x = 1\n",
         .line = 4,
         .column = 1,
         .message = "a variable's name is a letter or '_'"},
        {.text = "[campaign]\n" BASE "[grid]\na b = 1\n",
         .line = 4,
         .column = 2,
         .message = "unexpected ' ' in a name"},
        {.text = "[campaign]\n" BASE "[grid]\nx = 1\n[draw]\nx = uniform(0, 1)\n",
         .line = 6,
         .column = 1,
         .message = "'x' already varied on line 4"},
        {.text = "[campaign]\n" BASE "[grid]\nx = 1\n",
         .line = 4,
         .column = 1,
         .message = "variable 'x' is not used in [set]"},
        {.text = "[campaign]\n" BASE "[set]\nrun.duration_s = {y}\n",
         .line = 4,
         .column = 18,
         .message = "unknown variable '{y}'"},
        {.text = "[campaign]\n" BASE "[set]\nrun.duration_s = {y\n",
         .line = 4,
         .column = 18,
         .message = "'{' without '}'"},
        {.text = "[campaign]\n" BASE "[set]\nrun.duration_s = y}\n",
         .line = 4,
         .column = 19,
         .message = "'}' without '{'"},
        {.text = "[campaign]\n" BASE "[set]\nduration_s = 3\n",
         .line = 4,
         .column = 1,
         .message = "expected SECTION.KEY = VALUE"},
        {.text = "[campaign]\n" BASE "[grid]\nrun.duration_s = 1, 2\n[set]\n run.duration_s = 3\n",
         .line = 6,
         .column = 2,
         .message = "'run.duration_s' is varied in [grid] (line 4)"},
        {.text = "[campaign]\n" BASE "samples = 10000\n[grid]\nx = range(0, 1, 1001)\n[set]\na.b = {x}\n",
         .line = 0,
         .column = 0,
         .message = "10010000 runs: at most 10000000"},
    };
    for (size_t i = 0; i < sizeof CASES / sizeof CASES[0]; ++i) {
        const bad_case_t *bc = &CASES[i];
        char message[1200];
        const int rc = sim_campaign_parse(&c, bc->text, "dir/test.ini", &err);
        snprintf(message, sizeof message, "case %u: expected %d:%d: %s; got rc %d, %d:%d: %s", (unsigned)i, bc->line,
                 bc->column, bc->message, rc, err.line, err.column, err.message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, rc, message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(bc->line, err.line, message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(bc->column, err.column, message);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, bc->message), message);
        TEST_ASSERT_EQUAL_STRING("dir/test.ini", err.path);
        TEST_ASSERT_NULL(c.text); /* nothing left to free */
    }
}

/* The shipped campaigns: every run parses. */
static void test_the_shipped_campaigns_expand_and_every_run_parses(void)
{
    static const struct {
        const char *file;
        long runs;
    } SHIPPED[] = {{.file = SIM_CAMPAIGN_DIR "/robustness.ini", .runs = 1000},
                   {.file = SIM_CAMPAIGN_DIR "/smoke.ini", .runs = 12}};
    for (size_t i = 0; i < sizeof SHIPPED / sizeof SHIPPED[0]; ++i) {
        const int rc = sim_campaign_load(&c, SHIPPED[i].file, &err);
        char message[1400];
        snprintf(message, sizeof message, "%s:%d:%d: %s", err.path, err.line, err.column, err.message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, message);
        TEST_ASSERT_EQUAL_INT(SHIPPED[i].runs, (int)c.n_runs);
        for (long r = 1; r <= c.n_runs; ++r) {
            expand_ok(r);
            sim_parse_error_t perr;
            const int ok = sim_campaign_load_run(&c, &run, "out", &sc, &perr);
            snprintf(message, sizeof message, "%s run %ld: %s:%d:%d: %s", SHIPPED[i].file, r, perr.path, perr.line,
                     perr.column, perr.message);
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, ok, message);
        }
        sim_campaign_free(&c);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_grid_runs_in_row_major_order_first_key_slowest_with_samples_innermost);
    RUN_TEST(test_range_is_evenly_spaced_with_both_ends_exact);
    RUN_TEST(test_a_run_gets_its_seed_then_the_set_lines_then_the_varied_keys);
    RUN_TEST(test_a_campaign_that_sets_run_seed_gets_no_derived_seed);
    RUN_TEST(test_the_stream_of_seed_run_and_key_gives_the_documented_output);
    RUN_TEST(test_draws_have_the_moments_of_their_distributions);
    RUN_TEST(test_a_runs_draws_do_not_depend_on_the_order_of_expansion);
    RUN_TEST(test_shards_partition_the_runs_and_list_each_with_its_values);
    RUN_TEST(test_values_are_the_shortest_text_that_reads_back);
    RUN_TEST(test_shard_is_k_of_n);
    RUN_TEST(test_a_run_the_scenario_refuses_fails_at_its_setting);
    RUN_TEST(test_malformed_campaigns_are_refused_at_line_and_column);
    RUN_TEST(test_the_shipped_campaigns_expand_and_every_run_parses);
    return UNITY_END();
}
