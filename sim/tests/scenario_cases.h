/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What the scenario tests (test_sim_scenario_*.c, test_sim_signals.c) share:
 * the scenario and error they parse into, the tolerance of a parsed value,
 * a parse that must succeed and a table of inputs that must fail. Included
 * once by each of those programs, after unity.h.
 */
#ifndef LADRC_SIM_TESTS_SCENARIO_CASES_H
#define LADRC_SIM_TESTS_SCENARIO_CASES_H

#include "scenario/scenario.h"
#include "scenario/setup.h"
#include "ladrc/types.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef SIM_SCENARIO_DIR
#error "SIM_SCENARIO_DIR must name the scenarios directory"
#endif

/* Values are parsed with strtod and converted with one multiplication (deg
 * -> rad) or a square root and a multiplication (variance -> std), so they
 * match the same double computation here to an ulp or two; 1e-12 relative
 * is far below any wrong unit or field. */
#define REL_TOL 1e-12

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* large: one scenario holds 8 signals of 8 compiled expressions */
static sim_scenario_t sc;
static sim_parse_error_t err;

void setUp(void)
{
    memset(&err, 0, sizeof err);
}
void tearDown(void)
{
}

static inline void assert_close(double expected, double actual, const char *what)
{
    char message[200];
    snprintf(message, sizeof message, "%s: expected %.17g, got %.17g", what, expected, actual);
    TEST_ASSERT_TRUE_MESSAGE(fabs(actual - expected) <= REL_TOL * (1.0 + fabs(expected)), message);
}

/* Parses text that must be valid. */
static inline void parse_ok(const char *text)
{
    const int rc = sim_scenario_parse(&sc, text, "dir/test.ini", &err);
    char message[800];
    snprintf(message, sizeof message, "%d:%d: %s", err.line, err.column, err.message);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, message);
}

typedef struct {
    const char *text;
    int line;
    int column;
    const char *message;
} bad_case_t;

static inline void check_bad_cases(const bad_case_t *cases, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        const bad_case_t *c = &cases[i];
        char what[400];
        snprintf(what, sizeof what, "case %u <<%s>>", (unsigned)i, c->text);
        memset(&err, 0, sizeof err);
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, sim_scenario_parse(&sc, c->text, "bad.ini", &err), what);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(c->message, err.message, what);
        TEST_ASSERT_EQUAL_INT_MESSAGE(c->line, err.line, what);
        TEST_ASSERT_EQUAL_INT_MESSAGE(c->column, err.column, what);
        TEST_ASSERT_EQUAL_STRING_MESSAGE("bad.ini", err.path, what);
    }
}

#define CHECK_BAD_CASES(cases) check_bad_cases((cases), sizeof(cases) / sizeof((cases)[0]))

#endif
