/* SPDX-License-Identifier: BSD-3-Clause */
#include "plant.h"
#include "rotation.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

/* The lane kernels below are inlined with their widths as constants. */
#if defined(__GNUC__)
#define SIM_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SIM_ALWAYS_INLINE inline
#endif

/* RK4 state: angles, rates, rotor w^2 (these four only move with a lag),
 * the attitude quaternion (only integrated for a rigid body). */
enum { N_ANGLE = 0, N_RATE = 3, N_ROTOR = 6, N_QUAT = 10, N_STATE = 14 };

void sim_vehicle_paper(sim_vehicle_t *v)
{
    v->mass_kg = 0.8;
    v->inertia_kg_m2[0] = 5.445e-3;
    v->inertia_kg_m2[1] = 5.445e-3;
    v->inertia_kg_m2[2] = 1.089e-2;
    v->arm_m = 0.165;
    v->thrust_coeff_N_s2 = 2.98e-5;
    v->yaw_coeff_Nm_s2 = 2e-6;
    v->rot_drag_Nm_s = 9e-2;
    v->g_m_s2 = 9.81;
    v->rotors_ideal = 1;
    v->w2_min_rad2_s2 = 0.0;
    v->w2_max_rad2_s2 = HUGE_VAL;
    v->motor_tau_s = 0.0;
    v->motor_tau_down_s = 0.0;
    v->battery_life_s = 0.0;
    v->battery_drop = 0.0;
    v->rotor_drag_N_s_m = 0.0;
    v->rotor_height_m = 0.0;
    v->rigid_body = 0;
}

static double clamp_rotor(const sim_vehicle_t *v, double w2)
{
    if (v->rotors_ideal) {
        return w2;
    }
    if (w2 < v->w2_min_rad2_s2) {
        return v->w2_min_rad2_s2;
    }
    if (w2 > v->w2_max_rad2_s2) {
        return v->w2_max_rad2_s2;
    }
    return w2; /* NaN stays NaN: a bad command shows in the state */
}

void sim_plant_init(sim_plant_t *p, const sim_vehicle_t *v)
{
    p->v = *v;
    p->t_s = 0.0;
    for (int i = 0; i < 3; ++i) {
        p->angle_rad[i] = 0.0;
        p->rate_rad_s[i] = 0.0;
    }
    p->quat[0] = 1.0;
    p->quat[1] = p->quat[2] = p->quat[3] = 0.0;
    const double hover = sim_hover_w2_rad2_s2(v->mass_kg, v->g_m_s2, v->thrust_coeff_N_s2);
    for (int i = 0; i < 4; ++i) {
        p->w2_rad2_s2[i] = clamp_rotor(v, hover);
    }
}

void sim_plant_attitude(const sim_plant_t *p, double q[4])
{
    if (p->v.rigid_body) {
        for (int i = 0; i < 4; ++i) {
            q[i] = p->quat[i];
        }
    } else {
        sim_quat_from_euler(p->angle_rad, q);
    }
}

void sim_plant_hold(sim_plant_t *p, const double angle_rad[3])
{
    for (int i = 0; i < 3; ++i) {
        p->angle_rad[i] = angle_rad[i];
        p->rate_rad_s[i] = 0.0;
    }
    sim_quat_from_euler(angle_rad, p->quat);
}

void sim_plant_forces(const sim_vehicle_t *v, const double w2[4], double *thrust_N, double torque_Nm[3])
{
    const double kl = v->thrust_coeff_N_s2;
    if (thrust_N != NULL) {
        *thrust_N = kl * (w2[0] + w2[1] + w2[2] + w2[3]);
    }
    torque_Nm[0] = v->arm_m * kl * (w2[1] - w2[3]);
    torque_Nm[1] = v->arm_m * kl * (w2[2] - w2[0]);
    torque_Nm[2] = v->yaw_coeff_Nm_s2 * (-w2[0] + w2[1] - w2[2] + w2[3]);
}

double sim_plant_battery_factor(const sim_vehicle_t *v, double t_s)
{
    if (!(v->battery_life_s > 0.0)) {
        return 1.0;
    }
    const double drawn = t_s < v->battery_life_s ? (t_s > 0.0 ? t_s / v->battery_life_s : 0.0) : 1.0;
    const double volts = 1.0 - v->battery_drop * drawn; /* of the full pack's */
    return volts * volts;
}

