/* SPDX-License-Identifier: BSD-3-Clause */
/* Recorded series (scenario/series.h): the file's header, rows and units,
 * the evaluation between the rows and past the last one, the cursor, the
 * same bits on every load, and every error at its documented line and
 * column with nothing left allocated. */
#define _POSIX_C_SOURCE 200809L /* mkstemp */
#include "unity.h"
#include "scenario/series.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846
/* deg -> rad: the product v * (pi/180) rounds once, the constant once. */
#define SI_REL_TOL 4e-16
/* Linear interpolation of values of order 10: a few roundings of a + (b - a) f. */
#define INTERP_TOL 1e-12
/* Just below a seam the linear value is within one step's slope times an ulp
 * of t (about 1e-15 s, slopes of order 10 /s) of the last row's. */
#define SEAM_TOL 1e-12

static char path[64]; /* the test's temporary file, removed after it */

void setUp(void)
{
    path[0] = '\0';
}
void tearDown(void)
{
    if (path[0] != '\0') {
        remove(path);
    }
}

static sim_series_spec_t spec_of(sim_dim_t dim, sim_series_interp_t interp, sim_series_end_t end)
{
    sim_series_spec_t spec;
    spec.dim = dim;
    spec.key = NULL;
    spec.interp = interp;
    spec.end = end;
    return spec;
}

/* An angular acceleration, linear, hold at the end: what most tests read. */
static sim_series_spec_t accel_spec(void)
{
    return spec_of(SIM_DIM_ANG_ACCEL, SIM_SERIES_LINEAR, SIM_SERIES_HOLD_END);
}

static int near_rel(double a, double b, double rel)
{
    return fabs(a - b) <= rel * fabs(b);
}

static int near(double a, double b, double tol)
{
    return fabs(a - b) <= tol;
}

static int same_bits(const double *a, const double *b, size_t n)
{
    return memcmp(a, b, n * sizeof *a) == 0;
}

static void parse_ok(sim_series_t *s, const char *text, size_t len, const sim_series_spec_t *spec)
{
    sim_series_error_t err;
    const int rc = sim_series_parse(s, text, len, "test.csv", spec, &err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, err.message);
}

static void parse_text(sim_series_t *s, const char *text, const sim_series_spec_t *spec)
{
    parse_ok(s, text, strlen(text), spec);
}

static void assert_empty(const sim_series_t *s)
{
    TEST_ASSERT_EQUAL_UINT(0, s->n_rows);
    TEST_ASSERT_EQUAL_INT(0, s->n_cols);
    TEST_ASSERT_NULL(s->t_s);
    TEST_ASSERT_NULL(s->value);
    TEST_ASSERT_EQUAL_INT(0, s->name[0][0]);
    TEST_ASSERT_EQUAL_INT(0, s->name[1][0]);
}

/* 1-based column of needle's first occurrence in line. */
static int column_of(const char *line, const char *needle)
{
    const char *at = strstr(line, needle);
    TEST_ASSERT_NOT_NULL_MESSAGE(at, needle);
    return (int)(at - line) + 1;
}

/* Parsing len bytes fails at line:column with a message holding the words
 * (NULL: none), and leaves the series empty. */
static void expect_error_len(const char *text, size_t len, const sim_series_spec_t *spec, int line, int column,
                             const char *word1, const char *word2)
{
    sim_series_t s;
    sim_series_error_t err;
    memset(&s, 0x5a, sizeof s); /* whatever was there before */
    const int rc = sim_series_parse(&s, text, len, "bad.csv", spec, &err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(-1, rc, text);
    TEST_ASSERT_EQUAL_STRING("bad.csv", err.path);
    TEST_ASSERT_EQUAL_INT_MESSAGE(line, err.line, err.message);
    TEST_ASSERT_EQUAL_INT_MESSAGE(column, err.column, err.message);
    TEST_ASSERT_TRUE_MESSAGE(err.message[0] != '\0', text);
    if (word1 != NULL) {
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, word1), err.message);
    }
    if (word2 != NULL) {
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, word2), err.message);
    }
    assert_empty(&s);
    sim_series_free(&s); /* an emptied series may be freed */
}

static void expect_error_spec(const char *text, const sim_series_spec_t *spec, int line, int column, const char *word1,
                              const char *word2)
{
    expect_error_len(text, strlen(text), spec, line, column, word1, word2);
}

static void expect_error(const char *text, int line, int column, const char *word1, const char *word2)
{
    const sim_series_spec_t spec = accel_spec();
    expect_error_len(text, strlen(text), &spec, line, column, word1, word2);
}

/* ---- a well-formed file ------------------------------------------------ */

static void test_well_formed_file_parses_names_rows_and_si_values(void)
{
    /* BOM, comments and blank lines before, between and after the rows,
     * CRLF, blanks and tabs around the values and the units */
    static const char text[] = "\xEF\xBB\xBF# gust measured on a bench, 1 kHz\r\n"
                               "\r\n"
                               "  # indented comment\r\n"
                               "time [ ms ] ,\troll [deg/s^2], pitch[rad/s^2] , yaw_2.b-c [deg/s^2]  \r\n"
                               "0, 90, -1.5, 180\r\n"
                               "\r\n"
                               "# between the rows\r\n"
                               "  500 ,\t-45 ,2.25,0   \r\n"
                               "1500,0,0,-360\r\n"
                               "# at the end\r\n"
                               "\r\n";
    const sim_series_spec_t spec = spec_of(SIM_DIM_ANG_ACCEL, SIM_SERIES_HOLD, SIM_SERIES_REPEAT);
    sim_series_t s;
    parse_ok(&s, text, sizeof text - 1, &spec);
    TEST_ASSERT_EQUAL_UINT(3, s.n_rows);
    TEST_ASSERT_EQUAL_INT(3, s.n_cols);
    TEST_ASSERT_EQUAL_STRING("time", s.name[0]);
    TEST_ASSERT_EQUAL_STRING("roll", s.name[1]);
    TEST_ASSERT_EQUAL_STRING("pitch", s.name[2]);
    TEST_ASSERT_EQUAL_STRING("yaw_2.b-c", s.name[3]);
    TEST_ASSERT_EQUAL_INT(SIM_DIM_ANG_ACCEL, s.dim);
    TEST_ASSERT_EQUAL_INT(SIM_SERIES_HOLD, s.interp);
    TEST_ASSERT_EQUAL_INT(SIM_SERIES_REPEAT, s.end);
    /* ms times 0.001 */
    TEST_ASSERT_TRUE(s.t_s[0] == 0.0);
    TEST_ASSERT_TRUE(s.t_s[1] == 500 * 0.001);
    TEST_ASSERT_TRUE(s.t_s[2] == 1500 * 0.001);
    TEST_ASSERT_TRUE(s.period_s == s.t_s[2] - s.t_s[0]);
    /* deg times pi/180, rad as written; columns may mix them */
    const double expected[3][3] = {{90, -1.5, 180}, {-45, 2.25, 0}, {0, 0, -360}};
    const double factor[3] = {PI / 180.0, 1.0, PI / 180.0};
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) {
            const double want = expected[i][k] * factor[k];
            TEST_ASSERT_TRUE(near_rel(s.value[i * 3 + k], want, SI_REL_TOL));
        }
    }
    TEST_ASSERT_TRUE(near_rel(s.value[0], PI / 2.0, SI_REL_TOL));
    sim_series_free(&s);
    assert_empty(&s);
    sim_series_free(&s); /* twice is fine */
}

