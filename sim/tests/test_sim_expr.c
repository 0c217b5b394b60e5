/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulator expressions: number syntax, precedence and associativity, names
 * and functions, NaN propagation, constants, and every compile error with its
 * column and message. */
#include "unity.h"
#include "scenario/expr.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The program runs the same double operations (and libm calls) as the C
 * expression it is compared with, so the two agree to a few ulps; 1e-12
 * relative (plus 1e-12 absolute near 0) leaves a wide margin while any wrong
 * operator or operand is off by far more. */
#define REL_TOL 1e-12

static const double PI = 3.14159265358979323846;

void setUp(void)
{
}
void tearDown(void)
{
}

static void assert_close(double expected, double actual, const char *what)
{
    char message[160];
    snprintf(message, sizeof message, "%s: expected %.17g, got %.17g", what, expected, actual);
    TEST_ASSERT_TRUE_MESSAGE(fabs(actual - expected) <= REL_TOL * (1.0 + fabs(expected)), message);
}

/* Compiles text (which must compile) and checks its value at t_s. */
static void assert_value(const char *text, double t_s, double expected)
{
    sim_expr_t e;
    sim_expr_error_t err;
    char message[160];
    snprintf(message, sizeof message, "'%s' did not compile", text);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_expr_compile(&e, text, &err), message);
    assert_close(expected, sim_expr_eval(&e, t_s), text);
}

static void assert_nan(const char *text)
{
    sim_expr_t e;
    sim_expr_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_expr_compile(&e, text, &err), text);
    TEST_ASSERT_TRUE_MESSAGE(isnan(sim_expr_eval(&e, 0.0)), text);
}

static void assert_error(const char *text, int column, const char *message)
{
    sim_expr_t e;
    sim_expr_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(-1, sim_expr_compile(&e, text, &err), text);
    TEST_ASSERT_EQUAL_STRING_MESSAGE(message, err.message, text);
    TEST_ASSERT_EQUAL_INT_MESSAGE(column, err.column, text);
    /* a failed compile leaves an empty program */
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, e.n_ops, text);
}

static void test_numbers_in_every_written_form(void)
{
    assert_value("2", 0.0, 2.0);
    assert_value("2.", 0.0, 2.0);
    assert_value(".5", 0.0, 0.5);
    assert_value("2.50", 0.0, 2.5);
    assert_value("1e-3", 0.0, 1e-3);
    assert_value("4E+2", 0.0, 400.0);
    assert_value("1.5e1", 0.0, 15.0);
    assert_value("5.445e-3", 0.0, 5.445e-3);
    assert_value("007", 0.0, 7.0);
    assert_value("  \t3 ", 0.0, 3.0);
}

static void test_scan_number_stops_where_the_number_ends(void)
{
    double v = -1.0;
    TEST_ASSERT_EQUAL_UINT(1u, (unsigned)sim_expr_scan_number("1e", &v));
    assert_close(1.0, v, "1e");
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)sim_expr_scan_number("12abc", &v));
    assert_close(12.0, v, "12abc");
    TEST_ASSERT_EQUAL_UINT(1u, (unsigned)sim_expr_scan_number("0x10", &v));
    assert_close(0.0, v, "0x10");
    TEST_ASSERT_EQUAL_UINT(4u, (unsigned)sim_expr_scan_number("1e+2*t", &v));
    assert_close(100.0, v, "1e+2*t");
    TEST_ASSERT_EQUAL_UINT(3u, (unsigned)sim_expr_scan_number("1.5.2", &v));
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)sim_expr_scan_number("abc", &v));
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)sim_expr_scan_number(".", &v));
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)sim_expr_scan_number(".e5", &v));
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)sim_expr_scan_number("-1", &v));
    TEST_ASSERT_EQUAL_UINT(5u, (unsigned)sim_expr_scan_number("1e999", &v));
    TEST_ASSERT_TRUE(isinf(v));
}