/* Rows of R^T (world north-east-down into body axes) for roll, pitch, yaw
 * (ZYX): body = m world. */
static void world_to_body_rows(const double angle_rad[3], double m[3][3])
{
    const double cf = cos(angle_rad[0]), sf = sin(angle_rad[0]);
    const double ct = cos(angle_rad[1]), st = sin(angle_rad[1]);
    const double cp = cos(angle_rad[2]), sp = sin(angle_rad[2]);
    m[0][0] = ct * cp;
    m[0][1] = ct * sp;
    m[0][2] = -st;
    m[1][0] = -cf * sp + sf * st * cp;
    m[1][1] = cf * cp + sf * st * sp;
    m[1][2] = sf * ct;
    m[2][0] = sf * sp + cf * st * cp;
    m[2][1] = -sf * cp + cf * st * sp;
    m[2][2] = cf * ct;
}

void sim_plant_wind_to_body(const double angle_rad[3], const double wind_m_s[3], double body_m_s[3])
{
    double m[3][3];
    world_to_body_rows(angle_rad, m);
    for (int i = 0; i < 3; ++i) {
        body_m_s[i] = m[i][0] * wind_m_s[0] + m[i][1] * wind_m_s[1] + m[i][2] * wind_m_s[2];
    }
}

/* The wind law of the header on rotor speeds w (rad/s) and the air's
 * in-plane body velocity (vx, vy): the one formula of the rotor drag. */
static inline void drag_torque(const sim_vehicle_t *v, const double w[4], double vx, double vy, double torque[3])
{
    const double kd = v->rotor_drag_N_s_m, h = v->rotor_height_m;
    const double sum = w[0] + w[1] + w[2] + w[3];
    torque[0] = h * kd * vy * sum;
    torque[1] = -h * kd * vx * sum;
    torque[2] = kd * v->arm_m * ((w[2] - w[0]) * vy + (w[1] - w[3]) * vx);
}

/* Rotor speed (rad/s) of a w^2; a negative w^2 (ideal rotors) turns backwards. */
static inline double rotor_speed(double w2)
{
    return w2 >= 0.0 ? sqrt(w2) : -sqrt(-w2);
}

void sim_plant_wind_torque(const sim_vehicle_t *v, const double w2[4], const double wind_body_m_s[3],
                           double torque_Nm[3])
{
    const double w[4] = {rotor_speed(w2[0]), rotor_speed(w2[1]), rotor_speed(w2[2]), rotor_speed(w2[3])};
    drag_torque(v, w, wind_body_m_s[0], wind_body_m_s[1], torque_Nm);
}

/* Angular acceleration of one axis (eq. 2): own torque, the gyroscopic term
 * jd * ra * rb of the other two rates, drag on the own rate, then the
 * disturbance. The one formula of the plant's dynamics. */
static inline double axis_accel(double torque, double jd, double ra, double rb, double kt, double rate, double j,
                                double dist)
{
    return (torque + jd * ra * rb - kt * rate) / j + dist;
}

static inline void body_accel(const sim_vehicle_t *v, const double rate[3], const double torque[3],
                              const double dist[3], double accel[3])
{
    const double *j = v->inertia_kg_m2;
    const double kt = v->rot_drag_Nm_s;
    accel[0] = axis_accel(torque[0], j[1] - j[2], rate[1], rate[2], kt, rate[0], j[0], dist[0]);
    accel[1] = axis_accel(torque[1], j[2] - j[0], rate[0], rate[2], kt, rate[1], j[1], dist[1]);
    accel[2] = axis_accel(torque[2], j[0] - j[1], rate[1], rate[0], kt, rate[2], j[2], dist[2]);
}

void sim_plant_accel(const sim_plant_t *p, const double torque_Nm[3], const double dist[3], double accel_out[3])
{
    static const double none[3] = {0.0, 0.0, 0.0};
    body_accel(&p->v, p->rate_rad_s, torque_Nm, dist != NULL ? dist : none, accel_out);
}

/* The plants of a group side by side: each state variable a row, one plant
 * per column (lane), so that every step of the RK4 loops over the plants
 * innermost and the CPU works on their independent chains at once. Each
 * lane's arithmetic is that of a plant stepped alone, in the same order. */
