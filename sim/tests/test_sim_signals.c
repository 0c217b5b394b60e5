/* SPDX-License-Identifier: BSD-3-Clause */
/* Signals (signals.h): pieces over (from, to] windows as a scenario gives
 * them, the first piece that holds t, the scale; a batch of instants. */
#include "unity.h"
#include "scenario_cases.h"

static void test_signal_windows_hold_from_exclusive_to_inclusive(void)
{
    parse_ok("[run]\nduration_s = 30\n[disturbance]\n"
             "roll = 2 .. 6 : 8\n"
             "roll = 6 .. 12 : 20 - t\n"
             "roll = 25 .. : 1\n");
    const sim_signal_t *d = &sc.disturbance[0];
    TEST_ASSERT_EQUAL_INT(3, d->n_pieces);
    assert_close(0.0, sim_signal_eval(d, 0.0), "before");
    assert_close(0.0, sim_signal_eval(d, 2.0), "at from: outside");
    assert_close(8.0, sim_signal_eval(d, nextafter(2.0, 3.0)), "just after from");
    assert_close(8.0, sim_signal_eval(d, 6.0), "at to: inside");
    assert_close(20.0 - nextafter(6.0, 7.0), sim_signal_eval(d, nextafter(6.0, 7.0)), "next piece");
    assert_close(8.0, sim_signal_eval(d, 12.0), "12 is the second piece's end");
    assert_close(0.0, sim_signal_eval(d, nextafter(12.0, 13.0)), "gap");
    assert_close(0.0, sim_signal_eval(d, 25.0), "unbounded piece starts after 25");
    assert_close(1.0, sim_signal_eval(d, 1e9), "unbounded above");
    TEST_ASSERT_TRUE(isinf(d->to_s[2]) && d->to_s[2] > 0.0);
    assert_close(2.0, d->from_s[0], "first piece's start");
}

static void test_signal_eval_takes_the_first_piece_that_holds_t_and_scales_it(void)
{
    static sim_signal_t sig;
    memset(&sig, 0, sizeof sig);
    sig.scale = 2.0;
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&sig.expr[0], "1", NULL));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&sig.expr[1], "t", NULL));
    sig.from_s[0] = 0.0;
    sig.to_s[0] = 1.0;
    sig.from_s[1] = -INFINITY;
    sig.to_s[1] = INFINITY;
    sig.n_pieces = 2;
    assert_close(2.0, sim_signal_eval(&sig, 0.5), "first piece");
    assert_close(2.0, sim_signal_eval(&sig, 1.0), "first piece at its end");
    assert_close(0.0, sim_signal_eval(&sig, 0.0), "second piece at 0: t");
    assert_close(-6.0, sim_signal_eval(&sig, -3.0), "second piece");
    sig.n_pieces = 0;
    assert_close(0.0, sim_signal_eval(&sig, 0.5), "no pieces");
}

/* A batch gives each instant sim_signal_eval's value bit for bit: all in
 * one piece, across piece ends and gaps, in none, with a NaN instant. */
static void test_signal_batch_is_each_instant_bit_for_bit(void)
{
    parse_ok("[run]\nduration_s = 30\n[disturbance]\n"
             "roll = 2 .. 6 : 8 + sin(3*t)\n"
             "roll = 6 .. 12 : 20 - 120*sin(0.25*t)\n"
             "roll = 25 .. : 1\n");
    const sim_signal_t *d = &sc.disturbance[0];
    static const double starts[] = {2.5, 5.9, 11.99, 13.0, 24.99, 100.0, -1.0};
    for (size_t s = 0; s < sizeof starts / sizeof starts[0]; ++s) {
        double t[SIM_EXPR_BATCH_MAX], out[SIM_EXPR_BATCH_MAX], lo, hi;
        for (int k = 0; k < SIM_EXPR_BATCH_MAX; ++k) {
            t[k] = starts[s] + 0.001 * k;
        }
        if (s == 0) {
            t[7] = NAN; /* the range is NaN: instant by instant */
        }
        sim_signal_batch_range(t, SIM_EXPR_BATCH_MAX, &lo, &hi);
        sim_signal_eval_batch(d, t, SIM_EXPR_BATCH_MAX, lo, hi, out, NULL);
        for (int k = 0; k < SIM_EXPR_BATCH_MAX; ++k) {
            const double want = sim_signal_eval(d, t[k]);
            char what[80];
            snprintf(what, sizeof what, "batch from %g, instant %d", starts[s], k);
            TEST_ASSERT_TRUE_MESSAGE(memcmp(&want, &out[k], sizeof want) == 0, what);
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_signal_windows_hold_from_exclusive_to_inclusive);
    RUN_TEST(test_signal_eval_takes_the_first_piece_that_holds_t_and_scales_it);
    RUN_TEST(test_signal_batch_is_each_instant_bit_for_bit);
    return UNITY_END();
}