static void test_precedence_follows_the_usual_math_convention(void)
{
    assert_value("1 + 2*3", 0.0, 7.0);
    assert_value("(1 + 2)*3", 0.0, 9.0);
    assert_value("1 + 6/3", 0.0, 3.0);
    assert_value("2*3^2", 0.0, 18.0);
    assert_value("2^2*3", 0.0, 12.0);
    assert_value("-2^2", 0.0, -4.0); /* minus applies to the power */
    assert_value("(-2)^2", 0.0, 4.0);
    assert_value("2^-1", 0.0, 0.5);   /* a signed exponent */
    assert_value("2^-1^2", 0.0, 0.5); /* 2^(-(1^2)) */
    assert_value("2*-3", 0.0, -6.0);
    assert_value("--2", 0.0, 2.0);
    assert_value("+3 - -3", 0.0, 6.0);
    assert_value("-t^2", 3.0, -9.0);
    assert_value("1 - 2*-t", 2.0, 5.0);
}

static void test_associativity_left_except_power(void)
{
    assert_value("10 - 4 - 3", 0.0, 3.0);
    assert_value("8/4/2", 0.0, 1.0);
    assert_value("2^3^2", 0.0, 512.0); /* 2^(3^2) */
    assert_value("(2^3)^2", 0.0, 64.0);
    assert_value("1 - 2 + 3", 0.0, 2.0);
    assert_value("12/2*3", 0.0, 18.0);
}

static void test_names_t_pi_and_e(void)
{
    assert_value("t", 1.25, 1.25);
    assert_value("pi", 0.0, PI);
    assert_value("e", 0.0, exp(1.0));
    assert_value("pi*t/2", 1.0, PI / 2.0);
    assert_value("e^t", 2.0, exp(2.0));
}

static void test_every_function_gives_its_value(void)
{
    assert_value("sin(t)", 0.7, sin(0.7));
    assert_value("cos(t)", 0.7, cos(0.7));
    assert_value("tan(t)", 0.7, tan(0.7));
    assert_value("asin(0.3)", 0.0, asin(0.3));
    assert_value("acos(0.3)", 0.0, acos(0.3));
    assert_value("atan(2)", 0.0, atan(2.0));
    assert_value("exp(t)", 1.5, exp(1.5));
    assert_value("log(t)", 1.5, log(1.5));
    assert_value("sqrt(16)", 0.0, 4.0);
    assert_value("abs(-3)", 0.0, 3.0);
    assert_value("floor(-1.5)", 0.0, -2.0);
    assert_value("ceil(-1.5)", 0.0, -1.0);
    assert_value("step(0)", 0.0, 1.0);
    assert_value("step(t)", -1e-9, 0.0);
    assert_value("step(t - 2)", 2.5, 1.0);
    assert_value("sign(-2)", 0.0, -1.0);
    assert_value("sign(0)", 0.0, 0.0);
    assert_value("sign(3)", 0.0, 1.0);
    assert_value("min(2, 3)", 0.0, 2.0);
    assert_value("max(2,3)", 0.0, 3.0);
    assert_value("max(min(t, 1), -1)", 5.0, 1.0);
    assert_value("max(min(t, 1), -1)", -5.0, -1.0);
    assert_value("sin (t) + cos( t )", 0.3, sin(0.3) + cos(0.3));
}

static void test_the_paper_signals_evaluate_as_written(void)
{
    for (double t = 0.0; t <= 30.0; t += 0.37) {
        assert_value("5 + 15*cos(pi*t/2)", t, 5.0 + 15.0 * cos(PI * t / 2.0));
        assert_value("20 - 120*sin(0.25*pi*t)", t, 20.0 - 120.0 * sin(0.25 * PI * t));
        assert_value("20 + 120*sin(3*t)", t, 20.0 + 120.0 * sin(3.0 * t));
    }
}