typedef double lanes_t[SIM_PLANT_GROUP_MAX];

/* The air of a stage: its velocity over the ground at the stage time, and
 * each lane's rows x and y of R^T at the step's start (NULL wind: still air). */
typedef struct {
    const double *wind_m_s;
    lanes_t (*rows)[3];
} air_t;

/* dx/dt of every lane for the held (clamped) command and the disturbance d
 * at the stage time (the same for all lanes). Without lag the torque is the
 * command's, worked out once per step; with it, the rotors' w^2 are state
 * and the torque follows them, with the lag of spin-up or spin-down. */
static SIM_ALWAYS_INLINE void derivative(const sim_vehicle_t *v, int lag, int rigid, int n, lanes_t cmd[4],
                                         lanes_t cmd_torque[3], lanes_t x[N_STATE], const double d[3], const air_t *air,
                                         lanes_t dx[N_STATE])
{
    const double tau_up = v->motor_tau_s;
    const double tau_down = v->motor_tau_down_s > 0.0 ? v->motor_tau_down_s : tau_up;
    for (int l = 0; l < n; ++l) {
        double torque[3], rate[3], accel[3];
        if (lag) {
            const double w2[4] = {x[N_ROTOR][l], x[N_ROTOR + 1][l], x[N_ROTOR + 2][l], x[N_ROTOR + 3][l]};
            sim_plant_forces(v, w2, NULL, torque);
            for (int i = 0; i < 4; ++i) {
                const double gap = cmd[i][l] - x[N_ROTOR + i][l];
                dx[N_ROTOR + i][l] = gap / (gap >= 0.0 ? tau_up : tau_down);
            }
        } else {
            for (int i = 0; i < 3; ++i) {
                torque[i] = cmd_torque[i][l];
            }
            for (int i = 0; rigid && i < 4; ++i) {
                dx[N_ROTOR + i][l] = 0.0; /* integrated along with the quaternion, unmoved */
            }
        }
        if (air->wind_m_s != NULL) {
            const double *wd = air->wind_m_s;
            const double vx = air->rows[0][0][l] * wd[0] + air->rows[0][1][l] * wd[1] + air->rows[0][2][l] * wd[2];
            const double vy = air->rows[1][0][l] * wd[0] + air->rows[1][1][l] * wd[1] + air->rows[1][2][l] * wd[2];
            double w[4], drag[3];
            for (int i = 0; i < 4; ++i) {
                w[i] = rotor_speed(lag ? x[N_ROTOR + i][l] : cmd[i][l]);
            }
            drag_torque(v, w, vx, vy, drag);
            for (int i = 0; i < 3; ++i) {
                torque[i] += drag[i];
            }
        }
        for (int i = 0; i < 3; ++i) {
            rate[i] = x[N_RATE + i][l];
            dx[N_ANGLE + i][l] = rate[i];
        }
        body_accel(v, rate, torque, d, accel);
        for (int i = 0; i < 3; ++i) {
            dx[N_RATE + i][l] = accel[i];
        }
        if (rigid) {
            const double q[4] = {x[N_QUAT][l], x[N_QUAT + 1][l], x[N_QUAT + 2][l], x[N_QUAT + 3][l]};
            const double half_rate[4] = {0.0, 0.5 * rate[0], 0.5 * rate[1], 0.5 * rate[2]};
            double dq[4];
            sim_quat_mul(q, half_rate, dq);
            for (int i = 0; i < 4; ++i) {
                dx[N_QUAT + i][l] = dq[i];
            }
        }
    }
}

/* Where a step's disturbances come from: a table by stage (3 per substep,
 * in the order sim_plant_stage_times lists their times), else a call at the
 * stage time, else none. */
typedef struct {
    const double (*table)[3];
    const double (*wind)[3]; /* by stage as table; NULL: still air */
    sim_disturbance_fn dist;
    void *ctx;
} source_t;

/* The disturbance at stage `stage` (0: t, 1: t + h/2, 2: t + h) of substep
 * s, whose time is t. */
