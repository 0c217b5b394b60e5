/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The quadrotor attitude plant of the paper (docs/method.md section 1, eq. 1-3),
 * in double precision, for the software-in-the-loop simulator.
 *
 * Plus frame, rotor i at speed w_i; the state holds w_i^2 (rad^2/s^2):
 *   U_L   = kL (w1^2 + w2^2 + w3^2 + w4^2)
 *   tau_x = l kL (w2^2 - w4^2)
 *   tau_y = l kL (w3^2 - w1^2)
 *   tau_z = b (-w1^2 + w2^2 - w3^2 + w4^2)
 *   phi''   = (tau_x + (Jy - Jz) theta' psi' - kt phi'  ) / Jx + d_phi(t)
 *   theta'' = (tau_y + (Jz - Jx) phi'   psi' - kt theta') / Jy + d_theta(t)
 *   psi''   = (tau_z + (Jx - Jy) theta' phi' - kt psi'  ) / Jz + d_psi(t)
 * Index 0, 1, 2 = roll phi about body X, pitch theta about Y, yaw psi about
 * Z. As in the paper the Euler-angle rates are the body rates (no kinematic
 * transformation) and the angles are not wrapped. With rigid_body the
 * rates are body rates and the attitude a unit quaternion q (rotation.h),
 * q' = q (0, rates) / 2, renormalised after each step: valid through any
 * attitude; angle_rad then holds q's ZYX angles, roll and yaw continuous
 * (moved by whole turns to within pi of the previous step's). d(t) is an angular
 * acceleration in rad/s^2 (docs/method.md section 1, [choice]). The altitude is not
 * simulated: the thrust holds it by construction (eq. 4).
 *
 * Rotors: the command w2_cmd is held over a step (zero-order hold). With
 * rotors_ideal it acts as given, any sign (the paper). Otherwise it is first
 * clamped to [w2_min, w2_max]. With motor_tau_s > 0 the rotors' w^2 follows
 * the (clamped) command through a first-order lag
 *   (w_i^2)' = (w2_cmd_i - w_i^2) / motor_tau_s,
 * integrated with the attitude in the same RK4 state; with motor_tau_s = 0
 * w^2 equals the command throughout the step. A rotor slowing down follows
 * motor_tau_down_s instead when it is > 0 (propellers brake on drag alone,
 * slower than the motor spins them up; 0: motor_tau_s both ways).
 *
 * Battery: with battery_life_s > 0 the rotors give w^2 = command * s(t),
 *   s(t) = (1 - battery_drop * min(t / battery_life_s, 1))^2,
 * held over a step: a rotor's speed at a given command is proportional to
 * the pack's voltage, which falls by the fraction battery_drop over its
 * life (linear in the charge drawn at a steady hover); thrust and yaw
 * torque go with w^2, so the effective thrust coefficient falls as s(t).
 *
 * Wind: the air's velocity relative to the ground, given at the stage
 * times (sim_plant_step_group_air), acts through each rotor's drag. Body
 * axes are forward-right-down, thrust along -z; the torques above put rotor
 * 1 at x = -l, rotor 3 at x = +l, rotor 2 at y = -l, rotor 4 at y = +l,
 * their hubs rotor_height_m above the centre of mass. The vehicle holds its
 * place (no translation is simulated), so the air moves past it at the wind
 * v, in body axes vb = R(angles)^T v (R from yaw, pitch, roll, ZYX, taken
 * at the start of the step). Each rotor feels a force in the disc plane
 *   F_i = k_d w_i (vb_x, vb_y, 0),   k_d = rotor_drag_N_s_m (N per m/s per rad/s)
 * (the induced drag and the blade-flapping tilt of the thrust, both linear
 * in w_i v at low advance ratio), at its hub: the torque r_i x F_i,
 *   tau_x = h k_d vb_y sum(w_i),  tau_y = -h k_d vb_x sum(w_i),
 *   tau_z = k_d l ((w3 - w1) vb_y + (w2 - w4) vb_x),
 * with h = rotor_height_m, which also stands for the flapping hub moment
 * (an effective height). rotor_drag_N_s_m = 0: the wind does nothing.
 *
 * No heap, no stdio, no globals.
 */
#ifndef LADRC_SIM_PLANT_H
#define LADRC_SIM_PLANT_H

typedef struct {
    double mass_kg;
    double inertia_kg_m2[3];  /* Jx, Jy, Jz */
    double arm_m;             /* l */
    double thrust_coeff_N_s2; /* kL */
    double yaw_coeff_Nm_s2;   /* b */
    double rot_drag_Nm_s;     /* kt */
    double g_m_s2;
    int rotors_ideal;                      /* 1: w^2 as commanded, any sign (paper) */
    double w2_min_rad2_s2, w2_max_rad2_s2; /* limits when not ideal */
    double motor_tau_s;                    /* first-order lag of w^2 towards the command, 0 = none */
    double motor_tau_down_s;               /* the lag while w^2 falls; 0 = motor_tau_s */
    double battery_life_s;                 /* time to the end of the voltage drop; 0 = no battery sag */
    double battery_drop;                   /* fraction of the voltage lost over battery_life_s, [0, 1) */
    double rotor_drag_N_s_m;               /* k_d: in-plane rotor force per m/s of air per rad/s, >= 0 */
    double rotor_height_m;                 /* h: the hubs' (effective) height above the centre of mass */
    int rigid_body;                        /* 1: quaternion kinematics (any attitude); 0: the paper's */
} sim_vehicle_t;

/* Disturbance angular accelerations (rad/s^2) of axes 0..2 at time t_s,
 * written to d_out[3]. */
typedef void (*sim_disturbance_fn)(double t_s, void *ctx, double d_out[3]);

typedef struct {
    sim_vehicle_t v;
    double t_s;
    double angle_rad[3];
    double rate_rad_s[3];
    double w2_rad2_s2[4]; /* what the rotors give now (after limits and lag) */
    double quat[4];       /* rigid_body: the attitude, body to world (else unused: sim_plant_attitude) */
} sim_plant_t;

/* The paper's vehicle (Table 1): m = 0.8 kg, J = (5.445e-3, 5.445e-3,
 * 1.089e-2) kg m^2, l = 0.165 m, kL = 2.98e-5 N s^2, b = 2e-6 N m s^2,
 * kt = 9e-2 N m s, g = 9.81 m/s^2; ideal rotors without lag (the limits,
 * unused then, are 0 and HUGE_VAL). */
void sim_vehicle_paper(sim_vehicle_t *v);

/* Copies *v; time 0, level (quat 1 0 0 0), at rest, each rotor at the hover value
 * m g / (4 kL) (clamped to the limits when not ideal). The vehicle is not
 * validated: J_i > 0, kL > 0, and motor_tau_s >= 0 are the caller's to
 * ensure. */
void sim_plant_init(sim_plant_t *p, const sim_vehicle_t *v);

/* The attitude as a unit quaternion (rotation.h): the integrated one of a
 * rigid body, else that of angle_rad (ZYX). */
void sim_plant_attitude(const sim_plant_t *p, double q[4]);

/* The ground holds the vehicle: at rest on angle_rad (roll, pitch, yaw;
 * the quaternion of a rigid body set from them), its rotors untouched. */
void sim_plant_hold(sim_plant_t *p, const double angle_rad[3]);

/* Each rotor's w^2 at hover, m g / (4 kL) (rad^2/s^2), unclamped. */
static inline double sim_hover_w2_rad2_s2(double mass_kg, double g_m_s2, double thrust_coeff_N_s2)
{
    return mass_kg * g_m_s2 / (4.0 * thrust_coeff_N_s2);
}

/* Thrust and body torques of the four w^2 values, as given (no limits).
 * thrust_N may be NULL. */
void sim_plant_forces(const sim_vehicle_t *v, const double w2[4], double *thrust_N, double torque_Nm[3]);

/* Advances p by dt_s with w2_cmd held, in `substeps` classical RK4 steps
 * (values below 1 count as 1); dist (may be NULL: no disturbance) is called
 * at the stage times t, t + h/2 and t + h of every substep, in that order
 * (the two middle stages share one call). Does nothing when dt_s is not > 0. */
void sim_plant_step(sim_plant_t *p, const double w2_cmd[4], double dt_s, int substeps, sim_disturbance_fn dist,
                    void *ctx);

/* Plants sim_plant_step_group steps side by side. */
#define SIM_PLANT_GROUP_MAX 8

/* Steps plants[0..n), plant g with w2_cmd[g], each to exactly the state
 * sim_plant_step(plants[g], w2_cmd[g], dt_s, substeps, dist, ctx) leaves,
 * bit for bit, but the first SIM_PLANT_GROUP_MAX of them that are at
 * plants[0]'s time with its vehicle (every field equal) side by side: their
 * RK4 stages interleaved, independent chains the CPU overlaps, and one dist
 * call per stage time for all of them (the calls sim_plant_step makes for
 * one plant). Any other plant is then stepped alone, with its own calls.
 * Distinct plants only; does nothing when dt_s is not > 0. */
void sim_plant_step_group(sim_plant_t *const plants[], const double (*w2_cmd)[4], int n, double dt_s, int substeps,
                          sim_disturbance_fn dist, void *ctx);

/* The same with the disturbances given instead of asked for: d_stage[k]
 * holds the disturbance at the k-th time sim_plant_stage_times(plants[0],
 * dt_s, substeps, .) lists (3 per substep; the middle one serves two RK4
 * stages), and the plants step as if dist had returned those values at
 * those times. Plants at another time than plants[0] (bit for bit) are not
 * stepped. Returns the number of plants stepped. */
int sim_plant_step_group_table(sim_plant_t *const plants[], const double (*w2_cmd)[4], int n, double dt_s, int substeps,
                               const double (*d_stage)[3]);

/* The same in wind: wind_stage[k] is the air's velocity over the ground
 * (m/s, north-east-down) at the k-th stage time, as d_stage; NULL: still
 * air (sim_plant_step_group_table). */
int sim_plant_step_group_air(sim_plant_t *const plants[], const double (*w2_cmd)[4], int n, double dt_s, int substeps,
                             const double (*d_stage)[3], const double (*wind_stage)[3]);

/* The factor s(t) of the battery law above on the rotors' w^2 at t_s (1
 * without battery sag). */
double sim_plant_battery_factor(const sim_vehicle_t *v, double t_s);

/* The torques (N m) the air moving at wind_body_m_s past the vehicle (body
 * axes, forward-right-down) makes on rotors at w2 (rad^2/s^2), as the
 * header's wind law gives them. */
void sim_plant_wind_torque(const sim_vehicle_t *v, const double w2[4], const double wind_body_m_s[3],
                           double torque_Nm[3]);

/* wind_m_s (north-east-down) in the body axes of angle_rad (roll, pitch,
 * yaw; ZYX). */
void sim_plant_wind_to_body(const double angle_rad[3], const double wind_m_s[3], double body_m_s[3]);

/* The times sim_plant_step(p, ., dt_s, substeps, dist, .) will call dist at,
 * in that order, bit for bit: t, t + h/2 and t + h of every substep, 3 per
 * substep (substeps below 1 count as 1), written to times_out; returns their
 * number (0 when dt_s is not > 0). Lets a caller work out a step's
 * disturbances beforehand, in one batch. */
int sim_plant_stage_times(const sim_plant_t *p, double dt_s, int substeps, double *times_out);

/* The angular accelerations (rad/s^2) of eq. 2 at p's current rates for the
 * given torques and disturbance accelerations (dist may be NULL: zero). */
void sim_plant_accel(const sim_plant_t *p, const double torque_Nm[3], const double dist[3], double accel_out[3]);

#endif