static void test_nan_propagates_through_every_function(void)
{
    assert_nan("step(0/0)");
    assert_nan("sign(sqrt(-1))");
    assert_nan("min(0/0, 1)");
    assert_nan("min(1, 0/0)");
    assert_nan("max(0/0, 1)");
    assert_nan("max(1, 0/0)");
    assert_nan("abs(0/0)");
    /* non-finite values are returned as they are */
    sim_expr_t e;
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&e, "log(t)", NULL));
    TEST_ASSERT_TRUE(isinf(sim_expr_eval(&e, 0.0)) && sim_expr_eval(&e, 0.0) < 0.0);
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&e, "1/t", NULL));
    TEST_ASSERT_TRUE(isinf(sim_expr_eval(&e, 0.0)));
}

static void test_constant_expressions_are_recognised(void)
{
    sim_expr_t e;
    double v = 0.0;
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&e, "2*pi", NULL));
    TEST_ASSERT_EQUAL_INT(1, sim_expr_is_constant(&e, &v));
    assert_close(2.0 * PI, v, "2*pi");
    TEST_ASSERT_EQUAL_INT(1, sim_expr_is_constant(&e, NULL));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&e, "sin(t)*0", NULL));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_is_constant(&e, &v));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&e, "t", NULL));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_is_constant(&e, &v));
}

static void test_a_failed_compile_leaves_a_program_that_gives_nan(void)
{
    sim_expr_t e;
    double v = 0.0;
    TEST_ASSERT_EQUAL_INT(-1, sim_expr_compile(&e, "1 +", NULL));
    TEST_ASSERT_TRUE(isnan(sim_expr_eval(&e, 0.0)));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_is_constant(&e, &v));
    sim_expr_error_t err;
    TEST_ASSERT_EQUAL_INT(-1, sim_expr_compile(NULL, "1", &err));
    TEST_ASSERT_EQUAL_INT(-1, sim_expr_compile(&e, NULL, &err));
}

static void test_syntax_errors_name_what_was_expected_and_where(void)
{
    assert_error("", 1, "expected a number, name or '('");
    assert_error("   ", 4, "expected a number, name or '('");
    assert_error("1 +", 4, "expected a number, name or '('");
    assert_error("1 + * 2", 5, "expected a number, name or '('");
    assert_error(")", 1, "expected a number, name or '('");
    assert_error("2 ^", 4, "expected a number, name or '('");
    assert_error("(1 + 2", 7, "expected ')'");
    assert_error("((t)", 5, "expected ')'");
    assert_error("1 2", 3, "trailing characters");
    assert_error("2x", 2, "trailing characters");
    assert_error("2e", 2, "trailing characters");
    assert_error("1.5.2", 4, "trailing characters");
    assert_error("(1))", 4, "trailing characters");
    assert_error("2 # comment", 3, "trailing characters");
    assert_error("1 .. 2", 3, "trailing characters");
    assert_error("max(1)", 6, "expected ','");
    assert_error("sin(1, 2)", 6, "expected ')'");
    assert_error("min(1, )", 8, "expected a number, name or '('");
}

static void test_name_errors_quote_the_name(void)
{
    assert_error("sn(t)", 1, "unknown function 'sn'");
    assert_error("1 + Sin(t)", 5, "unknown function 'Sin'");
    assert_error("e(1)", 1, "unknown function 'e'");
    assert_error("2*x", 3, "unknown name 'x'");
    assert_error("time", 1, "unknown name 'time'");
    assert_error("sin t", 5, "expected '(' after 'sin'");
    assert_error("max", 4, "expected '(' after 'max'");
    assert_error("abcdefghijabcdefghijabcdefghijabcdefghijXYZ", 1,
                 "unknown name 'abcdefghijabcdefghijabcdefghijabcdefghij'");
    assert_error("1e999", 1, "number out of range");
    assert_error("t + 1e999", 5, "number out of range");
}