static SIM_ALWAYS_INLINE void disturbance_at(const source_t *src, int s, int stage, double t, double d[3])
{
    if (src->table != NULL) {
        const double *row = src->table[3 * s + stage];
        d[0] = row[0];
        d[1] = row[1];
        d[2] = row[2];
    } else if (src->dist != NULL) {
        src->dist(t, src->ctx, d);
    } else {
        d[0] = d[1] = d[2] = 0.0;
    }
}

/* The RK4 step length of a plant step: dt_s over substeps (at least 1). */
static int substep_count(int substeps)
{
    return substeps < 1 ? 1 : substeps;
}

/* Stage time `stage` (0: t, 1: t + h/2, 2: t + h) of substep s of a step
 * from t0 with RK4 steps of length h: stage times from t0 each substep, no
 * drift from summing h. The one formula of the stage times the plant asks
 * the disturbance at, and of the list sim_plant_stage_times gives. */
static double stage_time(double t0, double h, int s, int stage)
{
    const double t = t0 + s * h;
    return stage == 0 ? t : (stage == 1 ? t + 0.5 * h : t + h);
}

/* y = x + a k for the first m state rows of every lane (an RK4 stage's point). */
static SIM_ALWAYS_INLINE void stage_point(int m, int n, lanes_t x[N_STATE], double a, lanes_t k[N_STATE],
                                          lanes_t y[N_STATE])
{
    for (int i = 0; i < m; ++i) {
        for (int l = 0; l < n; ++l) {
            y[i][l] = x[i][l] + a * k[i][l];
        }
    }
}

/* One classical RK4 step of length h from time t0 + s h for every lane; the
 * rotor states only take part with a lag (without one their derivative is 0
 * and they stay put). */
static SIM_ALWAYS_INLINE void rk4_substep(const sim_vehicle_t *v, int lag, int rigid, int n, lanes_t cmd[4],
                                          lanes_t cmd_torque[3], lanes_t rows[2][3], double t0, int s, double h,
                                          const source_t *src, lanes_t x[N_STATE])
{
    const int m = rigid ? N_STATE : (lag ? N_QUAT : N_ROTOR);
    lanes_t k1[N_STATE], k2[N_STATE], k3[N_STATE], k4[N_STATE], y[N_STATE];
    double d[3];
    air_t air = {.wind_m_s = NULL, .rows = rows};
    disturbance_at(src, s, 0, stage_time(t0, h, s, 0), d);
    air.wind_m_s = src->wind != NULL ? src->wind[3 * s] : NULL;
    derivative(v, lag, rigid, n, cmd, cmd_torque, x, d, &air, k1);
    stage_point(m, n, x, 0.5 * h, k1, y);
    disturbance_at(src, s, 1, stage_time(t0, h, s, 1), d); /* the same for k2 and k3 */
    air.wind_m_s = src->wind != NULL ? src->wind[3 * s + 1] : NULL;
    derivative(v, lag, rigid, n, cmd, cmd_torque, y, d, &air, k2);
    stage_point(m, n, x, 0.5 * h, k2, y);
    derivative(v, lag, rigid, n, cmd, cmd_torque, y, d, &air, k3);
    stage_point(m, n, x, h, k3, y);
    disturbance_at(src, s, 2, stage_time(t0, h, s, 2), d);
    air.wind_m_s = src->wind != NULL ? src->wind[3 * s + 2] : NULL;
    derivative(v, lag, rigid, n, cmd, cmd_torque, y, d, &air, k4);
    const double h6 = h / 6.0;
    for (int i = 0; i < m; ++i) {
        for (int l = 0; l < n; ++l) {
            x[i][l] += h6 * (k1[i][l] + 2.0 * k2[i][l] + 2.0 * k3[i][l] + k4[i][l]);
        }
    }
}

/* The substeps of a step for lanes [0, w); lag and w are constants where it
 * is called. */
static SIM_ALWAYS_INLINE void integrate(const sim_vehicle_t *v, int lag, int rigid, int w, lanes_t cmd[4],
                                        lanes_t cmd_torque[3], lanes_t rows[2][3], int n_sub, double t0, double h,
                                        const source_t *src, lanes_t x[N_STATE])
{
    for (int s = 0; s < n_sub; ++s) {
        rk4_substep(v, lag, rigid, w, cmd, cmd_torque, rows, t0, s, h, src, x);
        for (int l = 0; rigid && l < w; ++l) { /* back to unit norm after each substep */
            double n2 = 0.0;
            for (int i = 0; i < 4; ++i) {
                n2 += x[N_QUAT + i][l] * x[N_QUAT + i][l];
            }
            const double inv = 1.0 / sqrt(n2);
            for (int i = 0; i < 4; ++i) {
                x[N_QUAT + i][l] *= inv;
            }
        }
    }
}

