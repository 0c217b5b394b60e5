/* SPDX-License-Identifier: BSD-3-Clause */
/* Config property campaign: random and boundary configs for each init (every
 * field drawn near its default, or from the hostile classes: huge finite,
 * denormal, zero, NaN, +-inf, negative; enums and counts one beyond either
 * end). Every config an init accepts must then run on nominal inputs with
 * finite outputs and without refusing a single update (no fault flag): an
 * accepted config is a usable one.
 * LADRC_CONFIG_CASES sets the configs per init (default 10^5) and
 * LADRC_CONFIG_TICKS the ticks each accepted one runs (default 200: of the
 * findings that shaped the inits, all but one showed within 30 ticks, the
 * other at tick 582; the long form runs 10^4). */
#include "unity.h"
#include "test_axis_command.h"
#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/estimator.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/leso.h"
#include "ladrc/levant.h"
#include "ladrc/rls.h"
#include "test_hostile.h"
#include "test_plant.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#ifdef LADRC_TEST_ON_TARGET
#define DEFAULT_CASES 2000L
#define DEFAULT_TICKS 200L
#else
#define DEFAULT_CASES 100000L
#define DEFAULT_TICKS 200L
#endif
#define SEED UINT64_C(0xc0f16)

typedef struct {
    long tried, accepted, violations;
} tally_t;

static long from_env(const char *name, long fallback)
{
    const char *s = getenv(name);
    const long n = (s != NULL) ? atol(s) : 0L;
    return (n > 0L) ? n : fallback;
}

static long cases(void)
{
    return from_env("LADRC_CONFIG_CASES", DEFAULT_CASES);
}
static long ticks(void)
{
    return from_env("LADRC_CONFIG_TICKS", DEFAULT_TICKS);
}

/* A field: its default a tenth of the time, within 1.5 decades of it half
 * the time, otherwise a hostile value. */
static ladrc_real_t field(test_rng_t *rng, double nominal)
{
    const double u = test_rng_uniform(rng);
    if (u < 0.1) {
        return (ladrc_real_t)nominal;
    }
    if (u < 0.6) {
        return (ladrc_real_t)(nominal * pow(10.0, 3.0 * test_rng_uniform(rng) - 1.5));
    }
    const test_value_class_t cls = (test_value_class_t)test_rng_below(rng, (unsigned)TEST_VALUE_CLASSES);
    return test_value_of_class(rng, cls, fabs(nominal) + 1e-3);
}

/* Mostly `nominal`, sometimes anything in [-1, top + 1]. */
static int small_int(test_rng_t *rng, int nominal, int top)
{
    return (test_rng_uniform(rng) < 0.7) ? nominal : (int)test_rng_below(rng, (unsigned)(top + 3)) - 1;
}

static void violation(tally_t *t, const char *init, const char *what, long tick)
{
    if (t->violations < 10) {
        printf("violation: %s config %ld, tick %ld: %s\n", init, t->tried, tick, what);
    }
    t->violations++;
}

/* A nominal motion inside the config's ranges: amplitude a rad at 2 rad/s
 * (rate 2 a, acceleration 4 a), within half the angle range, a quarter of
 * the rate range and a tenth of the acceleration the command can give. */
static double amplitude(const ladrc_axis_config_t *c)
{
    const double authority_Nm = fmin(fmin(-(double)c->u_min_Nm, (double)c->u_max_Nm), (double)c->applied_limit_Nm);
    const double accel = !ladrc_variant_has_observer(c->variant) ? INFINITY : authority_Nm * fabs((double)c->b0);
    return fmin(fmin(0.3, 0.5 * (double)c->angle_limit_rad), fmin(0.25 * (double)c->rate_limit_rad_s, accel / 40.0));
}