static void test_program_and_stack_limits_are_errors_at_the_token_that_overflows(void)
{
    char text[512];
    /* t+t+...: n terms compile to 2n - 1 ops; 48 fit in 96, 49 do not */
    strcpy(text, "t");
    for (int i = 1; i < 48; ++i) {
        strcat(text, "+t");
    }
    sim_expr_t e;
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&e, text, NULL));
    TEST_ASSERT_EQUAL_INT(95, e.n_ops);
    assert_close(48.0 * 2.0, sim_expr_eval(&e, 2.0), "48 terms");
    strcat(text, "+t");
    /* op 97 is the 48th '+', emitted after its right operand: column 96 */
    assert_error(text, 96, "expression too long");

    /* 1+(1+(...(1+1)...)) with n "1+(": the innermost 1+1 stacks n + 2 values */
    text[0] = '\0';
    for (int i = 0; i < 30; ++i) {
        strcat(text, "1+(");
    }
    strcat(text, "1+1");
    for (int i = 0; i < 30; ++i) {
        strcat(text, ")");
    }
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&e, text, NULL));
    assert_close(32.0, sim_expr_eval(&e, 0.0), "32 values deep");
    text[0] = '\0';
    for (int i = 0; i < 31; ++i) {
        strcat(text, "1+(");
    }
    strcat(text, "1+1");
    for (int i = 0; i < 31; ++i) {
        strcat(text, ")");
    }
    /* the 33rd value is the last 1 */
    assert_error(text, 31 * 3 + 3, "expression too deeply nested");

    /* parentheses alone nest the parser, not the stack: 63 levels are fine */
    text[0] = '\0';
    for (int i = 0; i < 63; ++i) {
        strcat(text, "(");
    }
    strcat(text, "t");
    for (int i = 0; i < 63; ++i) {
        strcat(text, ")");
    }
    assert_value(text, 4.0, 4.0);
    text[0] = '\0';
    for (int i = 0; i < 200; ++i) {
        strcat(text, "(");
    }
    strcat(text, "t");
    assert_error(text, 65, "expression too deeply nested");
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Expressions covering every operator in every operand position (constant,
 * t, subexpression, on either side), foldable parts and NaN/inf results. */
static const char *const FOLDING_CORPUS[] = {
    "20 - 120*sin(3*t)",
    "20 + 120*sin(0.25*pi*t)",
    "5 + 15*cos(pi*t/2)",
    "10*cos(pi*t/2)",
    "8",
    "-t",
    "2^t",
    "t^2",
    "t^t",
    "2^3^2",
    "-2^2",
    "(1 + 2) * t",
    "t * (1 + 2)",
    "t / (2*pi)",
    "(2*pi) / t",
    "min(t, 1)",
    "min(1, t)",
    "max(t, 0.5)",
    "max(0.5, t)",
    "min(sin(t), cos(t))",
    "max(sin(t), 0/0)",
    "min(0/0, t)",
    "sin(t)*sin(t) + cos(t)*cos(t)",
    "(t + 1) - (t - 1)",
    "(t+1)/(t-1)",
    "(t*2)^(t/3)",
    "tan(t) + asin(t/40) + acos(t/40) + atan(t)",
    "exp(-t) * log(t + 1) + sqrt(t)",
    "abs(t - 3) + floor(t) + ceil(t)",
    "step(t - 2) + sign(t - 5) + step(0/0)",
    "1/t",
    "log(t)",
    "0/0",
    "sin(1) + t",
    "t + sin(1)",
    "-(t - 3)",
    "+t",
    "1 - (2 - (3 - (4 - t)))",
    "((t))",
    "max(min(t, 1), -1)",
    "2 - t - 3",
};

static void test_the_folded_program_gives_the_postfix_programs_bits(void)
{
    static const double times[] = {0.0, -0.0, 1e-3, 0.5, 2.0, 3.0, 6.000001, 12.5, 24.9999, 30.0, -4.25, 1e9};
    for (size_t k = 0; k < sizeof FOLDING_CORPUS / sizeof FOLDING_CORPUS[0]; ++k) {
        sim_expr_t e;
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_expr_compile(&e, FOLDING_CORPUS[k], NULL), FOLDING_CORPUS[k]);
        TEST_ASSERT_TRUE_MESSAGE(e.n_code > 0, FOLDING_CORPUS[k]);
        for (size_t j = 0; j < sizeof times / sizeof times[0]; ++j) {
            char message[160];
            const double want = sim_expr_eval_postfix(&e, times[j]);
            const double got = sim_expr_eval(&e, times[j]);
            snprintf(message, sizeof message, "'%s' at t = %g: postfix %.17g, evaluated %.17g", FOLDING_CORPUS[k],
                     times[j], want, got);
            TEST_ASSERT_TRUE_MESSAGE(same_bits(want, got), message);
        }
    }
}