/* integrate() for w lanes (1, 2, 4, 6 or SIM_PLANT_GROUP_MAX), each width
 * and lag its own code. */
static SIM_ALWAYS_INLINE void integrate_width(const sim_vehicle_t *v, int lag, int w, lanes_t cmd[4],
                                              lanes_t cmd_torque[3], lanes_t rows[2][3], int n_sub, double t0, double h,
                                              const source_t *src, lanes_t x[N_STATE])
{
#define LANES_CASE(W)                                                                                                  \
    case W:                                                                                                            \
        if (v->rigid_body) {                                                                                           \
            integrate(v, lag, 1, W, cmd, cmd_torque, rows, n_sub, t0, h, src, x);                                      \
        } else if (lag) {                                                                                              \
            integrate(v, 1, 0, W, cmd, cmd_torque, rows, n_sub, t0, h, src, x);                                        \
        } else {                                                                                                       \
            integrate(v, 0, 0, W, cmd, cmd_torque, rows, n_sub, t0, h, src, x);                                        \
        }                                                                                                              \
        break;
    switch (w) {
        LANES_CASE(1)
        LANES_CASE(2)
        LANES_CASE(4)
        LANES_CASE(6)
    default:
        LANES_CASE(SIM_PLANT_GROUP_MAX)
    }
#undef LANES_CASE
}

static void integrate_portable(const sim_vehicle_t *v, int lag, int w, lanes_t cmd[4], lanes_t cmd_torque[3],
                               lanes_t rows[2][3], int n_sub, double t0, double h, const source_t *src,
                               lanes_t x[N_STATE])
{
    integrate_width(v, lag, w, cmd, cmd_torque, rows, n_sub, t0, h, src, x);
}

/* On x86-64 the build targets SSE2 (two lanes per instruction); where the
 * CPU has AVX the same code compiled for it runs four. The operations are
 * IEEE additions, multiplications and divisions either way, lane by lane,
 * in the same order, and AVX brings no fused multiply-add (that is FMA, not
 * enabled here, and contraction is off under -std=c99): the same bits. */
#if defined(__GNUC__) && defined(__x86_64__)
#define SIM_PLANT_AVX 1
__attribute__((target("avx"))) static void integrate_avx(const sim_vehicle_t *v, int lag, int w, lanes_t cmd[4],
                                                         lanes_t cmd_torque[3], lanes_t rows[2][3], int n_sub,
                                                         double t0, double h, const source_t *src, lanes_t x[N_STATE])
{
    integrate_width(v, lag, w, cmd, cmd_torque, rows, n_sub, t0, h, src, x);
}
#endif

/* Steps plants[0..n) (n <= SIM_PLANT_GROUP_MAX), all at p0's time with its
 * vehicle, in lockstep: one dist call per stage time for all. */
