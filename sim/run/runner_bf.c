/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The BETAFLIGHT run's controller: each control tick one lockstep exchange
 * with a Betaflight SITL (bridge/bf_link.h). The sensors go out as the state
 * packet, the references as the pilot's sticks (bridge/bf_pilot.h), and the
 * four motor outputs come back onto the plant's rotors in Betaflight's
 * motor order for a plus frame (QUADP: rear, right, left, front).
 *
 * Before the scenario's t = 0 the SITL boots and warms up (its gyro
 * calibration wants the vehicle still): warmup_s of its time with the plant
 * held as it starts, disarmed, throttle low; then, when the run starts
 * armed, the arm switch goes up until its motors spin (at most
 * BF_ARM_WAIT_S). Those ticks are not the run's: its metrics start at t = 0.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "runner_parts.h"

#define BF_WARMUP_S_DEFAULT 2.0
#define BF_ARM_WAIT_S 2.0
#define SEA_LEVEL_PA 101325.0
/* The RC link's frame period: Betaflight takes frames closer than some
 * 0.8 ms for a broken link and leaves its sticks where they were, so the
 * pilot's frame goes out with every state packet at 1 kHz and slower, and
 * with every n-th one faster (1 kHz at most, a fast receiver's rate). */
#define BF_RC_PERIOD_S 0.001

/* Betaflight's QUADP motor k drives the plant's rotor BF_TO_PLANT[k]
 * (plant.h: rotor 1 rear, 2 left, 3 front, 4 right). */
static const int BF_TO_PLANT[BF_MOTORS] = {0, 3, 1, 2};

/* The packet's axes as the SITL's Gazebo bridge reads them into
 * Betaflight's forward-left-up body: it negates the pitch rate and the
 * whole specific force, so the packet carries the roll and pitch rates as
 * they are, the yaw rate negated, and the specific force with its forward
 * part negated. Measured: with the yaw rate as it is, Betaflight's yaw runs
 * away at its default motor direction; with the forward force as it is, its
 * attitude estimate tilts nose down for nose up and angle mode diverges. */
static const double BF_GYRO_SIGN[3] = {1.0, 1.0, -1.0};
static const double BF_ACCEL_SIGN[3] = {-1.0, 1.0, 1.0};

/* The ESC command c in [0, 1] that gives a rotor w2 (the inverse of
 * runner_command_w2). */
static double command_of_w2(const sim_scenario_t *sc, double w2)
{
    const double k = isfinite(sc->thrust_curve) ? sc->thrust_curve : 0.0;
    const double x = fmax(0.0, fmin(1.0, w2 / sc->w2_max_rad2_s2));
    if (k < 1e-9) {
        return x;
    }
    const double a = 1.0 - k; /* k c^2 + a c - x = 0 */
    return (-a + sqrt(a * a + 4.0 * k * x)) / (2.0 * k);
}

/* The state packet of the plant as measured at the SITL's time t_s. */
static void state_packet(const sim_plant_t *plant, const double rate_rad_s[3], const double accel_m_s2[3], double t_s,
                         bf_fdm_t *s)
{
    memset(s, 0, sizeof *s);
    s->t_s = t_s;
    double q[4];
    sim_plant_attitude(plant, q);
    bf_gazebo_quat(q, s->quat_wxyz);
    for (int i = 0; i < 3; ++i) {
        s->gyro_rad_s[i] = BF_GYRO_SIGN[i] * rate_rad_s[i];
        s->accel_m_s2[i] = BF_ACCEL_SIGN[i] * accel_m_s2[i];
    }
    s->pressure_Pa = SEA_LEVEL_PA;
}

/* The still vehicle's packet before t = 0. */
static void still_packet(const attitude_run_t *r, double t_s, bf_fdm_t *s)
{
    const double rate[3] = {0.0, 0.0, 0.0}, gravity[3] = {0.0, 0.0, -r->plant.v.g_m_s2};
    double accel[3];
    sim_plant_wind_to_body(r->plant.angle_rad, gravity, accel);
    state_packet(&r->plant, rate, accel, t_s, s);
}