static void test_constant_parts_are_folded_to_one_operand(void)
{
    sim_expr_t e;
    /* 20 - 120*sin(0.25*pi*t): 10 postfix ops; the folded form loads
     * 0.25*pi, multiplies by t, takes sin, then two constant operations */
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&e, "20 - 120*sin(0.25*pi*t)", NULL));
    TEST_ASSERT_EQUAL_INT(10, e.n_ops);
    TEST_ASSERT_EQUAL_INT(5, e.n_code);
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&e, "2*pi*sqrt(4)", NULL));
    TEST_ASSERT_EQUAL_INT(1, e.n_code);
    assert_close(4.0 * PI, sim_expr_eval(&e, 0.0), "folded constant");
}

static void test_a_memo_returns_the_bits_of_the_call_it_replaces(void)
{
    sim_expr_t a, b, c;
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&a, "20 - 120*sin(3*t)", NULL));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&b, "20 + 120*sin(3*t) + cos(t) + exp(t) + log(t) + atan(t)", NULL));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&c, "sin(t) + sin(-t) + sin(3*t)", NULL));
    static const double times[] = {0.0, -0.0, 0.7, 13.25};
    for (size_t j = 0; j < sizeof times / sizeof times[0]; ++j) {
        sim_expr_memo_t memo;
        sim_expr_memo_clear(&memo);
        const double t = times[j];
        /* b fills the memo past its size, so c's sin(3*t) may have been replaced */
        TEST_ASSERT_TRUE(same_bits(sim_expr_eval(&a, t), sim_expr_eval_memo(&a, t, &memo)));
        TEST_ASSERT_TRUE(same_bits(sim_expr_eval(&b, t), sim_expr_eval_memo(&b, t, &memo)));
        TEST_ASSERT_TRUE(same_bits(sim_expr_eval(&c, t), sim_expr_eval_memo(&c, t, &memo)));
        TEST_ASSERT_TRUE(same_bits(sim_expr_eval(&a, t), sim_expr_eval_memo(&a, t, &memo)));
        TEST_ASSERT_TRUE(memo.n == SIM_EXPR_MEMO_SIZE);
    }
    /* sin(-0) is -0 and sin(0) is 0: the memo tells them apart */
    sim_expr_t s;
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&s, "sin(t)", NULL));
    sim_expr_memo_t memo;
    sim_expr_memo_clear(&memo);
    TEST_ASSERT_TRUE(same_bits(0.0, sim_expr_eval_memo(&s, 0.0, &memo)));
    TEST_ASSERT_TRUE(same_bits(-0.0, sim_expr_eval_memo(&s, -0.0, &memo)));
}

/* Same bits, or both NaN: the evaluated forms may give NaN another sign or
 * payload (expr.h). */
static int same_value(double a, double b)
{
    return same_bits(a, b) || (isnan(a) && isnan(b));
}