static void draw_axis(test_rng_t *rng, ladrc_axis_config_t *c, ladrc_variant_t v)
{
    const double dt = (test_rng_uniform(rng) < 0.5) ? 0.001 : (double)field(rng, 0.001);
    const double j = (test_rng_uniform(rng) < 0.5) ? 5.445e-3 : (double)field(rng, 5.445e-3);
    ladrc_axis_config_default(c, v, (ladrc_real_t)dt, (ladrc_real_t)j);
    ladrc_real_t *const reals[] = {&c->u_min_Nm,
                                   &c->u_max_Nm,
                                   &c->angle_limit_rad,
                                   &c->rate_limit_rad_s,
                                   &c->applied_limit_Nm,
                                   &c->wc_rad_s,
                                   &c->wo_rad_s,
                                   &c->b0,
                                   &c->td_accel_rad_s2,
                                   &c->td_h0_s,
                                   &c->levant_lipschitz_rad_s4,
                                   &c->pid_kp,
                                   &c->pid_ki,
                                   &c->pid_kd,
                                   &c->pid_d_filter_tau_s,
                                   &c->pid_i_limit_Nm,
                                   &c->lp_lambda0_per_s,
                                   &c->lp_k0_per_s,
                                   &c->hp_freq_rad_s[0],
                                   &c->hp_freq_rad_s[LADRC_HP_MAX_TONES - 1],
                                   &c->hp_freq_min_rad_s,
                                   &c->hp_freq_max_rad_s,
                                   &c->hp_lambda0_per_s,
                                   &c->hp_freq_lambda0_per_s,
                                   &c->hp_freq_filter_rad_s,
                                   &c->indi_att_kp_per_s,
                                   &c->indi_rate_kp_per_s,
                                   &c->indi_filter_rad_s,
                                   &c->cas_att_kp,
                                   &c->cas_rate_max_rad_s,
                                   &c->cas_rate_kp,
                                   &c->cas_rate_ki,
                                   &c->cas_rate_kd,
                                   &c->cas_d_filter_tau_s,
                                   &c->cas_i_limit_Nm,
                                   &c->cas_rate_filter_tau_s};
    const size_t n = sizeof reals / sizeof reals[0];
    /* a few fields off their defaults per config, so that some pass */
    const unsigned changes = 1u + test_rng_below(rng, 4u);
    for (unsigned k = 0; k < changes; ++k) {
        ladrc_real_t *f = reals[test_rng_below(rng, (unsigned)n)];
        const double nominal = isfinite((double)*f) && *f != LADRC_R(0.0) ? (double)*f : 1.0;
        *f = field(rng, nominal);
    }
    if (c->u_min_Nm > LADRC_R(0.0) && test_rng_uniform(rng) < 0.5) {
        c->u_min_Nm = -c->u_min_Nm;
    }
    c->leso_method = (ladrc_leso_method_t)small_int(rng, (int)c->leso_method, 1);
    c->shaper = (ladrc_shaper_t)small_int(rng, (int)c->shaper, 2);
    c->levant_method = (ladrc_levant_method_t)small_int(rng, (int)c->levant_method, 2);
    c->hp_freq_mode = (ladrc_hp_freq_mode_t)small_int(rng, (int)c->hp_freq_mode, 1);
    c->hp_n_tones = (uint8_t)small_int(rng, (int)c->hp_n_tones, LADRC_HP_MAX_TONES);
    c->hp_fit_decimation = (uint16_t)small_int(rng, (int)c->hp_fit_decimation, 8);
    c->hp_sample = (ladrc_hp_sample_t)small_int(rng, (int)c->hp_sample, 1); /* observer, gyro, or beyond */
}

/* One accepted axis config on nominal inputs inside its ranges: an ADRC
 * variant flies a plant its model matches exactly (y'' = b0 u, a slow
 * reference a sin(2 t)); PID, which knows no plant, follows the motion open
 * loop (its output cannot feed back into a model it does not have), and so
 * does CASCADED (its gains, drawn apart, need not close a stable loop). */
static void run_axis(tally_t *t, const char *name, ladrc_axis_t *axis, const ladrc_axis_config_t *c, long n)
{
    const double a = amplitude(c);
    const double dt = (double)c->dt_s;
    const int closed = ladrc_variant_has_observer(c->variant);
    test_double_integrator_t plant;
    test_plant_init(&plant, (double)c->b0, NULL, NULL);
    for (long k = 0; k < n; ++k) {
        const double time_s = (double)k * dt;
        const ladrc_real_t ref = (ladrc_real_t)(a * sin(2.0 * time_s));
        const ladrc_real_t angle = (ladrc_real_t)(closed ? plant.y_rad : a * sin(2.0 * time_s - 0.1));
        const ladrc_real_t rate = (ladrc_real_t)(closed ? plant.rate_rad_s : 2.0 * a * cos(2.0 * time_s - 0.1));
        const ladrc_real_t u = axis_command_with_rate(axis, ref, angle, rate);
        if (!test_is_finite(u)) {
            violation(t, name, "command not finite", k);
            return;
        }
        if (ladrc_axis_get_faults(axis) != LADRC_FAULT_NONE) {
            violation(t, name, "an update refused (fault flag)", k);
            return;
        }
        test_plant_step(&plant, (double)u, dt, 1);
    }
}