static void step_lanes(sim_plant_t *const plants[], const double (*w2_cmd)[4], int n, double dt_s, int substeps,
                       const source_t *src)
{
    const sim_vehicle_t *v = &plants[0]->v;
    const int n_sub = substep_count(substeps);
    const double h = dt_s / n_sub;
    const double t0 = plants[0]->t_s;
    const int lag = v->motor_tau_s > 0.0;
    const double battery = sim_plant_battery_factor(v, t0);
    lanes_t cmd[4], cmd_torque[3], x[N_STATE], rows[2][3];
    for (int l = 0; l < n; ++l) {
        const sim_plant_t *p = plants[l];
        double c[4], torque[3];
        if (src->wind != NULL) {
            double m[3][3];
            world_to_body_rows(p->angle_rad, m);
            for (int i = 0; i < 2; ++i) {
                for (int j = 0; j < 3; ++j) {
                    rows[i][j][l] = m[i][j];
                }
            }
        }
        for (int i = 0; i < 4; ++i) {
            c[i] = clamp_rotor(v, w2_cmd[l][i]) * battery;
            cmd[i][l] = c[i];
            x[N_ROTOR + i][l] = p->w2_rad2_s2[i];
        }
        sim_plant_forces(v, c, NULL, torque);
        for (int i = 0; i < 3; ++i) {
            cmd_torque[i][l] = torque[i];
            x[N_ANGLE + i][l] = p->angle_rad[i];
            x[N_RATE + i][l] = p->rate_rad_s[i];
        }
        for (int i = 0; i < 4; ++i) {
            x[N_QUAT + i][l] = p->quat[i];
        }
    }
    /* The loops over the lanes run over a width known at compile time (the
     * next of 1, 2, 4, 6, 8), so that they unroll; lanes beyond n repeat
     * lane 0, their results unused. */
    const int w = n <= 2 ? n : (n <= 4 ? 4 : (n <= 6 ? 6 : SIM_PLANT_GROUP_MAX));
    for (int l = n; l < w; ++l) {
        for (int i = 0; i < 4; ++i) {
            cmd[i][l] = cmd[i][0];
        }
        for (int i = 0; i < 3; ++i) {
            cmd_torque[i][l] = cmd_torque[i][0];
        }
        for (int i = 0; i < N_STATE; ++i) {
            x[i][l] = x[i][0];
        }
        for (int i = 0; src->wind != NULL && i < 2; ++i) {
            for (int j = 0; j < 3; ++j) {
                rows[i][j][l] = rows[i][j][0];
            }
        }
    }
#ifdef SIM_PLANT_AVX
    if (__builtin_cpu_supports("avx")) {
        integrate_avx(v, lag, w, cmd, cmd_torque, rows, n_sub, t0, h, src, x);
    } else
#endif
    {
        integrate_portable(v, lag, w, cmd, cmd_torque, rows, n_sub, t0, h, src, x);
    }
    for (int l = 0; l < n; ++l) {
        sim_plant_t *p = plants[l];
        for (int i = 0; i < 3; ++i) {
            p->rate_rad_s[i] = x[N_RATE + i][l];
        }
        if (v->rigid_body) {
            for (int i = 0; i < 4; ++i) {
                p->quat[i] = x[N_QUAT + i][l];
            }
            const double previous[3] = {p->angle_rad[0], p->angle_rad[1], p->angle_rad[2]};
            sim_quat_to_euler(p->quat, previous, p->angle_rad);
        } else {
            for (int i = 0; i < 3; ++i) {
                p->angle_rad[i] = x[N_ANGLE + i][l];
            }
        }
        for (int i = 0; i < 4; ++i) {
            p->w2_rad2_s2[i] = lag ? x[N_ROTOR + i][l] : cmd[i][l];
        }
        p->t_s = t0 + dt_s;
    }
}

/* The same bits (==, but -0 and 0 told apart: clamping returns the limit itself). */
static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Vehicles that give the same arithmetic: plants that can share a group's
 * constants. */
static int same_vehicle(const sim_vehicle_t *a, const sim_vehicle_t *b)
{
    return same_bits(a->mass_kg, b->mass_kg) && same_bits(a->inertia_kg_m2[0], b->inertia_kg_m2[0]) &&
           same_bits(a->inertia_kg_m2[1], b->inertia_kg_m2[1]) && same_bits(a->inertia_kg_m2[2], b->inertia_kg_m2[2]) &&
           same_bits(a->arm_m, b->arm_m) && same_bits(a->thrust_coeff_N_s2, b->thrust_coeff_N_s2) &&
           same_bits(a->yaw_coeff_Nm_s2, b->yaw_coeff_Nm_s2) && same_bits(a->rot_drag_Nm_s, b->rot_drag_Nm_s) &&
           same_bits(a->g_m_s2, b->g_m_s2) && a->rotors_ideal == b->rotors_ideal &&
           same_bits(a->w2_min_rad2_s2, b->w2_min_rad2_s2) && same_bits(a->w2_max_rad2_s2, b->w2_max_rad2_s2) &&
           same_bits(a->motor_tau_s, b->motor_tau_s) && same_bits(a->motor_tau_down_s, b->motor_tau_down_s) &&
           same_bits(a->battery_life_s, b->battery_life_s) && same_bits(a->battery_drop, b->battery_drop) &&
           same_bits(a->rotor_drag_N_s_m, b->rotor_drag_N_s_m) && same_bits(a->rotor_height_m, b->rotor_height_m) &&
           a->rigid_body == b->rigid_body;
}

