/* SPDX-License-Identifier: BSD-3-Clause */
#include "plant.h"

#include <math.h>
#include <stddef.h>

/* RK4 state: angles, rates, rotor w^2 (the last four only move with a lag). */
enum { N_ANGLE = 0, N_RATE = 3, N_ROTOR = 6, N_STATE = 10 };

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
    return w2;  /* NaN stays NaN: a bad command shows in the state */
}

void sim_plant_init(sim_plant_t *p, const sim_vehicle_t *v)
{
    p->v = *v;
    p->t_s = 0.0;
    for (int i = 0; i < 3; ++i) {
        p->angle_rad[i] = 0.0;
        p->rate_rad_s[i] = 0.0;
    }
    const double hover = v->mass_kg * v->g_m_s2 / (4.0 * v->thrust_coeff_N_s2);
    for (int i = 0; i < 4; ++i) {
        p->w2_rad2_s2[i] = clamp_rotor(v, hover);
    }
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

static void body_accel(const sim_vehicle_t *v, const double rate[3], const double torque[3],
                       const double dist[3], double accel[3])
{
    const double *j = v->inertia_kg_m2;
    const double kt = v->rot_drag_Nm_s;
    accel[0] = (torque[0] + (j[1] - j[2]) * rate[1] * rate[2] - kt * rate[0]) / j[0] + dist[0];
    accel[1] = (torque[1] + (j[2] - j[0]) * rate[0] * rate[2] - kt * rate[1]) / j[1] + dist[1];
    accel[2] = (torque[2] + (j[0] - j[1]) * rate[1] * rate[0] - kt * rate[2]) / j[2] + dist[2];
}

void sim_plant_accel(const sim_plant_t *p, const double torque_Nm[3], const double dist[3],
                     double accel_out[3])
{
    static const double none[3] = {0.0, 0.0, 0.0};
    body_accel(&p->v, p->rate_rad_s, torque_Nm, dist != NULL ? dist : none, accel_out);
}

/* dx/dt for the held (clamped) command and the disturbance d at the stage
 * time. Without lag the torque is the command's, worked out once per step;
 * with it, the rotors' w^2 are state and the torque follows them. */
static void derivative(const sim_vehicle_t *v, int lag, const double cmd[4], const double cmd_torque[3],
                       const double x[N_STATE], const double d[3], double dx[N_STATE])
{
    double lag_torque[3];
    const double *torque = cmd_torque;
    if (lag) {
        sim_plant_forces(v, &x[N_ROTOR], NULL, lag_torque);
        torque = lag_torque;
        for (int i = 0; i < 4; ++i) {
            dx[N_ROTOR + i] = (cmd[i] - x[N_ROTOR + i]) / v->motor_tau_s;
        }
    }
    for (int i = 0; i < 3; ++i) {
        dx[N_ANGLE + i] = x[N_RATE + i];
    }
    body_accel(v, &x[N_RATE], torque, d, &dx[N_RATE]);
}

static void disturbance_at(sim_disturbance_fn dist, void *ctx, double t, double d[3])
{
    if (dist != NULL) {
        dist(t, ctx, d);
    } else {
        d[0] = d[1] = d[2] = 0.0;
    }
}

/* The RK4 step length of a plant step: dt_s over substeps (at least 1). */
static int substep_count(int substeps) { return substeps < 1 ? 1 : substeps; }

/* Stage time `stage` (0: t, 1: t + h/2, 2: t + h) of substep s of a step
 * from t0 with RK4 steps of length h: stage times from t0 each substep, no
 * drift from summing h. The one formula of the stage times the plant asks
 * the disturbance at, and of the list sim_plant_stage_times gives. */
static double stage_time(double t0, double h, int s, int stage)
{
    const double t = t0 + s * h;
    return stage == 0 ? t : (stage == 1 ? t + 0.5 * h : t + h);
}

/* One classical RK4 step of length h from time t0 + s h; the rotor states only take
 * part with a lag (without one their derivative is 0 and they stay put). */
static void rk4_substep(const sim_vehicle_t *v, int lag, const double cmd[4], const double cmd_torque[3],
                        double t0, int s, double h, sim_disturbance_fn dist, void *ctx, double x[N_STATE])
{
    const int n = lag ? N_STATE : N_ROTOR;
    double k1[N_STATE], k2[N_STATE], k3[N_STATE], k4[N_STATE], y[N_STATE], d[3];
    disturbance_at(dist, ctx, stage_time(t0, h, s, 0), d);
    derivative(v, lag, cmd, cmd_torque, x, d, k1);
    for (int i = 0; i < n; ++i) {
        y[i] = x[i] + 0.5 * h * k1[i];
    }
    disturbance_at(dist, ctx, stage_time(t0, h, s, 1), d); /* the same for k2 and k3 */
    derivative(v, lag, cmd, cmd_torque, y, d, k2);
    for (int i = 0; i < n; ++i) {
        y[i] = x[i] + 0.5 * h * k2[i];
    }
    derivative(v, lag, cmd, cmd_torque, y, d, k3);
    for (int i = 0; i < n; ++i) {
        y[i] = x[i] + h * k3[i];
    }
    disturbance_at(dist, ctx, stage_time(t0, h, s, 2), d);
    derivative(v, lag, cmd, cmd_torque, y, d, k4);
    for (int i = 0; i < n; ++i) {
        x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
}

void sim_plant_step(sim_plant_t *p, const double w2_cmd[4], double dt_s, int substeps,
                    sim_disturbance_fn dist, void *ctx)
{
    if (!(dt_s > 0.0)) {
        return;
    }
    const int n = substep_count(substeps);
    const double h = dt_s / n;
    const double t0 = p->t_s;
    const int lag = p->v.motor_tau_s > 0.0;
    double cmd[4], cmd_torque[3], x[N_STATE];
    for (int i = 0; i < 4; ++i) {
        cmd[i] = clamp_rotor(&p->v, w2_cmd[i]);
        x[N_ROTOR + i] = p->w2_rad2_s2[i];
    }
    sim_plant_forces(&p->v, cmd, NULL, cmd_torque);
    for (int i = 0; i < 3; ++i) {
        x[N_ANGLE + i] = p->angle_rad[i];
        x[N_RATE + i] = p->rate_rad_s[i];
    }
    for (int s = 0; s < n; ++s) {
        if (lag) {
            rk4_substep(&p->v, 1, cmd, cmd_torque, t0, s, h, dist, ctx, x);
        } else {
            rk4_substep(&p->v, 0, cmd, cmd_torque, t0, s, h, dist, ctx, x);
        }
    }
    for (int i = 0; i < 3; ++i) {
        p->angle_rad[i] = x[N_ANGLE + i];
        p->rate_rad_s[i] = x[N_RATE + i];
    }
    for (int i = 0; i < 4; ++i) {
        p->w2_rad2_s2[i] = p->v.motor_tau_s > 0.0 ? x[N_ROTOR + i] : cmd[i];
    }
    p->t_s = t0 + dt_s;
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
