/* SPDX-License-Identifier: BSD-3-Clause */
/* Quaternion attitude: the rotation vector, the error with tilt priority, the
 * attitude layer's quaternion frame (validation, faults, agreement with the
 * Euler frame near level) and every variant through flips on a rigid body
 * with quaternion kinematics. */
#include "unity.h"
#include "ladrc/attitude.h"
#include "test_rigid_quat.h"

#include <math.h>
#include <stdio.h>

#define DT_S 1e-3
#define PI 3.14159265358979
#define DEG (PI / 180.0)
/* A few float products and an asin: rounding of some 1e-7 rad, relative
 * 1e-6; 1e-5 leaves a factor 10. */
#ifdef LADRC_REAL_DOUBLE
#define ROTVEC_TOL 1e-12
#else
#define ROTVEC_TOL 1e-5
#endif

/* Flips at the paper's gains: the largest error of any variant is 4.0 deg
 * (INDI), so 8 deg; a sign flip or a singularity sends it towards 180. A
 * second after the move every variant is within 0.46 deg (PID's slow
 * integral on yaw; the others below 0.03): 1 deg. */
#define FLIP_WORST_DEG 8.0
#define FLIP_FINAL_DEG 1.0
/* Near level the frames differ by the kinematics' second-order terms: the
 * Euler angles' error and the rotation vector part by |e|^2 / 2, 0.25 deg
 * for the 5.4 deg step below (measured: 0.15 at most). */
#define FRAMES_AGREE_DEG 0.25
#define FLIP_TD_ACCEL_RAD_S2 400.0
#define FLIP_RATE_MAX_DEG_S 720.0

static const ladrc_real_t inertia[3] = {5.445e-3f, 5.445e-3f, 1.089e-2f};
static const ladrc_real_t drag_Nms = 9e-2f;

void setUp(void)
{
}
void tearDown(void)
{
}

static ladrc_quat_t to_quat(const double q[4])
{
    ladrc_quat_t r = {(ladrc_real_t)q[0], (ladrc_real_t)q[1], (ladrc_real_t)q[2], (ladrc_real_t)q[3]};
    return r;
}

static ladrc_quat_t axis_angle(double ax, double ay, double az, double angle_rad)
{
    const double n = sqrt(ax * ax + ay * ay + az * az);
    const double s = sin(0.5 * angle_rad) / n;
    const double q[4] = {cos(0.5 * angle_rad), s * ax, s * ay, s * az};
    return to_quat(q);
}

static void test_rotvec_gives_axis_times_angle_at_every_angle(void)
{
    const double angles[] = {0.0, 1e-4, 0.05, 0.2, 1.0, 2.0, 2.9, 3.1, PI};
    for (unsigned a = 0; a < sizeof angles / sizeof angles[0]; ++a) {
        const double axis[3] = {0.36, -0.48, 0.8}; /* unit */
        ladrc_real_t v[3];
        ladrc_quat_rotvec(axis_angle(axis[0], axis[1], axis[2], angles[a]), v);
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_TRUE(fabs((double)v[i] - axis[i] * angles[a]) <= ROTVEC_TOL * (1.0 + angles[a]));
        }
        /* -q is the same rotation */
        ladrc_quat_t q = axis_angle(axis[0], axis[1], axis[2], angles[a]);
        const ladrc_quat_t neg = {-q.w, -q.x, -q.y, -q.z};
        ladrc_real_t vn[3];
        ladrc_quat_rotvec(neg, vn);
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_TRUE(fabs((double)vn[i] - (double)v[i]) <= ROTVEC_TOL * (1.0 + angles[a]));
        }
    }
}

static void test_from_euler_composes_z_y_x(void)
{
    const double roll = 0.3, pitch = 2.2, yaw = -1.4; /* pitch beyond 90 deg */
    double ref[4];
    test_quat_from_euler(roll, pitch, yaw, ref);
    const ladrc_quat_t q = ladrc_quat_from_euler((ladrc_real_t)roll, (ladrc_real_t)pitch, (ladrc_real_t)yaw);
    const double got[4] = {q.w, q.x, q.y, q.z};
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_TRUE(fabs(got[i] - ref[i]) <= ROTVEC_TOL);
    }
}