static void test_every_unit_of_the_table_and_its_dimension(void)
{
    static const struct {
        const char *unit;
        sim_dim_t dim;
        double to_si;
    } table[] = {
        {"s", SIM_DIM_TIME, 1.0},
        {"ms", SIM_DIM_TIME, 0.001},
        {"rad", SIM_DIM_ANGLE, 1.0},
        {"deg", SIM_DIM_ANGLE, PI / 180.0},
        {"rad/s", SIM_DIM_ANG_RATE, 1.0},
        {"deg/s", SIM_DIM_ANG_RATE, PI / 180.0},
        {"rad/s^2", SIM_DIM_ANG_ACCEL, 1.0},
        {"deg/s^2", SIM_DIM_ANG_ACCEL, PI / 180.0},
        {"m/s", SIM_DIM_VELOCITY, 1.0},
        {"m/s^2", SIM_DIM_LIN_ACCEL, 1.0},
    };
    for (size_t i = 0; i < sizeof table / sizeof table[0]; ++i) {
        sim_dim_t dim = SIM_DIM_COUNT;
        double to_si = 0.0;
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_series_unit(table[i].unit, strlen(table[i].unit), &dim, &to_si),
                                      table[i].unit);
        TEST_ASSERT_EQUAL_INT_MESSAGE(table[i].dim, dim, table[i].unit);
        TEST_ASSERT_TRUE_MESSAGE(near_rel(to_si, table[i].to_si, SI_REL_TOL), table[i].unit);
    }
    /* the length counts, not a NUL: "rad/s^2" read as its first 5 characters is rad/s */
    sim_dim_t dim;
    double to_si;
    TEST_ASSERT_EQUAL_INT(0, sim_series_unit("rad/s^2", 5, &dim, &to_si));
    TEST_ASSERT_EQUAL_INT(SIM_DIM_ANG_RATE, dim);
    /* case-sensitive, no blanks, nothing else */
    static const char *const unknown[] = {"", "S", "Deg", "rad/s^3", " s", "s ", "de g", "deg/sec", "m/s2", "rad/s/s"};
    for (size_t i = 0; i < sizeof unknown / sizeof unknown[0]; ++i) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, sim_series_unit(unknown[i], strlen(unknown[i]), &dim, &to_si), unknown[i]);
    }

    TEST_ASSERT_EQUAL_STRING("a time (s or ms)", sim_dim_describe(SIM_DIM_TIME));
    TEST_ASSERT_EQUAL_STRING("an angle (rad or deg)", sim_dim_describe(SIM_DIM_ANGLE));
    TEST_ASSERT_EQUAL_STRING("an angular rate (rad/s or deg/s)", sim_dim_describe(SIM_DIM_ANG_RATE));
    TEST_ASSERT_EQUAL_STRING("an angular acceleration (rad/s^2 or deg/s^2)", sim_dim_describe(SIM_DIM_ANG_ACCEL));
    TEST_ASSERT_EQUAL_STRING("a velocity (m/s)", sim_dim_describe(SIM_DIM_VELOCITY));
    TEST_ASSERT_EQUAL_STRING("an acceleration (m/s^2)", sim_dim_describe(SIM_DIM_LIN_ACCEL));
    TEST_ASSERT_EQUAL_STRING("?", sim_dim_describe(SIM_DIM_COUNT));
    TEST_ASSERT_EQUAL_STRING("?", sim_dim_describe((sim_dim_t)-1));
}