static void report(const char *name, tally_t t)
{
    printf("config: %-22s %ld configs, %ld accepted, %ld ticks each, %ld violations\n", name, t.tried, t.accepted,
           ticks(), t.violations);
    TEST_ASSERT_EQUAL_INT(0, (int)t.violations);
    TEST_ASSERT_TRUE(t.accepted > t.tried / 100); /* the campaign reaches the accepting side */
}

static void axis_campaign(ladrc_variant_t v, const char *name)
{
    tally_t t = {0};
    test_rng_t rng = {.state = SEED + (uint64_t)v};
    static ladrc_axis_t axis;
    const long n = cases();
    for (t.tried = 0; t.tried < n; ++t.tried) {
        ladrc_axis_config_t c;
        draw_axis(&rng, &c, v);
        if (ladrc_axis_init(&axis, &c) == LADRC_OK) {
            t.accepted++;
            run_axis(&t, name, &axis, &c, ticks());
        }
    }
    report(name, t);
}

static void test_axis_ladrc_configs(void)
{
    axis_campaign(LADRC_VARIANT_LADRC, "axis LADRC");
}
static void test_axis_lp_configs(void)
{
    axis_campaign(LADRC_VARIANT_LP_MLADRC, "axis LP-MLADRC");
}
static void test_axis_hp_configs(void)
{
    axis_campaign(LADRC_VARIANT_HP_MLADRC, "axis HP-MLADRC");
}
static void test_axis_pid_configs(void)
{
    axis_campaign(LADRC_VARIANT_PID, "axis PID");
}
static void test_axis_indi_configs(void)
{
    axis_campaign(LADRC_VARIANT_INDI, "axis INDI");
}
static void test_axis_cascaded_configs(void)
{
    axis_campaign(LADRC_VARIANT_CASCADED, "axis CASCADED");
}

static void run_attitude(tally_t *t, ladrc_attitude_t *att, const ladrc_attitude_config_t *c, long n)
{
    const double a = amplitude(&c->axis[0]);
    for (long k = 0; k < n; ++k) {
        const double time_s = (double)k * (double)c->axis[0].dt_s;
        ladrc_real_t ref[3], angle[3], rate[3], torque[3];
        for (int i = 0; i < 3; ++i) {
            const double phase = 0.1 + 0.5 * i; /* the axes move together: the coupling feed works */
            ref[i] = (ladrc_real_t)(a * sin(2.0 * time_s + phase));
            angle[i] = (ladrc_real_t)(a * sin(2.0 * time_s + phase - 0.1));
            rate[i] = (ladrc_real_t)(2.0 * a * cos(2.0 * time_s + phase - 0.1));
        }
        const ladrc_fault_t f = ladrc_attitude_step(att, ref, angle, rate, torque);
        if (!(test_is_finite(torque[0]) && test_is_finite(torque[1]) && test_is_finite(torque[2]))) {
            violation(t, "attitude", "torque not finite", k);
            return;
        }
        if (f != LADRC_FAULT_NONE) {
            violation(t, "attitude", "an update refused (fault flag)", k);
            return;
        }
    }
}

/* The attitude layer's own fields: step, inertias, drag, the coupling feed
 * (the axis campaigns cover the axes' fields). */
static void test_attitude_configs(void)
{
    tally_t t = {0};
    test_rng_t rng = {.state = SEED + 100u};
    static ladrc_attitude_t att;
    const long n = cases();
    for (t.tried = 0; t.tried < n; ++t.tried) {
        ladrc_attitude_config_t c;
        ladrc_real_t j[3];
        for (int i = 0; i < 3; ++i) {
            j[i] = (test_rng_uniform(&rng) < 0.3) ? (ladrc_real_t)5.445e-3 : field(&rng, 5.445e-3);
        }
        const ladrc_variant_t v = (ladrc_variant_t)test_rng_below(&rng, (unsigned)LADRC_VARIANT_COUNT);
        const ladrc_real_t dt = (test_rng_uniform(&rng) < 0.5) ? LADRC_R(0.001) : field(&rng, 0.001);
        ladrc_attitude_config_default(&c, v, dt, j, field(&rng, 0.09));
        c.coupling_feed = (uint8_t)small_int(&rng, 1, 1);
        if (ladrc_attitude_init(&att, &c, NULL) == LADRC_OK) {
            t.accepted++;
            run_attitude(&t, &att, &c, ticks());
        }
    }
    report("attitude", t);
}