static void test_normalise_refuses_what_is_no_attitude(void)
{
    ladrc_quat_t u = {LADRC_R(9.0), LADRC_R(9.0), LADRC_R(9.0), LADRC_R(9.0)};
    const ladrc_quat_t scaled = {LADRC_R(2.0), LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    TEST_ASSERT_EQUAL_INT(1, ladrc_quat_normalise(scaled, &u));
    TEST_ASSERT_TRUE(fabs((double)u.w - 1.0) <= ROTVEC_TOL);
    const ladrc_quat_t zero = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    const ladrc_quat_t nan = {(ladrc_real_t)NAN, LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    const ladrc_quat_t inf = {LADRC_R(1.0), (ladrc_real_t)INFINITY, LADRC_R(0.0), LADRC_R(0.0)};
    TEST_ASSERT_EQUAL_INT(0, ladrc_quat_normalise(zero, &u));
    TEST_ASSERT_EQUAL_INT(0, ladrc_quat_normalise(nan, &u));
    TEST_ASSERT_EQUAL_INT(0, ladrc_quat_normalise(inf, &u));
    TEST_ASSERT_TRUE(fabs((double)u.w - 1.0) <= ROTVEC_TOL); /* untouched */
}

/* Largest |component| difference of two error vectors (rad). */
static double gap(const ladrc_real_t a[3], const double b[3])
{
    double m = 0.0;
    for (int i = 0; i < 3; ++i) {
        m = fmax(m, fabs((double)a[i] - b[i]));
    }
    return m;
}

static void test_tilt_error_near_level_is_the_per_axis_error(void)
{
    /* errors of up to 5 deg on every axis, from a level and from a tilted attitude */
    const double starts[2][3] = {{0.0, 0.0, 0.0}, {0.1, -0.05, 2.0}};
    const double errors[3][3] = {
        {2.0 * DEG, 0.0, 0.0}, {-1.0 * DEG, 3.0 * DEG, 0.5 * DEG}, {5 * DEG, -5 * DEG, 5 * DEG}};
    for (int s = 0; s < 2; ++s) {
        for (int k = 0; k < 3; ++k) {
            double q[4], qr[4], ref_err[3];
            test_quat_from_euler(starts[s][0], starts[s][1], starts[s][2], q);
            /* the reference: q rotated by the error in body axes */
            const ladrc_quat_t dq = axis_angle(
                errors[k][0], errors[k][1], errors[k][2],
                sqrt(errors[k][0] * errors[k][0] + errors[k][1] * errors[k][1] + errors[k][2] * errors[k][2]));
            const ladrc_quat_t ref = ladrc_quat_mul(to_quat(q), dq);
            qr[0] = ref.w, qr[1] = ref.x, qr[2] = ref.y, qr[3] = ref.z;
            test_quat_error(q, qr, ref_err);
            ladrc_real_t plain[3], weighted[3];
            ladrc_quat_tilt_error(to_quat(q), ref, LADRC_R(1.0), plain);
            ladrc_quat_tilt_error(to_quat(q), ref, LADRC_YAW_WEIGHT_DEFAULT, weighted);
            /* weight 1: the rotation vector itself */
            TEST_ASSERT_TRUE(gap(plain, ref_err) <= ROTVEC_TOL);
            /* weighted: the same to second order in the error, (1/k - 1) |e|^2 / 2 at
             * most (the swing-twist cross term), 0.6 mrad at 5 deg on all axes */
            const double e2 = ref_err[0] * ref_err[0] + ref_err[1] * ref_err[1] + ref_err[2] * ref_err[2];
            TEST_ASSERT_TRUE(gap(weighted, ref_err) <= (1.0 / 0.4 - 1.0) * 0.5 * e2 + ROTVEC_TOL);
        }
    }
}

/* Angle (rad) between the tilt parts (x, y) of two error vectors. */
static double tilt_direction_gap(const ladrc_real_t a[3], const ladrc_real_t b[3])
{
    const double dot = (double)a[0] * b[0] + (double)a[1] * b[1];
    const double cross = (double)a[0] * b[1] - (double)a[1] * b[0];
    return fabs(atan2(cross, dot));
}

static void test_tilt_error_serves_the_tilt_first(void)
{
    /* a tilt of 60 deg and a yaw of 150 deg at once, from 45 deg of roll */
    const ladrc_quat_t q = ladrc_quat_from_euler(LADRC_R(45.0) * (ladrc_real_t)DEG, 0, 0);
    const ladrc_quat_t ref =
        ladrc_quat_mul(q, ladrc_quat_mul(axis_angle(0, 0, 1, 150 * DEG), axis_angle(1, 1, 0, 60 * DEG)));
    ladrc_real_t plain[3], weighted[3], tilt_only[3];
    ladrc_quat_tilt_error(q, ref, LADRC_R(1.0), plain);
    ladrc_quat_tilt_error(q, ref, LADRC_YAW_WEIGHT_DEFAULT, weighted);
    ladrc_quat_tilt_error(q, ref, LADRC_R(1e-6), tilt_only); /* k -> 0: the swing alone */
    /* the plain rotation vector turns the tilt part away from the shortest
     * tilt; the weighted one points it at least twice as close */
    const double off_plain = tilt_direction_gap(plain, tilt_only);
    const double off_weighted = tilt_direction_gap(weighted, tilt_only);
    TEST_ASSERT_TRUE(off_plain > 10.0 * DEG);
    TEST_ASSERT_TRUE(off_weighted < 0.5 * off_plain);
    /* and the yaw still asks for the same sense of turn */
    TEST_ASSERT_TRUE(plain[2] * weighted[2] > 0.0f);
}

static void test_tilt_error_of_a_half_turn_is_finite(void)
{
    const ladrc_quat_t level = {LADRC_R(1.0), 0, 0, 0};
    const ladrc_real_t weights[2] = {LADRC_R(1.0), LADRC_YAW_WEIGHT_DEFAULT};
    for (int w = 0; w < 2; ++w) {
        ladrc_real_t e[3];
        ladrc_quat_tilt_error(level, axis_angle(1, 0, 0, PI), weights[w], e); /* upside down */
        TEST_ASSERT_TRUE(fabs(fabs((double)e[0]) - PI) <= ROTVEC_TOL * 10.0);
        TEST_ASSERT_TRUE(fabs((double)e[1]) <= ROTVEC_TOL && fabs((double)e[2]) <= ROTVEC_TOL);
        ladrc_quat_tilt_error(level, axis_angle(0, 0, 1, PI), weights[w], e); /* turned round */
        TEST_ASSERT_TRUE(fabs(fabs((double)e[2]) - PI) <= 0.1 * PI);          /* the weighted turn: within 10 % of pi */
        TEST_ASSERT_TRUE(fabs((double)e[0]) <= ROTVEC_TOL && fabs((double)e[1]) <= ROTVEC_TOL);
    }
}

static void make_config(ladrc_attitude_config_t *cfg, ladrc_variant_t variant)
{
    ladrc_attitude_config_default(cfg, variant, (ladrc_real_t)DT_S, inertia, drag_Nms);
    ladrc_attitude_config_quaternion(cfg);
}

static void test_init_checks_the_frame(void)
{
    ladrc_attitude_t att;
    ladrc_attitude_config_t cfg;
    int bad = 9;
    make_config(&cfg, LADRC_VARIANT_LADRC);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, &bad));
    cfg.frame = (ladrc_attitude_frame_t)2;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_ATTITUDE_FRAME, ladrc_attitude_init(&att, &cfg, &bad));
    TEST_ASSERT_EQUAL_INT(-1, bad);
    const ladrc_real_t weights[4] = {LADRC_R(0.0), LADRC_R(-0.5), LADRC_R(1.5), (ladrc_real_t)NAN};
    for (int w = 0; w < 4; ++w) {
        make_config(&cfg, LADRC_VARIANT_LADRC);
        cfg.yaw_weight = weights[w];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_YAW_WEIGHT, ladrc_attitude_init(&att, &cfg, &bad));
    }
    make_config(&cfg, LADRC_VARIANT_LADRC);
    cfg.axis[LADRC_PITCH].wrap_angle = 0u;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_WRAP_ANGLE, ladrc_attitude_init(&att, &cfg, &bad));
    TEST_ASSERT_EQUAL_INT(LADRC_PITCH, bad);
    /* the Euler frame reads neither */
    cfg.frame = LADRC_FRAME_EULER;
    cfg.yaw_weight = (ladrc_real_t)NAN;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, &bad));
}