static void test_every_dimension_reads_its_units(void)
{
    static const struct {
        sim_dim_t dim;
        const char *header;
        double factor;
    } cases[] = {
        {SIM_DIM_ANGLE, "t [s], a [deg]\n", PI / 180.0},      {SIM_DIM_ANGLE, "t [s], a [rad]\n", 1.0},
        {SIM_DIM_ANG_RATE, "t [s], a [deg/s]\n", PI / 180.0}, {SIM_DIM_ANG_RATE, "t [s], a [rad/s]\n", 1.0},
        {SIM_DIM_VELOCITY, "t [s], a [m/s]\n", 1.0},          {SIM_DIM_LIN_ACCEL, "t [s], a [m/s^2]\n", 1.0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char text[128];
        snprintf(text, sizeof text, "%s0, 2\n1, -3\n", cases[i].header);
        const sim_series_spec_t spec = spec_of(cases[i].dim, SIM_SERIES_LINEAR, SIM_SERIES_HOLD_END);
        sim_series_t s;
        parse_text(&s, text, &spec);
        TEST_ASSERT_EQUAL_INT(1, s.n_cols);
        TEST_ASSERT_TRUE_MESSAGE(near_rel(s.value[0], 2.0 * cases[i].factor, SI_REL_TOL), cases[i].header);
        TEST_ASSERT_TRUE_MESSAGE(near_rel(s.value[1], -3.0 * cases[i].factor, SI_REL_TOL), cases[i].header);
        sim_series_free(&s);
    }
}

static void test_numbers_in_every_written_form(void)
{
    static const char text[] = "t [s], roll [rad/s^2]\n"
                               "-3, 2\n"
                               "2., -3\n"
                               ".5e1, .5\n"
                               "+4E+2, 1e-3\n"
                               "4.5e2, +4E+2\n"
                               "1000, -0\n";
    const sim_series_spec_t spec = accel_spec();
    sim_series_t s;
    parse_text(&s, text, &spec);
    TEST_ASSERT_EQUAL_UINT(6, s.n_rows);
    const double t[6] = {-3.0, 2.0, 5.0, 400.0, 450.0, 1000.0};
    const double v[6] = {2.0, -3.0, 0.5, 1e-3, 400.0, 0.0};
    for (int i = 0; i < 6; ++i) {
        TEST_ASSERT_TRUE(s.t_s[i] == t[i]);
        TEST_ASSERT_TRUE(s.value[i] == v[i]);
    }
    TEST_ASSERT_TRUE(signbit(s.value[5])); /* -0 kept as written */
    TEST_ASSERT_TRUE(s.period_s == 1003.0);
    sim_series_free(&s);
}

/* ---- evaluation -------------------------------------------------------- */

/* t = 1, 2, 4 (first t not 0): exact binary times. */
static const char THREE_ROWS[] = "t [s], roll [rad/s^2], pitch [rad/s^2]\n"
                                 "1, 0, 10\n"
                                 "2, 10, -10\n"
                                 "4, 4, 0\n";

static void test_linear_between_rows_and_the_first_row_before_it(void)
{
    const sim_series_spec_t spec = accel_spec();
    sim_series_t s;
    parse_text(&s, THREE_ROWS, &spec);
    double out[SIM_SERIES_MAX_COLS];
    /* before the first row's time, and at it: the first row */
    const double before[] = {-1e300, -5.0, 0.0, 1.0};
    for (size_t i = 0; i < sizeof before / sizeof before[0]; ++i) {
        sim_series_eval(&s, NULL, before[i], out);
        TEST_ASSERT_TRUE(out[0] == 0.0 && out[1] == 10.0 && out[2] == 0.0);
    }
    sim_series_eval(&s, NULL, -INFINITY, out);
    TEST_ASSERT_TRUE(out[0] == 0.0 && out[1] == 10.0);
    /* at the rows: their values exactly */
    sim_series_eval(&s, NULL, 2.0, out);
    TEST_ASSERT_TRUE(out[0] == 10.0 && out[1] == -10.0);
    /* between */
    sim_series_eval(&s, NULL, 1.25, out);
    TEST_ASSERT_TRUE(near(out[0], 2.5, INTERP_TOL));
    TEST_ASSERT_TRUE(near(out[1], 5.0, INTERP_TOL));
    sim_series_eval(&s, NULL, 3.0, out);
    TEST_ASSERT_TRUE(near(out[0], 7.0, INTERP_TOL));
    TEST_ASSERT_TRUE(near(out[1], -5.0, INTERP_TOL));
    sim_series_eval(&s, NULL, 3.9, out);
    TEST_ASSERT_TRUE(near(out[0], 10.0 - 6.0 * 0.95, INTERP_TOL));
    /* columns beyond n_cols are 0 */
    TEST_ASSERT_TRUE(out[2] == 0.0);
    /* hold at the end: the last row from its time on */
    const double after[] = {4.0, 4.5, 1e6, 1e300, INFINITY};
    for (size_t i = 0; i < sizeof after / sizeof after[0]; ++i) {
        sim_series_eval(&s, NULL, after[i], out);
        TEST_ASSERT_TRUE(out[0] == 4.0 && out[1] == 0.0 && out[2] == 0.0);
    }
    /* NaN in, NaN out on the series' columns only */
    sim_series_eval(&s, NULL, NAN, out);
    TEST_ASSERT_TRUE(isnan(out[0]) && isnan(out[1]) && out[2] == 0.0);
    sim_series_free(&s);
}

static void test_hold_gives_the_last_row_at_or_before_t(void)
{
    const sim_series_spec_t spec = spec_of(SIM_DIM_ANG_ACCEL, SIM_SERIES_HOLD, SIM_SERIES_HOLD_END);
    sim_series_t s;
    parse_text(&s, THREE_ROWS, &spec);
    double out[SIM_SERIES_MAX_COLS];
    const struct {
        double t, roll, pitch;
    } cases[] = {
        {-3.0, 0, 10},  {1.0, 0, 10},    {1.5, 0, 10}, {nextafter(2.0, 0.0), 0, 10},
        {2.0, 10, -10}, {3.99, 10, -10}, {4.0, 4, 0},  {100.0, 4, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        sim_series_eval(&s, NULL, cases[i].t, out);
        TEST_ASSERT_TRUE(out[0] == cases[i].roll && out[1] == cases[i].pitch && out[2] == 0.0);
    }
    sim_series_free(&s);
}

static void test_repeat_loops_with_the_first_row_at_the_seam(void)
{
    /* P = 4 - 1 = 3 s; the seams are at 4, 7, 10 ... */
    const sim_series_spec_t spec = spec_of(SIM_DIM_ANG_ACCEL, SIM_SERIES_LINEAR, SIM_SERIES_REPEAT);
    sim_series_t s;
    parse_text(&s, THREE_ROWS, &spec);
    TEST_ASSERT_TRUE(s.period_s == 3.0);
    double out[SIM_SERIES_MAX_COLS], again[SIM_SERIES_MAX_COLS];
    /* at the last row's time and every seam after it: the first row's values */
    for (int k = 1; k <= 5; ++k) {
        sim_series_eval(&s, NULL, 1.0 + 3.0 * k, out);
        TEST_ASSERT_TRUE(out[0] == 0.0 && out[1] == 10.0);
    }
    /* approaching the seam: towards the last row's values (4, 0), a step there */
    sim_series_eval(&s, NULL, nextafter(4.0, 0.0), out);
    TEST_ASSERT_TRUE(near(out[0], 4.0, SEAM_TOL) && near(out[1], 0.0, SEAM_TOL));
    sim_series_eval(&s, NULL, nextafter(7.0, 0.0), out);
    TEST_ASSERT_TRUE(near(out[0], 4.0, SEAM_TOL) && near(out[1], 0.0, SEAM_TOL));
    /* a later loop repeats the first, at times exact in binary */
    const double in_first[] = {1.25, 1.5, 2.0, 2.5, 3.0, 3.75};
    for (size_t i = 0; i < sizeof in_first / sizeof in_first[0]; ++i) {
        sim_series_eval(&s, NULL, in_first[i], out);
        for (int k = 1; k <= 3; ++k) {
            sim_series_eval(&s, NULL, in_first[i] + 3.0 * k, again);
            TEST_ASSERT_TRUE(same_bits(out, again, SIM_SERIES_MAX_COLS));
        }
    }
    sim_series_eval(&s, NULL, 5.0, out); /* 2 s into the loop: row 2 exactly */
    TEST_ASSERT_TRUE(out[0] == 10.0 && out[1] == -10.0);
    /* before the first row's time it is not looped */
    sim_series_eval(&s, NULL, -2.0, out);
    TEST_ASSERT_TRUE(out[0] == 0.0 && out[1] == 10.0);
    sim_series_free(&s);

    /* the last row repeating the first: continuous across the seam */
    static const char closed[] = "t [s], roll [rad/s^2]\n0, 1\n0.5, 3\n1, 1\n";
    parse_text(&s, closed, &spec);
    sim_series_eval(&s, NULL, nextafter(1.0, 0.0), out);
    sim_series_eval(&s, NULL, 1.0, again);
    TEST_ASSERT_TRUE(near(out[0], 1.0, SEAM_TOL) && again[0] == 1.0);
    sim_series_eval(&s, NULL, 2.25, out);
    TEST_ASSERT_TRUE(near(out[0], 2.0, INTERP_TOL));
    sim_series_free(&s);
}

static void test_repeat_with_hold_never_gives_the_last_row(void)
{
    const sim_series_spec_t spec = spec_of(SIM_DIM_ANG_ACCEL, SIM_SERIES_HOLD, SIM_SERIES_REPEAT);
    sim_series_t s;
    double out[SIM_SERIES_MAX_COLS];
    parse_text(&s, THREE_ROWS, &spec);
    sim_series_eval(&s, NULL, nextafter(4.0, 0.0), out);
    TEST_ASSERT_TRUE(out[0] == 10.0 && out[1] == -10.0); /* held from t = 2 */
    sim_series_eval(&s, NULL, 4.0, out);
    TEST_ASSERT_TRUE(out[0] == 0.0 && out[1] == 10.0);
    sim_series_eval(&s, NULL, 5.5, out);
    TEST_ASSERT_TRUE(out[0] == 10.0 && out[1] == -10.0);
    sim_series_free(&s);

    /* Times a few ulps around the seams of a file whose times are not exact
     * in binary: some of them (just below the seams at t = -0.003 and
     * -0.002) reduce to a time that rounds onto the last row's. */
    static const char inexact[] = "t [s], roll [rad/s^2]\n-0.005, 1\n-0.0045, 2\n-0.004, 3\n";
    parse_text(&s, inexact, &spec);
    for (int k = 1; k <= 4; ++k) {
        const double seam = s.t_s[0] + k * s.period_s;
        for (int dir = -1; dir <= 1; dir += 2) {
            double t = seam;
            for (int j = 0; j < 8; ++j) {
                t = nextafter(t, dir * INFINITY);
                sim_series_eval(&s, NULL, t, out);
                TEST_ASSERT_TRUE_MESSAGE(out[0] == 1.0 || out[0] == 2.0, "hold gave the last row past its time");
            }
        }
    }
    sim_series_free(&s);
}

static void test_refuse_and_covers(void)
{
    static const char gust[] = "t [s], roll [rad/s^2]\n0, 1\n2, 3\n4, 5\n";
    sim_series_spec_t spec = spec_of(SIM_DIM_ANG_ACCEL, SIM_SERIES_LINEAR, SIM_SERIES_REFUSE);
    sim_series_t s;
    parse_text(&s, gust, &spec);
    TEST_ASSERT_EQUAL_INT(SIM_SERIES_REFUSE, s.end);
    char why[160];
    TEST_ASSERT_EQUAL_INT(1, sim_series_covers(&s, 4.0, "gust.csv", why, sizeof why));
    TEST_ASSERT_EQUAL_INT(1, sim_series_covers(&s, 1.0, "gust.csv", why, sizeof why));
    TEST_ASSERT_EQUAL_INT(1, sim_series_covers(&s, 4.0, "gust.csv", NULL, 0));
    TEST_ASSERT_EQUAL_INT(0, sim_series_covers(&s, 10.0, "gust.csv", why, sizeof why));
    TEST_ASSERT_EQUAL_STRING("'gust.csv' ends at t = 4 s, before the run's end at 10 s", why);
    TEST_ASSERT_EQUAL_INT(0, sim_series_covers(&s, nextafter(4.0, 5.0), "dir/gust.csv", why, sizeof why));
    TEST_ASSERT_NOT_NULL(strstr(why, "'dir/gust.csv'"));
    TEST_ASSERT_NOT_NULL(strstr(why, "t = 4 s"));
    TEST_ASSERT_EQUAL_INT(0, sim_series_covers(&s, 12.5, "gust.csv", NULL, 0)); /* no text asked */
    /* a short buffer: cut, still terminated */
    char small[8];
    TEST_ASSERT_EQUAL_INT(0, sim_series_covers(&s, 10.0, "gust.csv", small, sizeof small));
    TEST_ASSERT_EQUAL_STRING("'gust.c", small);
    /* evaluated past the end anyway: it holds */
    double out[SIM_SERIES_MAX_COLS];
    sim_series_eval(&s, NULL, 9.0, out);
    TEST_ASSERT_TRUE(out[0] == 5.0);
    sim_series_eval(&s, NULL, 3.0, out);
    TEST_ASSERT_TRUE(near(out[0], 4.0, INTERP_TOL));
    sim_series_free(&s);

    /* repeat and hold cover any run */
    const sim_series_end_t others[] = {SIM_SERIES_REPEAT, SIM_SERIES_HOLD_END};
    for (int i = 0; i < 2; ++i) {
        spec.end = others[i];
        parse_text(&s, gust, &spec);
        TEST_ASSERT_EQUAL_INT(1, sim_series_covers(&s, 1e9, "gust.csv", why, sizeof why));
        sim_series_free(&s);
    }
}

/* ---- the cursor, and the same bits on every load ---------------------- */

static uint32_t lcg_next(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state;
}

static double lcg_unit(uint32_t *state)
{
    return (double)(lcg_next(state) >> 8) / 16777216.0; /* [0, 1) */
}

#define CURSOR_ROWS 400

/* A file of CURSOR_ROWS irregular rows of three columns (text to free). */
static char *irregular_file(size_t *len)
{
    const size_t cap = 128 + (size_t)CURSOR_ROWS * 160; /* four %.17g of at most 24 characters */
    char *text = malloc(cap);
    TEST_ASSERT_NOT_NULL(text);
    size_t n = (size_t)snprintf(text, cap, "t [ms], roll [deg/s^2], pitch [rad/s^2], yaw [deg/s^2]\n");
    uint32_t state = 12345u;
    double t_ms = -250.0;
    for (int i = 0; i < CURSOR_ROWS; ++i) {
        t_ms += 0.5 + 4.0 * lcg_unit(&state);
        n += (size_t)snprintf(text + n, cap - n, "%.17g, %.17g, %.17g, %.17g\n", t_ms, 100.0 * sin(0.1 * i),
                              lcg_unit(&state) - 0.5, (double)(i % 7) * 3.0);
        TEST_ASSERT_TRUE(n < cap);
    }
    *len = n;
    return text;
}

/* The value at t with the cursor equals the one without, bit for bit. */
static void check_cursor_at(const sim_series_t *s, sim_series_cursor_t *cursor, double t)
{
    double with[SIM_SERIES_MAX_COLS], without[SIM_SERIES_MAX_COLS];
    sim_series_eval(s, cursor, t, with);
    sim_series_eval(s, NULL, t, without);
    TEST_ASSERT_TRUE_MESSAGE(same_bits(with, without, SIM_SERIES_MAX_COLS), "the cursor changed a value");
}

static void test_the_cursor_never_changes_a_value(void)
{
    size_t len;
    char *text = irregular_file(&len);
    const sim_series_interp_t interps[] = {SIM_SERIES_LINEAR, SIM_SERIES_HOLD};
    const sim_series_end_t ends[] = {SIM_SERIES_REPEAT, SIM_SERIES_HOLD_END, SIM_SERIES_REFUSE};
    for (int a = 0; a < 2; ++a) {
        for (int b = 0; b < 3; ++b) {
            const sim_series_spec_t spec = spec_of(SIM_DIM_ANG_ACCEL, interps[a], ends[b]);
            sim_series_t s;
            parse_ok(&s, text, len, &spec);
            TEST_ASSERT_EQUAL_UINT(CURSOR_ROWS, s.n_rows);
            const double t0 = s.t_s[0] - 0.05, t1 = s.t_s[s.n_rows - 1] + 2.5 * s.period_s;
            const double h = 2.5e-4; /* a plant step of 0.5 ms in RK4 half steps */
            sim_series_cursor_t cursor;
            sim_series_cursor_init(&cursor);
            for (double t = t0; t < t1; t += h) { /* increasing */
                check_cursor_at(&s, &cursor, t);
            }
            for (double t = t1; t > t0; t -= h) { /* decreasing */
                check_cursor_at(&s, &cursor, t);
            }
            uint32_t state = 99u;
            for (int i = 0; i < 20000; ++i) { /* anywhere */
                check_cursor_at(&s, &cursor, t0 + (t1 - t0) * lcg_unit(&state));
            }
            for (size_t i = 0; i < s.n_rows; ++i) { /* at the rows, on the way back */
                check_cursor_at(&s, &cursor, s.t_s[s.n_rows - 1 - i]);
            }
            /* any cursor is safe: stale, past the rows, from another series */
            const size_t rows[] = {0, 1, CURSOR_ROWS - 2, CURSOR_ROWS - 1, CURSOR_ROWS, 123456, (size_t)-1};
            for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i) {
                for (int j = 0; j < 50; ++j) {
                    cursor.row = rows[i];
                    check_cursor_at(&s, &cursor, t0 + (t1 - t0) * lcg_unit(&state));
                }
            }
            sim_series_free(&s);
        }
    }
    free(text);
}

static void assert_same_series(const sim_series_t *a, const sim_series_t *b)
{
    TEST_ASSERT_EQUAL_UINT(a->n_rows, b->n_rows);
    TEST_ASSERT_EQUAL_INT(a->n_cols, b->n_cols);
    TEST_ASSERT_TRUE(same_bits(a->t_s, b->t_s, a->n_rows));
    TEST_ASSERT_TRUE(same_bits(a->value, b->value, a->n_rows * (size_t)a->n_cols));
    TEST_ASSERT_TRUE(same_bits(&a->period_s, &b->period_s, 1));
    TEST_ASSERT_EQUAL_MEMORY(a->name, b->name, sizeof a->name);
    TEST_ASSERT_EQUAL_INT(a->dim, b->dim);
    TEST_ASSERT_EQUAL_INT(a->interp, b->interp);
    TEST_ASSERT_EQUAL_INT(a->end, b->end);
}

static void test_the_same_bytes_give_byte_identical_series(void)
{
    size_t len;
    char *text = irregular_file(&len);
    const sim_series_spec_t spec = accel_spec();
    sim_series_t a, b;
    parse_ok(&a, text, len, &spec);
    parse_ok(&b, text, len, &spec);
    TEST_ASSERT_TRUE(a.t_s != b.t_s);
    assert_same_series(&a, &b);
    /* and so the same values */
    for (int i = 0; i < 1000; ++i) {
        const double t = -0.3 + 1e-3 * i;
        double va[SIM_SERIES_MAX_COLS], vb[SIM_SERIES_MAX_COLS];
        sim_series_eval(&a, NULL, t, va);
        sim_series_eval(&b, NULL, t, vb);
        TEST_ASSERT_TRUE(same_bits(va, vb, SIM_SERIES_MAX_COLS));
    }
    sim_series_free(&a);
    sim_series_free(&b);
    free(text);
}

/* A new file of our own in the test's folder, holding len bytes of text. */
static void write_temp(const char *text, size_t len)
{
    snprintf(path, sizeof path, "series_test_XXXXXX");
    const int fd = mkstemp(path);
    TEST_ASSERT_TRUE(fd >= 0);
    FILE *f = fdopen(fd, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_UINT(len, fwrite(text, 1, len, f));
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
}

static void test_load_reads_a_file_as_parse_reads_its_bytes(void)
{
    size_t len;
    char *text = irregular_file(&len);
    write_temp(text, len);
    const sim_series_spec_t spec = spec_of(SIM_DIM_ANG_ACCEL, SIM_SERIES_HOLD, SIM_SERIES_REPEAT);
    sim_series_t loaded, parsed;
    sim_series_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_series_load(&loaded, path, &spec, &err), err.message);
    parse_ok(&parsed, text, len, &spec);
    assert_same_series(&loaded, &parsed);
    sim_series_free(&loaded);
    sim_series_free(&parsed);
    free(text);
    remove(path);

    /* an error in a file: its path and the place parse gives */
    static const char bad[] = "t [s], roll [rad/s^2]\n0, 1\n1, x\n";
    write_temp(bad, sizeof bad - 1);
    memset(&loaded, 0x5a, sizeof loaded);
    TEST_ASSERT_EQUAL_INT(-1, sim_series_load(&loaded, path, &spec, &err));
    TEST_ASSERT_EQUAL_STRING(path, err.path);
    TEST_ASSERT_EQUAL_INT(3, err.line);
    TEST_ASSERT_EQUAL_INT(4, err.column);
    TEST_ASSERT_NOT_NULL(strstr(err.message, "expected a number"));
    assert_empty(&loaded);
    TEST_ASSERT_EQUAL_INT(-1, sim_series_load(&loaded, path, &spec, NULL)); /* not reported: fine */
    assert_empty(&loaded);
}

static void test_a_file_that_cannot_be_read_is_at_line_0_column_0(void)
{
    const sim_series_spec_t spec = accel_spec();
    sim_series_t s;
    sim_series_error_t err;
    memset(&s, 0x5a, sizeof s);
    TEST_ASSERT_EQUAL_INT(-1, sim_series_load(&s, "no_such_folder/no_such_series.csv", &spec, &err));
    TEST_ASSERT_EQUAL_INT(0, err.line);
    TEST_ASSERT_EQUAL_INT(0, err.column);
    TEST_ASSERT_EQUAL_STRING("no_such_folder/no_such_series.csv", err.path);
    TEST_ASSERT_NOT_NULL(strstr(err.message, "cannot open"));
    assert_empty(&s);
    /* a folder is no file either */
    memset(&s, 0x5a, sizeof s);
    TEST_ASSERT_EQUAL_INT(-1, sim_series_load(&s, ".", &spec, &err));
    TEST_ASSERT_EQUAL_INT(0, err.line);
    TEST_ASSERT_EQUAL_INT(0, err.column);
    assert_empty(&s);
    TEST_ASSERT_EQUAL_INT(-1, sim_series_load(&s, NULL, &spec, &err));
    TEST_ASSERT_EQUAL_INT(0, err.line);
    assert_empty(&s);
}

static void test_a_bad_request_is_refused_before_the_text(void)
{
    static const char good[] = "t [s], roll [rad/s^2]\n0, 1\n1, 2\n";
    sim_series_t s;
    sim_series_error_t err;
    sim_series_spec_t spec = accel_spec();
    memset(&s, 0x5a, sizeof s);
    TEST_ASSERT_EQUAL_INT(-1, sim_series_parse(&s, good, sizeof good - 1, "x.csv", NULL, &err));
    TEST_ASSERT_EQUAL_INT(0, err.line);
    TEST_ASSERT_EQUAL_INT(0, err.column);
    assert_empty(&s);
    spec.dim = SIM_DIM_TIME; /* not a value's dimension */
    TEST_ASSERT_EQUAL_INT(-1, sim_series_parse(&s, good, sizeof good - 1, "x.csv", &spec, &err));
    assert_empty(&s);
    spec.dim = SIM_DIM_COUNT;
    TEST_ASSERT_EQUAL_INT(-1, sim_series_parse(&s, good, sizeof good - 1, "x.csv", &spec, &err));
    spec = accel_spec();
    spec.interp = (sim_series_interp_t)2;
    TEST_ASSERT_EQUAL_INT(-1, sim_series_parse(&s, good, sizeof good - 1, "x.csv", &spec, &err));
    spec = accel_spec();
    spec.end = (sim_series_end_t)3;
    TEST_ASSERT_EQUAL_INT(-1, sim_series_parse(&s, good, sizeof good - 1, "x.csv", &spec, &err));
    assert_empty(&s);
    spec = accel_spec();
    TEST_ASSERT_EQUAL_INT(-1, sim_series_parse(NULL, good, sizeof good - 1, "x.csv", &spec, &err));
    TEST_ASSERT_EQUAL_INT(-1, sim_series_parse(&s, NULL, 5, "x.csv", &spec, &err));
    TEST_ASSERT_EQUAL_INT(0, err.line);
    assert_empty(&s);
    /* no error struct: still refused, still empty */
    TEST_ASSERT_EQUAL_INT(-1, sim_series_parse(&s, "t [s]\n", 6, NULL, &spec, NULL));
    assert_empty(&s);
    /* the text need not end with a NUL: only len bytes are read */
    static const char longer[] = "t [s], roll [rad/s^2]\n0, 1\n1, 2\n2, x";
    TEST_ASSERT_EQUAL_INT(0, sim_series_parse(&s, longer, sizeof longer - 1 - 4, "x.csv", &spec, &err));
    TEST_ASSERT_EQUAL_UINT(2, s.n_rows);
    sim_series_free(&s);
    /* a zeroed series may be freed; so may NULL */
    memset(&s, 0, sizeof s);
    sim_series_free(&s);
    sim_series_free(NULL);
}

/* ---- errors: the header ---------------------------------------------- */

static void test_a_missing_header_is_at_the_end_of_the_file(void)
{
    expect_error("", 1, 1, "empty file", "header");
    expect_error("# only a comment\n\n", 3, 1, "no header", NULL);
    expect_error("# a\n   \n# bc", 3, 5, "no header", NULL);
    expect_error("\xEF\xBB\xBF", 1, 1, "header", NULL);
    /* the first other line is the header: rows without one are a bad header */
    expect_error("# no header\n0, 1\n1, 2\n", 2, 1, "expected a header line", "t [s], roll [rad/s^2]");
    const sim_series_spec_t rate = spec_of(SIM_DIM_ANG_RATE, SIM_SERIES_LINEAR, SIM_SERIES_HOLD_END);
    expect_error_len("  [s], roll [rad/s]\n", 20, &rate, 1, 3, "expected a header line", "roll [rad/s]");
}

static void test_a_column_without_a_unit(void)
{
    expect_error("t_s, roll [rad/s^2]\n0, 1\n1, 2\n", 1, 1, "'t_s' has no unit", "brackets");
    const char *line = "  t [s], roll\n";
    expect_error("# comment\n  t [s], roll\n0, 1\n1, 2\n", 2, column_of(line, "roll"), "'roll' has no unit",
                 "roll [rad/s^2]");
    line = "t [s], roll (rad/s^2)";
    expect_error("t [s], roll (rad/s^2)\n", 1, column_of(line, "roll"), "no unit", NULL);
    /* no name at all, or a name that does not start with a letter or '_' */
    line = "t [s], [rad/s^2]";
    expect_error("t [s], [rad/s^2]\n", 1, column_of(line, "[rad"), "expected a column name", NULL);
    line = "t [s], 1roll [rad/s^2]";
    expect_error("t [s], 1roll [rad/s^2]\n", 1, column_of(line, "1roll"), "expected a column name", NULL);
    line = "t [s], roll [rad/s^2],";
    expect_error("t [s], roll [rad/s^2],\n", 1, (int)strlen(line) + 1, "expected a column name", NULL);
    /* names of 31 characters, not 32 */
    expect_error("t [s], a234567890123456789012345678901b [rad/s^2]\n", 1, 8, "longer than 31", NULL);
    sim_series_t s;
    const sim_series_spec_t spec = accel_spec();
    parse_text(&s, "t [s], _234567890123456789012345678901 [rad/s^2]\n0, 1\n1, 2\n", &spec);
    TEST_ASSERT_EQUAL_STRING("_234567890123456789012345678901", s.name[1]);
    sim_series_free(&s);
}

static void test_an_unknown_unit_is_at_its_bracket(void)
{
    const char *line = "t [s], roll [deg/s^3]";
    expect_error("t [s], roll [deg/s^3]\n0, 1\n", 1, column_of(line, "[deg"), "unknown unit [deg/s^3]",
                 "the series wants an angular acceleration (rad/s^2 or deg/s^2)");
    line = "t [s], roll [ de g ]";
    expect_error("t [s], roll [ de g ]\n", 1, column_of(line, "[ de"), "unknown unit [de g]", NULL);
    line = "t [s], roll [Deg/s^2]";
    expect_error("t [s], roll [Deg/s^2]\n", 1, column_of(line, "[Deg"), "unknown unit", NULL);
    line = "t [s], roll []";
    expect_error("t [s], roll []\n", 1, column_of(line, "[]"), "unknown unit []", NULL);
    line = "t [s], roll [rad/s^2";
    expect_error("t [s], roll [rad/s^2\n", 1, column_of(line, "[rad"), "expected ']'", NULL);
    line = "t [s], roll [rad/s^2] x";
    expect_error("t [s], roll [rad/s^2] x\n", 1, column_of(line, "x"), "unexpected 'x' after the unit", NULL);
    /* the time's own units: s or ms only */
    expect_error("t [min], roll [rad/s^2]\n", 1, 3, "unknown unit [min]", "the first column is the time, in s or ms");
}

static void test_a_unit_of_another_dimension_names_the_key(void)
{
    sim_series_spec_t spec = accel_spec();
    spec.key = "disturbance_series";
    const char *line = "t [s], roll [rad/s^2], pitch [deg/s]";
    expect_error_spec("t [s], roll [rad/s^2], pitch [deg/s]\n", &spec, 1, column_of(line, "[deg"),
                      "unit [deg/s] is an angular rate",
                      "key disturbance_series wants an angular acceleration (rad/s^2 or deg/s^2)");
    /* without a key */
    spec.key = NULL;
    expect_error_spec("t [s], roll [rad/s^2], pitch [deg/s]\n", &spec, 1, column_of(line, "[deg"),
                      "unit [deg/s] is an angular rate", "the series wants an angular acceleration");
    /* an angle wanted, an acceleration given */
    spec = spec_of(SIM_DIM_ANGLE, SIM_SERIES_HOLD, SIM_SERIES_REFUSE);
    spec.key = "noise_series";
    line = "t [ms],\troll [ m/s^2 ]";
    expect_error_spec("t [ms],\troll [ m/s^2 ]\n", &spec, 1, column_of(line, "[ m"), "unit [m/s^2] is an acceleration",
                      "key noise_series wants an angle (rad or deg)");
}

static void test_the_time_column_must_be_a_time(void)
{
    expect_error("t [deg], roll [rad/s^2]\n0, 1\n1, 2\n", 1, 3, "unit [deg] is an angle",
                 "the first column is the time, in s or ms");
    expect_error("t [rad/s^2], roll [rad/s^2]\n", 1, 3, "an angular acceleration", "the time");
    /* a value column in s is no value */
    const char *line = "t [s], roll [ms]";
    expect_error("t [s], roll [ms]\n", 1, column_of(line, "[ms"), "unit [ms] is a time", "angular acceleration");
}

static void test_the_number_of_header_columns(void)
{
    const char *line = "t [s], a [rad/s^2], b [rad/s^2], c [rad/s^2], d [rad/s^2]";
    char text[128];
    snprintf(text, sizeof text, "%s\n0, 1, 2, 3, 4\n", line);
    expect_error(text, 1, column_of(line, "d ["), "too many columns", "at most 3 value columns");
    /* the end of the header, before its trailing blanks */
    expect_error("\t t [s]  \n0\n1\n", 1, 8, "expected a value column after the time", NULL);
}

/* ---- errors: the rows ------------------------------------------------- */

static const char HEAD2[] = "t [s], roll [rad/s^2], pitch [rad/s^2]\n";

static void expect_row_error(const char *rows, int line, int column, const char *word1, const char *word2)
{
    char text[512];
    snprintf(text, sizeof text, "%s%s", HEAD2, rows);
    expect_error(text, line, column, word1, word2);
}

static void test_a_row_lacking_a_value_is_at_the_end_of_the_row(void)
{
    const char *row = "0.5, 1.0";
    expect_row_error("0, 1, 2\n0.5, 1.0  \r\n1, 1, 1\n", 3, (int)strlen(row) + 1, "expected 3 values",
                     "found 2: a value is missing");
    /* "\t0.5": the tab is column 1, the row ends at column 5 */
    expect_row_error("0,2,3\r\n\t0.5\t\r\n", 3, 5, "found 1", NULL);
    /* an empty cell is no number, at its place: "0.5, , 1" has it at the second comma */
    expect_row_error("0, 1, 2\n0.5, , 1\n", 3, 6, "expected a number", NULL);
    row = "0.5, 1,";
    expect_row_error("0, 1, 2\n0.5, 1,\n", 3, (int)strlen(row) + 1, "expected a number", NULL);
}

static void test_an_extra_value_is_at_its_cell(void)
{
    const char *row = "0.5, 1.0, 2.0,  3.0";
    expect_row_error("0, 1, 2\n0.5, 1.0, 2.0,  3.0\n", 3, column_of(row, "3.0"), "unexpected value",
                     "the header has 3 columns");
    row = "0.5, 1.0, 2.0,";
    expect_row_error("0.5, 1.0, 2.0,\n", 2, (int)strlen(row) + 1, "unexpected value", NULL);
}

static void test_what_is_not_a_number_is_at_its_cell(void)
{
    static const char *const bad[] = {"abc", "0x10", "1.2.3", "- 5", "--5", "1e",  "1e+",
                                      "e5",  ".",    "+",     "2 3", "1d0", "(1)", "1_000"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        char rows[64];
        snprintf(rows, sizeof rows, "0, 1, 2\n1, 0, %s\n", bad[i]);
        expect_row_error(rows, 3, 7, "expected a number", NULL);
    }
    expect_row_error("0, 1, 2\n1, 0, abc\n", 3, 7, "got 'abc'", NULL);
    /* a '#' after a value is no comment */
    expect_row_error("0, 1, 2\n1, 3 # peak, 4\n", 3, 4, "expected a number", "'3 # peak'");
    expect_row_error("0, 1, 2 # first\n1, 3, 4\n", 2, 7, "expected a number", NULL);
    expect_row_error("0, 1, 2\n1, 3, 4#\n", 3, 7, "expected a number", NULL);
    /* a long cell is shown cut */
    expect_row_error("0, 1, 2\n1, 3, 1234567890123456789012345678901234567890123456789012345678901234x\n", 3, 7,
                     "expected a number", NULL);
}

static void test_values_must_be_finite(void)
{
    static const char *const bad[] = {"nan", "NaN", "-nan", "+NAN", "inf", "-inf", "+Inf", "infinity", "-Infinity"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        char rows[64];
        snprintf(rows, sizeof rows, "0, 1, 2\n1, %s, 0\n", bad[i]);
        expect_row_error(rows, 3, 4, "is not finite", "finite number");
        snprintf(rows, sizeof rows, "%s, 1, 2\n1, 0, 0\n", bad[i]);
        expect_row_error(rows, 2, 1, "is not finite", NULL);
    }
    expect_row_error("0, 1, 2\n1, 0, 1e999\n", 3, 7, "out of range", "'1e999'");
    expect_row_error("0, 1, 2\n1, -1e400, 0\n", 3, 4, "out of range", NULL);
    /* the span from the first to the last time must be finite */
    expect_row_error("-1e308, 1, 2\n0, 1, 2\n1e308, 0, 0\n", 4, 1, "too far from the first row", "span");
    /* the largest values are finite */
    sim_series_t s;
    const sim_series_spec_t spec = accel_spec();
    parse_text(&s, "t [s], roll [rad/s^2]\n0, 1.7976931348623157e308\n1, -1.7976931348623157e308\n", &spec);
    double out[SIM_SERIES_MAX_COLS];
    sim_series_eval(&s, NULL, 0.5, out);
    TEST_ASSERT_TRUE(isfinite(out[0])); /* no overflow between them: 0 in exact arithmetic */
    TEST_ASSERT_TRUE(fabs(out[0]) <= 1e-15 * 1.7976931348623157e308);
    sim_series_free(&s);
}

static void test_times_must_increase_strictly(void)
{
    expect_row_error("0, 1, 2\n# a comment\n0.5, 1, 2\n0.5, 0, 0\n", 5, 1, "does not follow the previous row's",
                     "(line 4): the times must increase strictly");
    expect_row_error("0, 1, 2\n  -0.5, 1, 2\n", 3, 3, "t = -0.5 s does not follow", "t = 0 s (line 2)");
    /* -0 equals 0 */
    expect_row_error("0, 1, 2\n-0, 1, 2\n", 3, 1, "increase strictly", NULL);
    /* compared in seconds: 1000 ms after 1 s is the same time */
    expect_error("t [ms], roll [rad/s^2]\n0, 0\n1000, 1\n1000.0, 2\n", 4, 1, "t = 1 s", "increase strictly");
}

static void test_a_nul_byte_is_at_its_place(void)
{
    static const char in_row[] = "t [s], roll [rad/s^2]\n0, 1\n1, 2\0\n2, 3\n";
    const sim_series_spec_t spec = accel_spec();
    expect_error_len(in_row, sizeof in_row - 1, &spec, 3, 5, "NUL", NULL);
    static const char in_comment[] = "# a\0comment\nt [s], roll [rad/s^2]\n0, 1\n1, 2\n";
    expect_error_len(in_comment, sizeof in_comment - 1, &spec, 1, 4, "NUL", NULL);
    static const char in_header[] = "\xEF\xBB\xBFt [s]\0, roll [rad/s^2]\n0, 1\n1, 2\n";
    expect_error_len(in_header, sizeof in_header - 1, &spec, 1, 6, "NUL", NULL);
    static const char last[] = "t [s], roll [rad/s^2]\n0, 1\n1, 2\n\0";
    expect_error_len(last, sizeof last - 1, &spec, 4, 1, "NUL", NULL);
}

static void test_a_series_needs_two_rows(void)
{
    expect_row_error("0, 1, 2\n", 3, 1, "1 row: a series needs at least 2", NULL);
    expect_row_error("# comment\n0, 1, 2\n\n", 5, 1, "1 row", NULL);
    expect_row_error("0, 1, 2", 2, 8, "1 row", NULL);
    expect_row_error("", 2, 1, "0 rows", NULL);
    expect_error("t [s], roll [rad/s^2]", 1, 22, "0 rows", NULL);
    sim_series_t s;
    const sim_series_spec_t spec = accel_spec();
    parse_text(&s, "t [s], roll [rad/s^2]\n0, 1\n1e-300, 2", &spec); /* two rows, no newline at the end */
    TEST_ASSERT_EQUAL_UINT(2, s.n_rows);
    TEST_ASSERT_TRUE(s.period_s == 1e-300);
    sim_series_free(&s);
}

static void test_columns_count_bytes_after_the_bom_and_lines_count_crlf(void)
{
    /* a tab is one column; the BOM is not counted */
    const char *line = "t\t[s],\troll [x]";
    expect_error("\xEF\xBB\xBFt\t[s],\troll [x]\r\n", 1, column_of(line, "[x"), "unknown unit [x]", NULL);
    expect_error("\xEF\xBB\xBF\xEF\xBB\xBFt [s], roll [rad/s^2]\n", 1, 1, "expected a header line", NULL);
    /* CRLF lines: the line of the error, its column without the CR */
    expect_error("\xEF\xBB\xBF# c\r\n\r\nt [s], roll [rad/s^2]\r\n0, 1\r\n1, 2, 3\r\n", 5, 7, "unexpected value", NULL);
    expect_error("t [s], roll [rad/s^2], pitch [rad/s^2]\r\n0, 1\r\n", 2, 5, "a value is missing", NULL);
    /* non-ASCII bytes are bytes */
    line = "t [s], r\xC3\xB6ll [rad/s^2]";
    expect_error("t [s], r\xC3\xB6ll [rad/s^2]\n", 1, column_of(line, "r\xC3"), "no unit", NULL);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_well_formed_file_parses_names_rows_and_si_values);
    RUN_TEST(test_every_unit_of_the_table_and_its_dimension);
    RUN_TEST(test_every_dimension_reads_its_units);
    RUN_TEST(test_numbers_in_every_written_form);
    RUN_TEST(test_linear_between_rows_and_the_first_row_before_it);
    RUN_TEST(test_hold_gives_the_last_row_at_or_before_t);
    RUN_TEST(test_repeat_loops_with_the_first_row_at_the_seam);
    RUN_TEST(test_repeat_with_hold_never_gives_the_last_row);
    RUN_TEST(test_refuse_and_covers);
    RUN_TEST(test_the_cursor_never_changes_a_value);
    RUN_TEST(test_the_same_bytes_give_byte_identical_series);
    RUN_TEST(test_load_reads_a_file_as_parse_reads_its_bytes);
    RUN_TEST(test_a_file_that_cannot_be_read_is_at_line_0_column_0);
    RUN_TEST(test_a_bad_request_is_refused_before_the_text);
    RUN_TEST(test_a_missing_header_is_at_the_end_of_the_file);
    RUN_TEST(test_a_column_without_a_unit);
    RUN_TEST(test_an_unknown_unit_is_at_its_bracket);
    RUN_TEST(test_a_unit_of_another_dimension_names_the_key);
    RUN_TEST(test_the_time_column_must_be_a_time);
    RUN_TEST(test_the_number_of_header_columns);
    RUN_TEST(test_a_row_lacking_a_value_is_at_the_end_of_the_row);
    RUN_TEST(test_an_extra_value_is_at_its_cell);
    RUN_TEST(test_what_is_not_a_number_is_at_its_cell);
    RUN_TEST(test_values_must_be_finite);
    RUN_TEST(test_times_must_increase_strictly);
    RUN_TEST(test_a_nul_byte_is_at_its_place);
    RUN_TEST(test_a_series_needs_two_rows);
    RUN_TEST(test_columns_count_bytes_after_the_bom_and_lines_count_crlf);
    return UNITY_END();
}