/* 1 when exchange k carries an RC frame (BF_RC_PERIOD_S). */
static int rc_due(const runner_bf_t *bf, long k)
{
    return k % bf->rc_every == 0;
}

static int any_spinning(const float motor[BF_MOTORS])
{
    int on = 0;
    for (int m = 0; m < BF_MOTORS; ++m) {
        on |= motor[m] > 0.0f;
    }
    return on;
}

int runner_bf_open(const sim_scenario_t *sc, attitude_run_t *r, char *err, size_t err_len)
{
    const sim_overrides_t *o = &sc->overrides[SIM_CTRL_BETAFLIGHT];
    const char *env = getenv("LADRC_BETAFLIGHT_SITL"); /* a campaign's runs: the environment's */
    const char *dir = sc->betaflight_sitl[0] != '\0' ? sc->betaflight_sitl : env != NULL ? env : "";
    if (dir[0] == '\0') {
        snprintf(err, err_len,
                 "%s: BETAFLIGHT needs a Betaflight SITL: ladrc_sil --betaflight DIR, or LADRC_BETAFLIGHT_SITL=DIR "
                 "(tools/betaflight_sitl.sh CHECKOUT DIR builds one)",
                 sc->path);
        return -1;
    }
    runner_bf_t *bf = calloc(1, sizeof *bf);
    if (bf == NULL) {
        snprintf(err, err_len, "%s: BETAFLIGHT: out of memory", sc->path);
        return -1;
    }
    bf->link.sock = -1;
    bf->last_thrust_N = NAN;
    r->bf = bf;
    bf_pilot_config_t pc;
    runner_pilot_config(sc, o, o->bf_mode < 0 ? BF_MODE_ACRO : (bf_mode_t)o->bf_mode, &pc);
    bf_pilot_init(&bf->pilot, &pc);
    const double dt = sc->control_dt_s;
    bf->rc_every = (long)ceil(BF_RC_PERIOD_S / dt - 1e-9);
    bf->rc_every = bf->rc_every < 1 ? 1 : bf->rc_every;
    const double ref0[3] = {r->plant.angle_rad[0], r->plant.angle_rad[1], r->plant.angle_rad[2]}, still[3] = {0, 0, 0};
    bf_rc_t rc;
    bf_fdm_t s;
    bf_pilot_sticks(&bf->pilot, 0.0, ref0, still, 0.0, 0, &rc);
    still_packet(r, 0.0, &s);
    if (bf_link_open(&bf->link, dir, o->bf_timeout_ms, &rc, &s, bf->motor, err, err_len) != 0) {
        return -1;
    }
    const long warmup = lround((isnan(o->bf_warmup_s) ? BF_WARMUP_S_DEFAULT : o->bf_warmup_s) / dt);
    long k = 1;
    for (; k <= warmup; ++k) {
        bf_pilot_sticks(&bf->pilot, (double)k * dt, ref0, still, 0.0, 0, &rc);
        still_packet(r, (double)k * dt, &s);
        if (bf_link_exchange(&bf->link, rc_due(bf, k) ? &rc : NULL, &s, bf->motor, err, err_len) != 0) {
            return -1;
        }
    }
    if (r->armed) {
        const long wait = lround(BF_ARM_WAIT_S / dt);
        long j = 0;
        for (; j < wait && !any_spinning(bf->motor); ++j, ++k) {
            bf_pilot_sticks(&bf->pilot, (double)k * dt, ref0, still, 0.0, 1, &rc);
            still_packet(r, (double)k * dt, &s);
            if (bf_link_exchange(&bf->link, rc_due(bf, k) ? &rc : NULL, &s, bf->motor, err, err_len) != 0) {
                return -1;
            }
        }
        if (!any_spinning(bf->motor)) {
            char last[600];
            bf_link_last_output(&bf->link, last, sizeof last);
            snprintf(err, err_len,
                     "%s: Betaflight SITL %s did not arm within %.3g s of its time after %.3g s still and disarmed "
                     "(its motors stayed at 0); its last output: %s",
                     sc->path, dir, BF_ARM_WAIT_S, (double)warmup * dt, last);
            return -1;
        }
    }
    bf->t0_s = (double)k * dt;
    bf->k0 = k;
    bf_pilot_restart(&bf->pilot);
    return 0;
}