static void test_each_step_refuses_the_other_frame(void)
{
    ladrc_attitude_t euler, quat;
    ladrc_attitude_config_t cfg;
    ladrc_attitude_config_default(&cfg, LADRC_VARIANT_LADRC, (ladrc_real_t)DT_S, inertia, drag_Nms);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&euler, &cfg, NULL));
    make_config(&cfg, LADRC_VARIANT_LADRC);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&quat, &cfg, NULL));
    const ladrc_real_t zero[3] = {0, 0, 0};
    const ladrc_quat_t level = {LADRC_R(1.0), 0, 0, 0};
    ladrc_real_t torque[3] = {LADRC_R(7.0), LADRC_R(7.0), LADRC_R(7.0)};
    TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_STATE, ladrc_attitude_step(&quat, zero, zero, NULL, torque));
    TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_STATE, ladrc_attitude_step_quat(&euler, &level, &level, NULL, torque));
    TEST_ASSERT_TRUE(torque[0] == LADRC_R(7.0)); /* nothing written */
}

static void test_bad_attitude_holds_every_axis(void)
{
    ladrc_attitude_t att;
    ladrc_attitude_config_t cfg;
    make_config(&cfg, LADRC_VARIANT_LADRC);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, NULL));
    const ladrc_quat_t level = {LADRC_R(1.0), 0, 0, 0};
    const ladrc_quat_t ref = ladrc_quat_from_euler(LADRC_R(0.1), LADRC_R(-0.1), LADRC_R(0.2));
    const ladrc_quat_t bad[3] = {
        {(ladrc_real_t)NAN, 0, 0, 0}, {0, 0, 0, 0}, {LADRC_R(1.0), (ladrc_real_t)INFINITY, 0, 0}};
    ladrc_real_t torque[3], held[3];
    for (int k = 0; k < 20; ++k) {
        TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_NONE, ladrc_attitude_step_quat(&att, &ref, &level, NULL, held));
    }
    for (int b = 0; b < 3; ++b) {
        TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_INPUT, ladrc_attitude_step_quat(&att, &ref, &bad[b], NULL, torque));
        TEST_ASSERT_EQUAL_FLOAT_ARRAY(held, torque, 3);
        TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_INPUT, ladrc_attitude_step_quat(&att, &bad[b], &level, NULL, torque));
        TEST_ASSERT_EQUAL_FLOAT_ARRAY(held, torque, 3);
    }
    /* a bad reference alone: the body angles still follow the attitude */
    const ladrc_quat_t rolled = ladrc_quat_from_euler(LADRC_R(0.01), 0, 0);
    TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_INPUT, ladrc_attitude_step_quat(&att, &bad[0], &rolled, NULL, torque));
    TEST_ASSERT_TRUE(fabs((double)att.body_angle_rad[LADRC_ROLL] - 0.01) <= ROTVEC_TOL);
    TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_NONE, ladrc_attitude_step_quat(&att, &ref, &rolled, NULL, torque));
}

