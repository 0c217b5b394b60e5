/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * libFuzzer target: the expression compiler (sim/scenario/expr.c) on arbitrary text
 * (the input up to its first NUL byte). Besides what the sanitizers catch,
 * it checks that:
 * - a refused text has its error inside the text (1 <= column <= length + 1,
 *   a message) and leaves a program that evaluates to NaN;
 * - an accepted text gives programs within their arrays' sizes, and the same
 *   programs when compiled again;
 * - at every time of TIMES, the evaluated form (constants folded, the
 *   accumulator code of sim_expr_eval) gives the value of the unfolded
 *   postfix program (sim_expr_eval_postfix), bit for bit; the memo
 *   (sim_expr_eval_memo) gives the bits of the plain evaluation; and a
 *   constant expression (sim_expr_is_constant) has its value at every t.
 *
 * NaN results: two NaNs count as the same value whatever their sign and
 * payload bits. C and IEEE 754 leave both unspecified for a NaN computed
 * from NaN operands (which operand's payload an addition passes on depends
 * on operand order, and a compiler may swap the operands of + and *), and
 * nothing in the simulator reads them: the metrics test isnan(), and the
 * time series print NaN as "nan" or "-nan" from the result of the one
 * evaluation that runs (sim_expr_eval). Every other result, infinities and
 * the sign of zero included, must match bit for bit (memcmp).
 * Built with -DFUZZ_STRICT_NAN, NaNs must match bit for bit too.
 */
#include "fuzz.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenario/expr.h"

/* Scenario times and the edges of double. */
static const double TIMES[] = {
    0.0,  -0.0,  1e-3, 0.5,   1.0,    2.0,    3.0,     2.5,      6.0,      12.5,      25.0,
    30.0, -4.25, 1e9,  1e300, -1e300, 1e-310, DBL_MAX, -DBL_MAX, INFINITY, -INFINITY, 3.14159265358979323846};

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static int same_value(double a, double b)
{
#if defined(FUZZ_STRICT_NAN)
    return same_bits(a, b);
#else
    return same_bits(a, b) || (isnan(a) && isnan(b));
#endif
}

static char *text_of(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (text != NULL) {
        memcpy(text, data, size);
        text[size] = '\0';
    }
    return text;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = text_of(data, size);
    if (text == NULL) {
        return 0;
    }
    const size_t len = strlen(text);
    static sim_expr_t e, again;
    sim_expr_error_t err;
    const int rc = sim_expr_compile(&e, text, &err);
    FUZZ_CHECK(rc == 0 || rc == -1, "rc %d", rc);
    if (rc != 0) {
        FUZZ_CHECK(err.column >= 1 && (size_t)err.column <= len + 1, "column %d of %zu characters", err.column, len);
        FUZZ_CHECK(err.message[0] != '\0', "no message at column %d", err.column);
        FUZZ_CHECK(memchr(err.message, '\0', sizeof err.message) != NULL, "message not terminated");
        FUZZ_CHECK(isnan(sim_expr_eval(&e, 1.0)) && isnan(sim_expr_eval_postfix(&e, 1.0)),
                   "a failed compile must leave a program that gives NaN");
        free(text);
        return 0;
    }
    FUZZ_CHECK(e.n_ops >= 1 && e.n_ops <= SIM_EXPR_MAX_OPS, "n_ops %d", e.n_ops);
    FUZZ_CHECK(e.n_code >= 1 && e.n_code <= (int)(sizeof e.code), "n_code %d", e.n_code);

    FUZZ_CHECK(sim_expr_compile(&again, text, NULL) == 0, "a second compile failed");
    FUZZ_CHECK(again.n_ops == e.n_ops && again.n_code == e.n_code && memcmp(again.op, e.op, (size_t)e.n_ops) == 0 &&
                   memcmp(again.value, e.value, (size_t)e.n_ops * sizeof e.value[0]) == 0 &&
                   memcmp(again.code, e.code, (size_t)e.n_code) == 0 &&
                   memcmp(again.operand, e.operand, (size_t)e.n_code * sizeof e.operand[0]) == 0,
               "a second compile gave other programs");

    double constant = 0.0;
    const int is_constant = sim_expr_is_constant(&e, &constant);
    sim_expr_memo_t memo; /* shared by all the times: entries of other times must not answer */
    sim_expr_memo_clear(&memo);
    for (size_t i = 0; i < sizeof TIMES / sizeof TIMES[0]; ++i) {
        const double t = TIMES[i];
        const double folded = sim_expr_eval(&e, t);
        const double postfix = sim_expr_eval_postfix(&e, t);
        const double memoized = sim_expr_eval_memo(&e, t, &memo);
        FUZZ_CHECK(same_value(folded, postfix), "'%s' at t = %.17g: folded %.17g, postfix %.17g", text, t, folded,
                   postfix);
        FUZZ_CHECK(same_bits(folded, memoized), "'%s' at t = %.17g: plain %.17g, with the memo %.17g", text, t, folded,
                   memoized);
        if (is_constant) {
            FUZZ_CHECK(same_value(constant, folded), "'%s' constant %.17g, at t = %.17g %.17g", text, constant, t,
                       folded);
        }
    }
    free(text);
    return 0;
}