static void test_a_batch_gives_each_instants_bits(void)
{
    /* every corpus expression on batches of 1, 5, 12 and the most instants,
     * with and without a memo shared by all of them (the disturbances of
     * three axes share theirs); signed zeros and a jump of the instants
     * included */
    double t[SIM_EXPR_BATCH_MAX];
    for (int k = 0; k < SIM_EXPR_BATCH_MAX; ++k) {
        t[k] = k == 0 ? -0.0 : (k == 1 ? 0.0 : (k < 20 ? 1.9999 + 1e-4 * k : -4.25 + 0.37 * k));
    }
    static const int sizes[] = {1, 5, 12, SIM_EXPR_BATCH_MAX};
    int checked = 0;
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; ++s) {
        const int n = sizes[s];
        sim_expr_batch_memo_t memo;
        sim_expr_batch_memo_clear(&memo);
        for (size_t e = 0; e < sizeof FOLDING_CORPUS / sizeof FOLDING_CORPUS[0]; ++e) {
            sim_expr_t x;
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_expr_compile(&x, FOLDING_CORPUS[e], NULL), FOLDING_CORPUS[e]);
            double plain[SIM_EXPR_BATCH_MAX], shared[SIM_EXPR_BATCH_MAX];
            sim_expr_eval_batch(&x, t, n, plain, NULL);
            sim_expr_eval_batch(&x, t, n, shared, &memo);
            for (int k = 0; k < n; ++k) {
                char message[200];
                const double want = sim_expr_eval(&x, t[k]);
                snprintf(message, sizeof message, "'%s' at t = %g of %d: one at a time %.17g, batch %.17g / %.17g",
                         FOLDING_CORPUS[e], t[k], n, want, plain[k], shared[k]);
                TEST_ASSERT_TRUE_MESSAGE(same_value(want, plain[k]) && same_value(want, shared[k]), message);
                ++checked;
            }
        }
    }
    TEST_ASSERT_EQUAL_INT(50 * (int)(sizeof FOLDING_CORPUS / sizeof FOLDING_CORPUS[0]), checked);
}

static void test_a_batch_memo_hits_only_on_the_same_arguments(void)
{
    sim_expr_t a, b;
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&a, "20 - 120*sin(3*t)", NULL));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&b, "20 + 120*sin(3*t)", NULL));
    const double t[3] = {0.0, 0.5, 1.0}, t_neg_zero[3] = {-0.0, 0.5, 1.0};
    sim_expr_batch_memo_t memo;
    sim_expr_batch_memo_clear(&memo);
    double out[3];
    sim_expr_eval_batch(&a, t, 3, out, &memo);
    TEST_ASSERT_EQUAL_INT(1, memo.n);
    sim_expr_eval_batch(&b, t, 3, out, &memo); /* a hit: sin of the same three arguments */
    TEST_ASSERT_EQUAL_INT(1, memo.n);
    TEST_ASSERT_TRUE(same_bits(sim_expr_eval(&b, 0.5), out[1]));
    sim_expr_eval_batch(&b, t, 2, out, &memo); /* fewer arguments: a new entry */
    TEST_ASSERT_EQUAL_INT(2, memo.n);
    sim_expr_t s;
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&s, "sin(t)", NULL));
    sim_expr_eval_batch(&s, t, 3, out, &memo);
    TEST_ASSERT_TRUE(same_bits(0.0, out[0]));
    sim_expr_eval_batch(&s, t_neg_zero, 3, out, &memo); /* -0 is another argument: sin(-0) = -0 */
    TEST_ASSERT_TRUE(same_bits(-0.0, out[0]));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_numbers_in_every_written_form);
    RUN_TEST(test_scan_number_stops_where_the_number_ends);
    RUN_TEST(test_precedence_follows_the_usual_math_convention);
    RUN_TEST(test_associativity_left_except_power);
    RUN_TEST(test_names_t_pi_and_e);
    RUN_TEST(test_every_function_gives_its_value);
    RUN_TEST(test_the_paper_signals_evaluate_as_written);
    RUN_TEST(test_nan_propagates_through_every_function);
    RUN_TEST(test_constant_expressions_are_recognised);
    RUN_TEST(test_a_failed_compile_leaves_a_program_that_gives_nan);
    RUN_TEST(test_syntax_errors_name_what_was_expected_and_where);
    RUN_TEST(test_name_errors_quote_the_name);
    RUN_TEST(test_program_and_stack_limits_are_errors_at_the_token_that_overflows);
    RUN_TEST(test_the_folded_program_gives_the_postfix_programs_bits);
    RUN_TEST(test_constant_parts_are_folded_to_one_operand);
    RUN_TEST(test_a_memo_returns_the_bits_of_the_call_it_replaces);
    RUN_TEST(test_a_batch_gives_each_instants_bits);
    RUN_TEST(test_a_batch_memo_hits_only_on_the_same_arguments);
    return UNITY_END();
}