/* One closed loop on the quaternion body: the reference from ref_at(t),
 * ZYX angles (rad); returns the largest error (rad) over the run and, in
 * *final_rad, over its last second; *faults the union of the flags. */
typedef void (*reference_fn)(double t_s, double euler_rad[3]);

static double fly(ladrc_variant_t variant, reference_fn ref_at, double duration_s, double *final_rad,
                  ladrc_fault_t *faults)
{
    ladrc_attitude_config_t cfg;
    make_config(&cfg, variant);
    for (int i = 0; i < 3; ++i) {
        /* the paper's TD bound, 20 rad/s^2, is a gentle manoeuvre's; a flip
         * peaks at 18 rad/s^2 and the TD, a time-optimal tracker, would lag it */
        cfg.axis[i].td_accel_rad_s2 = (ladrc_real_t)FLIP_TD_ACCEL_RAD_S2;
        /* the flip peaks at 340 deg/s, beyond PX4's default attitude-mode
         * bound (220 deg/s): a flip is flown at the acro bound */
        cfg.axis[i].cas_rate_max_rad_s = (ladrc_real_t)(FLIP_RATE_MAX_DEG_S * DEG);
        cfg.axis[i].radrc_rate_max_rad_s = (ladrc_real_t)(FLIP_RATE_MAX_DEG_S * DEG);
        /* a flip's trajectory gives its rate on every axis: CASCADED feeds it
         * forward as the others do (PX4's default feeds forward yaw only) */
        cfg.axis[i].cas_setpoint_ff = 1u;
    }
    ladrc_attitude_t att;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, NULL));
    test_rigid_quat_t body;
    test_rigid_quat_init(&body);
    const double none[3] = {0, 0, 0};
    double worst = 0.0;
    *final_rad = 0.0;
    *faults = LADRC_FAULT_NONE;
    const long n = (long)(duration_s / DT_S + 0.5);
    for (long k = 0; k < n; ++k) {
        const double t = (double)k * DT_S;
        double euler[3], qr[4], e[3];
        ref_at(t, euler);
        test_quat_from_euler(euler[0], euler[1], euler[2], qr);
        const ladrc_quat_t q_ref = to_quat(qr), q_meas = to_quat(body.q);
        const ladrc_real_t rate[3] = {(ladrc_real_t)body.body.rate_rad_s[0], (ladrc_real_t)body.body.rate_rad_s[1],
                                      (ladrc_real_t)body.body.rate_rad_s[2]};
        ladrc_real_t torque[3];
        *faults |= ladrc_attitude_step_quat(&att, &q_ref, &q_meas, rate, torque);
        const double tau[3] = {torque[0], torque[1], torque[2]};
        test_quat_error(body.q, qr, e);
        const double err = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        worst = fmax(worst, isfinite(err) ? err : INFINITY);
        if (t >= duration_s - 1.0) {
            *final_rad = fmax(*final_rad, err);
        }
        test_rigid_quat_step(&body, tau, none, DT_S, 4);
    }
    return worst;
}