/* The gyro filter on nominal inputs: every channel a sinusoid within +-1, the rotors sweeping
 * smoothly over the whole band (0 to 0.5 / dt_s, a few per mille of it per tick). */
static void run_gyro_filter(tally_t *t, ladrc_gyro_filter_t *f, const ladrc_gyro_filter_config_t *c, long n)
{
    const double nyquist_hz = 0.5 / (double)c->dt_s;
    for (long k = 0; k < n; ++k) {
        const double time_s = (double)k * (double)c->dt_s;
        ladrc_real_t in[LADRC_GYRO_FILTER_MAX_CHANNELS], out[LADRC_GYRO_FILTER_MAX_CHANNELS];
        ladrc_real_t rotor_hz[LADRC_GYRO_FILTER_MAX_ROTORS];
        for (unsigned r = 0; r < LADRC_GYRO_FILTER_MAX_ROTORS; ++r) {
            rotor_hz[r] = (ladrc_real_t)(nyquist_hz * (0.5 + 0.5 * sin(0.01 * (double)k + r)));
        }
        for (unsigned i = 0; i < LADRC_GYRO_FILTER_MAX_CHANNELS; ++i) {
            in[i] = (ladrc_real_t)sin(0.3 * (double)k + i + 5.0 * time_s);
        }
        if (ladrc_gyro_filter_set_rotor_hz(f, rotor_hz) != LADRC_FAULT_NONE) {
            violation(t, "gyro filter", "a rotor speed refused (fault flag)", k);
            return;
        }
        const ladrc_fault_t flags = ladrc_gyro_filter_step(f, in, out);
        for (unsigned i = 0; i < c->channels; ++i) {
            if (!test_is_finite(out[i])) {
                violation(t, "gyro filter", "output not finite", k);
                return;
            }
        }
        if (flags != LADRC_FAULT_NONE) {
            violation(t, "gyro filter", "an update refused (fault flag)", k);
            return;
        }
    }
}

/* A gyro filter field: half the time its nominal value (eleven fields drawn as the others are
 * would leave too few configs accepted), else as field() draws it. */
static ladrc_real_t gyro_field(test_rng_t *rng, double nominal)
{
    return (test_rng_uniform(rng) < 0.5) ? (ladrc_real_t)nominal : field(rng, nominal);
}

/* The gyro filter's fields around a 1 kHz loop with every stage on. A twentieth of the configs of
 * the other campaigns: a tick of six channels of 37 sections costs as much as twenty axis ticks. */
static void test_gyro_filter_configs(void)
{
    tally_t t = {0};
    test_rng_t rng = {.state = SEED + 200u};
    static ladrc_gyro_filter_t f;
    const long n = cases() / 20L;
    for (t.tried = 0; t.tried < n; ++t.tried) {
        ladrc_gyro_filter_config_t c;
        const ladrc_real_t dt = gyro_field(&rng, 0.001);
        ladrc_gyro_filter_config_default(&c, dt, (uint8_t)small_int(&rng, 3, 6));
        c.lpf_order = (uint8_t)small_int(&rng, 2, 2);
        c.lpf_cutoff_hz = gyro_field(&rng, 150.0);
        c.n_notches = (uint8_t)small_int(&rng, 2, 4);
        for (unsigned i = 0; i < LADRC_GYRO_FILTER_MAX_NOTCHES; ++i) {
            c.notch_hz[i] = gyro_field(&rng, 60.0 + 50.0 * i);
        }
        c.notch_q = gyro_field(&rng, 5.0);
        c.rpm_rotors = (uint8_t)small_int(&rng, 4, 8);
        c.rpm_harmonics = (uint8_t)small_int(&rng, 3, 4);
        c.rpm_q = gyro_field(&rng, 5.0);
        c.rpm_min_hz = gyro_field(&rng, 80.0);
        c.rpm_fade_hz = gyro_field(&rng, 40.0);
        if (ladrc_gyro_filter_init(&f, &c) == LADRC_OK) {
            t.accepted++;
            run_gyro_filter(&t, &f, &c, ticks());
        }
    }
    report("gyro filter", t);
}

void setUp(void)
{
}
void tearDown(void)
{
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_axis_ladrc_configs);
    RUN_TEST(test_axis_lp_configs);
    RUN_TEST(test_axis_hp_configs);
    RUN_TEST(test_axis_pid_configs);
    RUN_TEST(test_axis_indi_configs);
    RUN_TEST(test_axis_cascaded_configs);
    RUN_TEST(test_attitude_configs);
    RUN_TEST(test_gyro_filter_configs);
    return UNITY_END();
}