void sim_plant_step(sim_plant_t *p, const double w2_cmd[4], double dt_s, int substeps, sim_disturbance_fn dist,
                    void *ctx)
{
    if (!(dt_s > 0.0)) {
        return;
    }
    sim_plant_t *const one[1] = {p};
    const double cmd[1][4] = {{w2_cmd[0], w2_cmd[1], w2_cmd[2], w2_cmd[3]}};
    const source_t src = {.table = NULL, .wind = NULL, .dist = dist, .ctx = ctx};
    step_lanes(one, cmd, 1, dt_s, substeps, &src);
}

/* The group step of both public forms: plants at plants[0]'s time with its
 * vehicle side by side, then those with another vehicle alone, each with
 * src; those at another time alone with `other` when it is given (not
 * stepped otherwise). Returns the number stepped. */
static int step_group(sim_plant_t *const plants[], const double (*w2_cmd)[4], int n, double dt_s, int substeps,
                      const source_t *src, const source_t *other)
{
    if (!(dt_s > 0.0) || n < 1) {
        return 0;
    }
    const sim_plant_t *lead = plants[0];
    const double t_lead = lead->t_s; /* the lead's time before the step */
    sim_plant_t *lanes[SIM_PLANT_GROUP_MAX] = {NULL};
    double cmd[SIM_PLANT_GROUP_MAX][4];
    int n_lanes = 0;
    for (int g = 0; g < n; ++g) {
        if (g == 0 || (n_lanes < SIM_PLANT_GROUP_MAX && same_bits(plants[g]->t_s, t_lead) &&
                       same_vehicle(&plants[g]->v, &lead->v))) {
            lanes[n_lanes] = plants[g];
            for (int i = 0; i < 4; ++i) {
                cmd[n_lanes][i] = w2_cmd[g][i];
            }
            ++n_lanes;
        }
    }
    step_lanes(lanes, (const double(*)[4])cmd, n_lanes, dt_s, substeps, src);
    int stepped = n_lanes;
    for (int g = 0, l = 0; g < n; ++g) { /* the others, each alone, after the group */
        if (l < n_lanes && plants[g] == lanes[l]) {
            ++l;
            continue;
        }
        const source_t *own = same_bits(plants[g]->t_s, t_lead) ? src : other;
        if (own != NULL) {
            sim_plant_t *const one[1] = {plants[g]};
            step_lanes(one, &w2_cmd[g], 1, dt_s, substeps, own);
            ++stepped;
        }
    }
    return stepped;
}

void sim_plant_step_group(sim_plant_t *const plants[], const double (*w2_cmd)[4], int n, double dt_s, int substeps,
                          sim_disturbance_fn dist, void *ctx)
{
    const source_t src = {.table = NULL, .wind = NULL, .dist = dist, .ctx = ctx};
    (void)step_group(plants, w2_cmd, n, dt_s, substeps, &src, &src);
}

int sim_plant_step_group_table(sim_plant_t *const plants[], const double (*w2_cmd)[4], int n, double dt_s, int substeps,
                               const double (*d_stage)[3])
{
    return sim_plant_step_group_air(plants, w2_cmd, n, dt_s, substeps, d_stage, NULL);
}

int sim_plant_step_group_air(sim_plant_t *const plants[], const double (*w2_cmd)[4], int n, double dt_s, int substeps,
                             const double (*d_stage)[3], const double (*wind_stage)[3])
{
    const source_t src = {.table = d_stage, .wind = wind_stage, .dist = NULL, .ctx = NULL};
    return step_group(plants, w2_cmd, n, dt_s, substeps, &src, NULL);
}

int sim_plant_stage_times(const sim_plant_t *p, double dt_s, int substeps, double *times_out)
{
    if (!(dt_s > 0.0)) {
        return 0;
    }
    const int n = substep_count(substeps);
    const double h = dt_s / n;
    int k = 0;
    for (int s = 0; s < n; ++s) {
        for (int stage = 0; stage < 3; ++stage) {
            times_out[k++] = stage_time(p->t_s, h, s, stage);
        }
    }
    return k;
}