/* A smooth move from 0 to 1 over [t0, t0 + 1 s] (its first three
 * derivatives continuous at both ends). */
static double smooth_move(double t_s, double t0_s)
{
    const double u = fmin(fmax(t_s - t0_s, 0.0), 1.0);
    return u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
}

static void roll_flip(double t_s, double e[3])
{
    e[0] = PI * smooth_move(t_s, 0.5), e[1] = 0.0, e[2] = 0.0;
}
static void pitch_flip(double t_s, double e[3])
{
    e[0] = 0.0, e[1] = PI * smooth_move(t_s, 0.5), e[2] = 0.0;
}
static void yaw_turn_at_60_pitch(double t_s, double e[3])
{
    e[0] = 0.0, e[1] = PI / 3.0 * smooth_move(t_s, 0.5), e[2] = PI * smooth_move(t_s, 2.5);
}

static void test_every_variant_flips_and_turns_through_any_attitude(void)
{
    const reference_fn moves[3] = {roll_flip, pitch_flip, yaw_turn_at_60_pitch};
    const char *names[3] = {"roll flip", "pitch flip", "yaw turn at 60 deg pitch"};
    for (int v = 0; v < LADRC_VARIANT_COUNT; ++v) {
        for (int m = 0; m < 3; ++m) {
            double final_rad;
            ladrc_fault_t faults;
            const double worst = fly((ladrc_variant_t)v, moves[m], 5.0, &final_rad, &faults);
            printf("variant %d %s: worst %.3f deg, last second %.4f deg\n", v, names[m], worst / DEG, final_rad / DEG);
            TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_NONE, faults);
            TEST_ASSERT_TRUE(worst <= FLIP_WORST_DEG * DEG);
            TEST_ASSERT_TRUE(final_rad <= FLIP_FINAL_DEG * DEG);
        }
    }
}