/* The throttle stick: the pilot holds altitude, as the mixers of the
 * library's runs hold it by construction. It starts at the ESC command that
 * gives the thrust asked and then moves the motors' thrust towards it with
 * the time constant THROTTLE_TAU_S (the firmware's throttle curve, idle and
 * mixer are its own: the pilot learns them as a pilot does). */
#define THROTTLE_TAU_S 0.3
static double throttle_stick(const sim_scenario_t *sc, const attitude_run_t *r, runner_bf_t *bf, double thrust_N)
{
    const double need = command_of_w2(sc, thrust_N / (4.0 * sc->thrust_coeff_N_s2));
    if (!r->armed) {
        bf->last_thrust_N = NAN;
        return bf->throttle = 0.0;
    }
    if (isnan(bf->last_thrust_N)) {
        bf->throttle = need;
    } else {
        const double got = command_of_w2(sc, bf->last_thrust_N / (4.0 * sc->thrust_coeff_N_s2));
        bf->throttle += sc->control_dt_s / THROTTLE_TAU_S * (need - got);
    }
    return bf->throttle = fmax(0.0, fmin(1.0, bf->throttle));
}

int runner_bf_control(const sim_scenario_t *sc, attitude_run_t *r, tick_t *tk, double w2_cmd[4])
{
    runner_bf_t *bf = r->bf;
    const ladrc_real_t tilt[3] = {(ladrc_real_t)tk->meas_angle[0], (ladrc_real_t)tk->meas_angle[1], 0};
    const double thrust_N = (double)runner_thrust_N(sc, r, tilt, tk->t);
    bf_rc_t rc;
    bf_fdm_t s;
    const double t_sitl = bf->t0_s + tk->t;
    double error_rad[3]; /* the pilot sees the vehicle, not its sensors */
    runner_attitude_error_rad(sc, &r->plant, tk->ref_rad, r->wrap_yaw, error_rad);
    bf_pilot_sticks(&bf->pilot, t_sitl, tk->ref_rad, error_rad, throttle_stick(sc, r, bf, thrust_N), r->armed, &rc);
    state_packet(&r->plant, tk->meas_rate, tk->accel_m_s2, t_sitl, &s);
    char err[BF_LINK_PATH_LEN + 1024];
    const long k = bf->k0 + lround(tk->t / sc->control_dt_s);
    if (bf_link_exchange(&bf->link, rc_due(bf, k) ? &rc : NULL, &s, bf->motor, err, sizeof err) != 0) {
        snprintf(r->spec->err, r->spec->err_len, "%s: BETAFLIGHT at t = %.6g s: %s", sc->path, tk->t, err);
        return -1;
    }
    for (int m = 0; m < BF_MOTORS; ++m) {
        w2_cmd[BF_TO_PLANT[m]] = runner_command_w2(sc, (double)bf->motor[m]);
    }
    double thrust, torque[3];
    sim_plant_forces(&r->plant.v, w2_cmd, &thrust, torque);
    bf->last_thrust_N = r->armed ? thrust : NAN;
    memset(&tk->out, 0, sizeof tk->out);
    tk->thrust_N = (ladrc_real_t)thrust_N;
    tk->out.thrust_N = (ladrc_real_t)thrust;
    for (int i = 0; i < 3; ++i) {
        tk->ctrl_rate[i] = tk->meas_rate[i];
        tk->ctrl_angle[i] = tk->meas_angle[i];
        tk->torque[i] = (ladrc_real_t)torque[i];
        tk->out.torque_Nm[i] = (ladrc_real_t)torque[i];
    }
    for (int q = 0; q < 4; ++q) {
        tk->out.w2_rad2_s2[q] = (ladrc_real_t)w2_cmd[q];
        tk->out.w_rad_s[q] = (ladrc_real_t)sqrt(fmax(w2_cmd[q], 0.0));
    }
    return 1;
}

void runner_bf_close(attitude_run_t *r)
{
    if (r->bf != NULL) {
        bf_link_close(&r->bf->link);
        free(r->bf);
        r->bf = NULL;
    }
}