static void test_near_level_the_frames_agree(void)
{
    /* steps of a few degrees on every axis from level: the Euler frame on
     * the paper's kinematics and the quaternion frame on a rigid body give
     * the same error histories, but for the kinematics' second-order terms */
    for (int v = 0; v < LADRC_VARIANT_COUNT; ++v) {
        ladrc_attitude_config_t cfg;
        ladrc_attitude_t euler, quat;
        ladrc_attitude_config_default(&cfg, (ladrc_variant_t)v, (ladrc_real_t)DT_S, inertia, drag_Nms);
        TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&euler, &cfg, NULL));
        ladrc_attitude_config_quaternion(&cfg);
        TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&quat, &cfg, NULL));
        test_rigid_body_t flat;
        test_rigid_quat_t body;
        test_rigid_body_init(&flat);
        test_rigid_quat_init(&body);
        const double step_rad[3] = {3.0 * DEG, -2.0 * DEG, 4.0 * DEG};
        double qr[4];
        test_quat_from_euler(step_rad[0], step_rad[1], step_rad[2], qr);
        const ladrc_quat_t q_ref = to_quat(qr);
        const ladrc_real_t ref[3] = {(ladrc_real_t)step_rad[0], (ladrc_real_t)step_rad[1], (ladrc_real_t)step_rad[2]};
        const double none[3] = {0, 0, 0};
        double worst_gap = 0.0;
        for (int k = 0; k < 2000; ++k) {
            ladrc_real_t angle[3], rate_e[3], rate_q[3], te[3], tq[3];
            for (int i = 0; i < 3; ++i) {
                angle[i] = (ladrc_real_t)flat.angle_rad[i];
                rate_e[i] = (ladrc_real_t)flat.rate_rad_s[i];
                rate_q[i] = (ladrc_real_t)body.body.rate_rad_s[i];
            }
            const ladrc_quat_t q_meas = to_quat(body.q);
            TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_NONE, ladrc_attitude_step(&euler, ref, angle, rate_e, te));
            TEST_ASSERT_EQUAL_UINT8(LADRC_FAULT_NONE, ladrc_attitude_step_quat(&quat, &q_ref, &q_meas, rate_q, tq));
            double de[3], dq[3], eq[3];
            test_quat_error(body.q, qr, eq);
            for (int i = 0; i < 3; ++i) {
                worst_gap = fmax(worst_gap, fabs((step_rad[i] - flat.angle_rad[i]) - eq[i]));
                de[i] = te[i], dq[i] = tq[i];
            }
            test_rigid_body_step(&flat, de, none, DT_S, 4);
            test_rigid_quat_step(&body, dq, none, DT_S, 4);
        }
        printf("variant %d: error histories %.4f deg apart at most\n", v, worst_gap / DEG);
        TEST_ASSERT_TRUE(worst_gap <= FRAMES_AGREE_DEG * DEG);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_rotvec_gives_axis_times_angle_at_every_angle);
    RUN_TEST(test_from_euler_composes_z_y_x);
    RUN_TEST(test_normalise_refuses_what_is_no_attitude);
    RUN_TEST(test_tilt_error_near_level_is_the_per_axis_error);
    RUN_TEST(test_tilt_error_serves_the_tilt_first);
    RUN_TEST(test_tilt_error_of_a_half_turn_is_finite);
    RUN_TEST(test_init_checks_the_frame);
    RUN_TEST(test_each_step_refuses_the_other_frame);
    RUN_TEST(test_bad_attitude_holds_every_axis);
    RUN_TEST(test_near_level_the_frames_agree);
    RUN_TEST(test_every_variant_flips_and_turns_through_any_attitude);
    return UNITY_END();
}
