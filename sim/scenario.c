/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Scenario parser. The text is copied once and cut up in place: each line
 * is NUL-terminated, its comment removed, and values are handed to the key
 * table below, which says where each key goes, its unit factor and its
 * range. Checks that involve other keys (kind, duration_s, ideal rotors,
 * the run's limits) run once the whole file is read; the earliest of their
 * errors is kept. Last, the library initialises what the run would fly
 * (setup.h), so that a value it refuses is an error at its key.
 */
#include "scenario.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ladrc/estimator.h"
#include "ladrc/leso.h"
#include "plant.h"
#include "sensor.h"
#include "setup.h"

#if defined(__GNUC__)
#define PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define PRINTF_LIKE(f, a)
#endif

#define DEG_TO_RAD (3.14159265358979323846 / 180.0)

/* Defaults that are not the paper vehicle's (documented in docs/scenario-format.md). */
#define DEFAULT_CONTROL_DT_S 0.001
#define DEFAULT_PLANT_SUBSTEPS 10
#define DEFAULT_SEED 1u
#define DEFAULT_TILT_MAX_DEG 40.0
#define DEFAULT_SETTLE_BAND_DEG 0.5
#define DEFAULT_DIVERGE_LIMIT_DEG 90.0

static const char *const CONTROLLER_NAMES[SIM_CTRL_COUNT] = {"HP-MLADRC", "LP-MLADRC", "LADRC",
                                                              "PID",       "CASCADED",  "INDI"};

int sim_controller_needs_rate(sim_controller_id_t id) { return id == SIM_CTRL_INDI; }

const char *sim_controller_name(sim_controller_id_t id)
{
    return ((int)id >= 0 && id < SIM_CTRL_COUNT) ? CONTROLLER_NAMES[id] : "?";
}

double sim_signal_eval_memo(const sim_signal_t *sig, double t_s, sim_expr_memo_t *memo)
{
    for (int i = 0; i < sig->n_pieces; ++i) {
        if (sig->from_s[i] < t_s && t_s <= sig->to_s[i]) {
            return sig->scale * sim_expr_eval_memo(&sig->expr[i], t_s, memo);
        }
    }
    return 0.0;
}

double sim_signal_eval(const sim_signal_t *sig, double t_s) { return sim_signal_eval_memo(sig, t_s, NULL); }

/* ---- sections and keys --------------------------------------------------- */

enum {
    SEC_RUN,
    SEC_VEHICLE,
    SEC_ROTORS,
    SEC_SENSORS,
    SEC_MISMATCH,
    SEC_REFERENCE,
    SEC_DISTURBANCE,
    SEC_METRICS,
    SEC_DIFFERENTIATOR,
    SEC_CONTROLLER, /* + controller id: one slot per [controller NAME] */
    SEC_COUNT = SEC_CONTROLLER + SIM_CTRL_COUNT
};

static const char *const SECTION_NAMES[SEC_CONTROLLER + 1] = {
    "run", "vehicle", "rotors", "sensors", "mismatch", "reference", "disturbance", "metrics",
    "differentiator", "controller"};

/* The kind a section or key belongs to. */
enum { FOR_BOTH, FOR_ATTITUDE, FOR_DIFFERENTIATOR };

static const int SECTION_KIND[SEC_CONTROLLER + 1] = {
    FOR_BOTH, FOR_ATTITUDE, FOR_ATTITUDE, FOR_ATTITUDE, FOR_ATTITUDE, FOR_ATTITUDE,
    FOR_ATTITUDE, FOR_ATTITUDE, FOR_DIFFERENTIATOR, FOR_ATTITUDE};

typedef enum {
    V_REAL,        /* one number */
    V_VEC3,        /* three numbers */
    V_INT,         /* an integer */
    V_SEED,        /* an unsigned 64-bit integer */
    V_CHOICE,      /* one word of `choices`, stored as int */
    V_KIND,        /* attitude | differentiator */
    V_TEXT,        /* the rest of the line */
    V_CONTROLLERS, /* controller names */
    V_WINDOW,      /* FROM TO, 0 <= FROM < TO, into offset and offset2 */
    V_SIGNAL       /* [FROM .. TO :] expression, repeatable */
} value_type_t;

typedef enum {
    R_ANY,
    R_POSITIVE,
    R_NONNEGATIVE,
    R_TILT,
    R_DELAY,
    R_HP_TONES,
    R_PHASE_MARGIN, /* > 0, < 90 */
    R_DURATION,   /* > 0, <= SIM_DURATION_MAX_S */
    R_CONTROL_DT, /* SIM_CONTROL_DT_MIN_S .. SIM_CONTROL_DT_MAX_S */
    R_SUBSTEPS    /* 1 .. SIM_PLANT_SUBSTEPS_MAX */
} range_t;

typedef struct {
    const char *name;
    int value;
} choice_t;

static const choice_t YES_NO[] = {{"yes", 1}, {"no", 0}, {NULL, 0}};
static const choice_t KINDS[] = {
    {"attitude", SIM_KIND_ATTITUDE}, {"differentiator", SIM_KIND_DIFFERENTIATOR}, {NULL, 0}};
static const choice_t LESO_METHODS[] = {{"zoh", LADRC_LESO_ZOH}, {"euler", LADRC_LESO_EULER}, {NULL, 0}};
static const choice_t TUNE_MODES[] = {{"none", SIM_TUNE_NONE}, {"margins", SIM_TUNE_MARGINS}, {NULL, 0}};
static const choice_t HP_FREQ_MODES[] = {
    {"known", LADRC_HP_FREQ_KNOWN}, {"online", LADRC_HP_FREQ_ONLINE}, {NULL, 0}};

#define CTRL_BIT(id) (1u << (id))
#define LADRC_FAMILY (CTRL_BIT(SIM_CTRL_HP_MLADRC) | CTRL_BIT(SIM_CTRL_LP_MLADRC) | CTRL_BIT(SIM_CTRL_LADRC))
#define ALL_CONTROLLERS ((1u << SIM_CTRL_COUNT) - 1u)

typedef struct {
    int section;           /* SEC_*; SEC_CONTROLLER for every [controller NAME] */
    const char *name;
    value_type_t type;
    size_t offset;         /* in sim_scenario_t, or in sim_overrides_t for [controller] */
    size_t offset2;        /* V_WINDOW: where TO goes */
    range_t range;
    double scale;          /* file unit -> stored unit (1 when 0) */
    int variance;          /* stores sqrt(value) * scale */
    const choice_t *choices;
    int kind;              /* FOR_*; FOR_BOTH: the section's */
    int required;          /* in a scenario of the key's kind */
    unsigned controllers;  /* [controller]: the controllers it applies to */
    const char *twin;      /* another key that sets the same field */
} key_def_t;

#define SC(field) offsetof(sim_scenario_t, field)
#define OV(field) offsetof(sim_overrides_t, field)

static const key_def_t KEYS[] = {
    {SEC_RUN, "kind", V_KIND, SC(kind), 0, R_ANY, 0, 0, KINDS, FOR_BOTH, 0, 0, NULL},
    {SEC_RUN, "duration_s", V_REAL, SC(duration_s), 0, R_DURATION, 0, 0, NULL, FOR_BOTH, 1, 0, NULL},
    {SEC_RUN, "control_dt_s", V_REAL, SC(control_dt_s), 0, R_CONTROL_DT, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_RUN, "plant_substeps", V_INT, SC(plant_substeps), 0, R_SUBSTEPS, 0, 0, NULL, FOR_ATTITUDE, 0, 0, NULL},
    {SEC_RUN, "seed", V_SEED, SC(seed), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_RUN, "output_dir", V_TEXT, SC(output_dir), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_RUN, "controllers", V_CONTROLLERS, SC(controllers), 0, R_ANY, 0, 0, NULL, FOR_ATTITUDE, 0, 0, NULL},

    {SEC_VEHICLE, "mass_kg", V_REAL, SC(mass_kg), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_VEHICLE, "inertia_kg_m2", V_VEC3, SC(inertia_kg_m2), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_VEHICLE, "arm_m", V_REAL, SC(arm_m), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_VEHICLE, "thrust_coeff_N_s2", V_REAL, SC(thrust_coeff_N_s2), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_VEHICLE, "yaw_coeff_Nm_s2", V_REAL, SC(yaw_coeff_Nm_s2), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_VEHICLE, "rot_drag_Nm_s", V_REAL, SC(rot_drag_Nm_s), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_VEHICLE, "g_m_s2", V_REAL, SC(g_m_s2), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},

    {SEC_ROTORS, "ideal", V_CHOICE, SC(rotors_ideal), 0, R_ANY, 0, 0, YES_NO, FOR_BOTH, 0, 0, NULL},
    {SEC_ROTORS, "w2_min_rad2_s2", V_REAL, SC(w2_min_rad2_s2), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_ROTORS, "w2_max_rad2_s2", V_REAL, SC(w2_max_rad2_s2), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_ROTORS, "motor_tau_s", V_REAL, SC(motor_tau_s), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_ROTORS, "tilt_max_deg", V_REAL, SC(tilt_max_rad), 0, R_TILT, DEG_TO_RAD, 0, NULL, FOR_BOTH, 0, 0, NULL},

    {SEC_SENSORS, "angle_noise_std_deg", V_REAL, SC(angle_noise_std_rad), 0, R_NONNEGATIVE, DEG_TO_RAD, 0, NULL,
     FOR_BOTH, 0, 0, "angle_noise_var_deg2"},
    {SEC_SENSORS, "angle_noise_var_deg2", V_REAL, SC(angle_noise_std_rad), 0, R_NONNEGATIVE, DEG_TO_RAD, 1, NULL,
     FOR_BOTH, 0, 0, "angle_noise_std_deg"},
    {SEC_SENSORS, "rate_noise_std_deg_s", V_REAL, SC(rate_noise_std_rad_s), 0, R_NONNEGATIVE, DEG_TO_RAD, 0, NULL,
     FOR_BOTH, 0, 0, "rate_noise_var_deg2_s2"},
    {SEC_SENSORS, "rate_noise_var_deg2_s2", V_REAL, SC(rate_noise_std_rad_s), 0, R_NONNEGATIVE, DEG_TO_RAD, 1, NULL,
     FOR_BOTH, 0, 0, "rate_noise_std_deg_s"},
    {SEC_SENSORS, "delay_ticks", V_INT, SC(delay_ticks), 0, R_DELAY, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_SENSORS, "use_rate", V_CHOICE, SC(use_rate), 0, R_ANY, 0, 0, YES_NO, FOR_BOTH, 0, 0, NULL},

    {SEC_MISMATCH, "inertia_scale", V_VEC3, SC(inertia_scale), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_MISMATCH, "rot_drag_scale", V_REAL, SC(rot_drag_scale), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},

    {SEC_REFERENCE, "roll", V_SIGNAL, SC(reference[0]), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_REFERENCE, "pitch", V_SIGNAL, SC(reference[1]), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_REFERENCE, "yaw", V_SIGNAL, SC(reference[2]), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_DISTURBANCE, "roll", V_SIGNAL, SC(disturbance[0]), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_DISTURBANCE, "pitch", V_SIGNAL, SC(disturbance[1]), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_DISTURBANCE, "yaw", V_SIGNAL, SC(disturbance[2]), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},

    {SEC_METRICS, "error_window_s", V_WINDOW, SC(error_window_s[0]), SC(error_window_s[1]), R_ANY, 0, 0, NULL,
     FOR_BOTH, 0, 0, NULL},
    {SEC_METRICS, "steady_window_s", V_WINDOW, SC(steady_window_s[0]), SC(steady_window_s[1]), R_ANY, 0, 0, NULL,
     FOR_BOTH, 0, 0, NULL},
    {SEC_METRICS, "settle_band_deg", V_REAL, SC(settle_band_deg), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_METRICS, "settle_window_s", V_WINDOW, SC(settle_after_s), SC(settle_until_s), R_ANY, 0, 0, NULL, FOR_BOTH,
     0, 0, NULL},
    {SEC_METRICS, "diverge_limit_deg", V_REAL, SC(diverge_limit_deg), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0,
     NULL},

    {SEC_DIFFERENTIATOR, "signal", V_SIGNAL, SC(diff_signal), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 1, 0, NULL},
    {SEC_DIFFERENTIATOR, "derivative", V_SIGNAL, SC(diff_derivative), 0, R_ANY, 0, 0, NULL, FOR_BOTH, 1, 0, NULL},
    {SEC_DIFFERENTIATOR, "noise_var", V_REAL, SC(diff_noise_var), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_DIFFERENTIATOR, "levant_lipschitz_rad_s4", V_REAL, SC(diff_levant_lipschitz), 0, R_POSITIVE, 0, 0, NULL,
     FOR_BOTH, 0, 0, NULL},
    {SEC_DIFFERENTIATOR, "td_accel_rad_s2", V_REAL, SC(diff_td_accel), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0,
     NULL},
    {SEC_DIFFERENTIATOR, "td_h0_s", V_REAL, SC(diff_td_h0_s), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, 0, NULL},
    {SEC_DIFFERENTIATOR, "error_window_s", V_WINDOW, SC(error_window_s[0]), SC(error_window_s[1]), R_ANY, 0, 0,
     NULL, FOR_BOTH, 0, 0, NULL},

    {SEC_CONTROLLER, "wc_rad_s", V_REAL, OV(wc_rad_s), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, LADRC_FAMILY, NULL},
    {SEC_CONTROLLER, "wo_rad_s", V_REAL, OV(wo_rad_s), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0, LADRC_FAMILY, NULL},
    {SEC_CONTROLLER, "leso_method", V_CHOICE, OV(leso_method), 0, R_ANY, 0, 0, LESO_METHODS, FOR_BOTH, 0,
     LADRC_FAMILY, NULL},
    {SEC_CONTROLLER, "hp_freq_mode", V_CHOICE, OV(hp_freq_mode), 0, R_ANY, 0, 0, HP_FREQ_MODES, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_HP_MLADRC), NULL},
    {SEC_CONTROLLER, "hp_freq_rad_s", V_REAL, OV(hp_freq_rad_s), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_HP_MLADRC), NULL},
    {SEC_CONTROLLER, "hp_freq2_rad_s", V_REAL, OV(hp_freq2_rad_s), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_HP_MLADRC), NULL},
    {SEC_CONTROLLER, "hp_tones", V_INT, OV(hp_tones), 0, R_HP_TONES, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_HP_MLADRC), NULL},
    {SEC_CONTROLLER, "levant_lipschitz_rad_s4", V_REAL, OV(levant_lipschitz_rad_s4), 0, R_POSITIVE, 0, 0, NULL,
     FOR_BOTH, 0, CTRL_BIT(SIM_CTRL_HP_MLADRC) | CTRL_BIT(SIM_CTRL_LP_MLADRC), NULL},
    {SEC_CONTROLLER, "td_accel_rad_s2", V_REAL, OV(td_accel_rad_s2), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_LADRC) | CTRL_BIT(SIM_CTRL_CASCADED) | CTRL_BIT(SIM_CTRL_INDI), NULL},
    {SEC_CONTROLLER, "pid_kp", V_REAL, OV(pid_kp), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0, CTRL_BIT(SIM_CTRL_PID),
     NULL},
    {SEC_CONTROLLER, "pid_ki", V_REAL, OV(pid_ki), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0, CTRL_BIT(SIM_CTRL_PID),
     NULL},
    {SEC_CONTROLLER, "pid_kd", V_REAL, OV(pid_kd), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0, CTRL_BIT(SIM_CTRL_PID),
     NULL},
    {SEC_CONTROLLER, "indi_att_kp_per_s", V_REAL, OV(indi_att_kp_per_s), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_INDI), NULL},
    {SEC_CONTROLLER, "indi_rate_kp_per_s", V_REAL, OV(indi_rate_kp_per_s), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_INDI), NULL},
    {SEC_CONTROLLER, "indi_filter_rad_s", V_REAL, OV(indi_filter_rad_s), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_INDI), NULL},
    {SEC_CONTROLLER, "cas_att_kp", V_REAL, OV(cas_att_kp), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_CASCADED), NULL},
    {SEC_CONTROLLER, "cas_rate_max_deg_s", V_REAL, OV(cas_rate_max_deg_s), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_CASCADED), NULL},
    {SEC_CONTROLLER, "cas_rate_kp", V_REAL, OV(cas_rate_kp), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_CASCADED), NULL},
    {SEC_CONTROLLER, "cas_rate_ki", V_REAL, OV(cas_rate_ki), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_CASCADED), NULL},
    {SEC_CONTROLLER, "cas_rate_kd", V_REAL, OV(cas_rate_kd), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_CASCADED), NULL},
    {SEC_CONTROLLER, "cas_d_filter_tau_s", V_REAL, OV(cas_d_filter_tau_s), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH,
     0, CTRL_BIT(SIM_CTRL_CASCADED), NULL},
    {SEC_CONTROLLER, "cas_i_limit_Nm", V_REAL, OV(cas_i_limit_Nm), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0,
     CTRL_BIT(SIM_CTRL_CASCADED), NULL},
    {SEC_CONTROLLER, "coupling_feed", V_CHOICE, OV(coupling_feed), 0, R_ANY, 0, 0, YES_NO, FOR_BOTH, 0,
     LADRC_FAMILY, NULL},
    {SEC_CONTROLLER, "model_motor_tau_s", V_REAL, OV(model_motor_tau_s), 0, R_NONNEGATIVE, 0, 0, NULL, FOR_BOTH, 0,
     LADRC_FAMILY | CTRL_BIT(SIM_CTRL_INDI), NULL},
    {SEC_CONTROLLER, "model_delay_ticks", V_INT, OV(model_delay_ticks), 0, R_DELAY, 0, 0, NULL, FOR_BOTH, 0,
     LADRC_FAMILY | CTRL_BIT(SIM_CTRL_INDI), NULL},
    {SEC_CONTROLLER, "wrap_yaw", V_CHOICE, OV(wrap_yaw), 0, R_ANY, 0, 0, YES_NO, FOR_BOTH, 0,
     LADRC_FAMILY | CTRL_BIT(SIM_CTRL_PID) | CTRL_BIT(SIM_CTRL_CASCADED) | CTRL_BIT(SIM_CTRL_INDI), NULL},
    {SEC_CONTROLLER, "tune", V_CHOICE, OV(tune), 0, R_ANY, 0, 0, TUNE_MODES, FOR_BOTH, 0,
     ALL_CONTROLLERS, NULL},
    {SEC_CONTROLLER, "tune_phase_margin_deg", V_REAL, OV(tune_pm_deg), 0, R_PHASE_MARGIN, 0, 0, NULL, FOR_BOTH, 0,
     ALL_CONTROLLERS, NULL},
    {SEC_CONTROLLER, "tune_gain_margin_db", V_REAL, OV(tune_gm_db), 0, R_POSITIVE, 0, 0, NULL, FOR_BOTH, 0,
     ALL_CONTROLLERS, NULL},
};

#define N_KEYS ((int)(sizeof KEYS / sizeof KEYS[0]))

/* ---- parser state and errors --------------------------------------------- */

typedef struct {
    int line;      /* 0: not given */
    int key_col;
    int value_col;
} loc_t;

typedef struct {
    sim_scenario_t *sc;
    sim_parse_error_t *err;
    int line;
    const char *line_start;
    int section;                          /* SEC_* slot, -1 before the first header */
    int section_line[SEC_COUNT];
    loc_t seen[SEC_COUNT][N_KEYS];
    int piece_line[N_KEYS][SIM_MAX_PIECES];
    int checked;                          /* a consistency error is in err */
    int first_set_line;                   /* > 0: reading the command line's settings from this line */
} parser_t;

static int column(const parser_t *p, const char *at) { return (int)(at - p->line_start) + 1; }

static void vset_error(sim_parse_error_t *err, int line, int col, const char *format, va_list ap)
{
    err->line = line;
    err->column = col;
    vsnprintf(err->message, sizeof err->message, format, ap);
}

/* Records an error at (line, col) of the current file; returns -1. */
static int PRINTF_LIKE(4, 5) fail_at(parser_t *p, int line, int col, const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    vset_error(p->err, line, col, format, ap);
    va_end(ap);
    return -1;
}

#define fail(p, at, ...) fail_at((p), (p)->line, column((p), (at)), __VA_ARGS__)

/* A consistency error: kept if it is the earliest in the file so far. */
static void PRINTF_LIKE(4, 5) check_fail(parser_t *p, int line, int col, const char *format, ...)
{
    if (p->checked && (line > p->err->line || (line == p->err->line && col >= p->err->column))) {
        return;
    }
    p->checked = 1;
    va_list ap;
    va_start(ap, format);
    vset_error(p->err, line, col, format, ap);
    va_end(ap);
}

/* ---- tokens and values ----------------------------------------------------- */

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\r'; }

static char *skip_space(char *s)
{
    while (is_space(*s)) {
        ++s;
    }
    return s;
}

static void trim_end(char *s)
{
    size_t n = strlen(s);
    while (n > 0 && is_space(s[n - 1])) {
        s[--n] = '\0';
    }
}

/* Next whitespace-separated token at or after *s: its start and length
 * (0 at the end of the value); *s moves past it. */
static char *next_token(char **s, size_t *len)
{
    char *start = skip_space(*s);
    char *end = start;
    while (*end != '\0' && !is_space(*end)) {
        ++end;
    }
    *len = (size_t)(end - start);
    *s = end;
    return start;
}

/* Tokens are shown in messages up to this many characters. */
#define SHOWN(len) ((len) > 40 ? 40 : (int)(len))

/* A signed decimal number filling exactly [tok, tok + len). */
static int parse_number(parser_t *p, const char *tok, size_t len, double *value)
{
    size_t i = (len > 0 && (tok[0] == '-' || tok[0] == '+')) ? 1u : 0u;
    double x = 0.0;
    size_t n = (i < len) ? sim_expr_scan_number(tok + i, &x) : 0u;
    if (n == 0 || i + n != len) {
        return fail(p, tok, "expected a number, got '%.*s'", SHOWN(len), tok);
    }
    if (!isfinite(x)) {
        return fail(p, tok, "number out of range");
    }
    *value = (tok[0] == '-') ? -x : x;
    return 0;
}

static int check_range(parser_t *p, const key_def_t *def, const char *tok, double v)
{
    switch (def->range) {
    case R_POSITIVE:
        return v > 0.0 ? 0 : fail(p, tok, "%s must be > 0", def->name);
    case R_NONNEGATIVE:
        return v >= 0.0 ? 0 : fail(p, tok, "%s must be >= 0", def->name);
    case R_TILT:
        return (v > 0.0 && v < 90.0) ? 0 : fail(p, tok, "%s must be > 0 and < 90", def->name);
    case R_DELAY:
        return (v >= 0.0 && v <= SIM_SENSOR_MAX_DELAY)
                   ? 0
                   : fail(p, tok, "%s must be between 0 and %d", def->name, SIM_SENSOR_MAX_DELAY);
    case R_HP_TONES:
        return (v >= 1.0 && v <= LADRC_HP_MAX_TONES)
                   ? 0
                   : fail(p, tok, "%s must be between 1 and %d", def->name, LADRC_HP_MAX_TONES);
    case R_PHASE_MARGIN:
        return (v > 0.0 && v < 90.0) ? 0 : fail(p, tok, "%s must be > 0 and < 90", def->name);
    case R_DURATION:
        return (v > 0.0 && v <= SIM_DURATION_MAX_S)
                   ? 0
                   : fail(p, tok, "%s must be > 0 and at most %g", def->name, SIM_DURATION_MAX_S);
    case R_CONTROL_DT:
        return (v >= SIM_CONTROL_DT_MIN_S && v <= SIM_CONTROL_DT_MAX_S)
                   ? 0
                   : fail(p, tok, "%s must be between %g and %g", def->name, SIM_CONTROL_DT_MIN_S,
                          SIM_CONTROL_DT_MAX_S);
    case R_SUBSTEPS:
        return (v >= 1.0 && v <= SIM_PLANT_SUBSTEPS_MAX)
                   ? 0
                   : fail(p, tok, "%s must be between 1 and %d", def->name, SIM_PLANT_SUBSTEPS_MAX);
    default:
        return 0;
    }
}

/* Exactly `count` numbers in value, each in range, stored with the unit factor. */
static int parse_reals(parser_t *p, const key_def_t *def, char *value, double *out, int count)
{
    char *s = value;
    size_t len;
    for (int i = 0; i < count; ++i) {
        char *tok = next_token(&s, &len);
        double v = 0.0;
        if (len == 0) { /* only with count > 1: an empty value is refused before */
            return fail(p, tok, "expected %d numbers", count);
        }
        if (parse_number(p, tok, len, &v) != 0 || check_range(p, def, tok, v) != 0) {
            return -1;
        }
        const double scale = def->scale != 0.0 ? def->scale : 1.0;
        out[i] = (def->variance ? sqrt(v) : v) * scale;
    }
    char *extra = next_token(&s, &len);
    if (len > 0) {
        return count == 1 ? fail(p, extra, "expected a single number")
                          : fail(p, extra, "expected %d numbers", count);
    }
    return 0;
}

/* The one token of a value, or an error naming what was expected. */
static char *single_token(parser_t *p, char *value, size_t *len, const char *expected)
{
    char *s = value;
    char *tok = next_token(&s, len);
    size_t extra_len;
    char *extra = next_token(&s, &extra_len);
    if (extra_len > 0) {
        fail(p, extra, "expected %s, got '%.*s'", expected, SHOWN(extra_len), extra);
        return NULL;
    }
    return tok;
}

static int parse_int(parser_t *p, const key_def_t *def, char *value, int *out)
{
    size_t len;
    char *tok = single_token(p, value, &len, "a single integer");
    if (tok == NULL) {
        return -1;
    }
    size_t i = (tok[0] == '-' || tok[0] == '+') ? 1u : 0u;
    if (i == len) {
        return fail(p, tok, "expected an integer, got '%.*s'", SHOWN(len), tok);
    }
    for (size_t k = i; k < len; ++k) {
        if (tok[k] < '0' || tok[k] > '9') {
            return fail(p, tok, "expected an integer, got '%.*s'", SHOWN(len), tok);
        }
    }
    errno = 0;
    long v = strtol(tok, NULL, 10);
    if (errno != 0 || v > 1000000000L || v < -1000000000L) {
        return fail(p, tok, "number out of range");
    }
    if (check_range(p, def, tok, (double)v) != 0) {
        return -1;
    }
    *out = (int)v;
    return 0;
}

static int parse_seed(parser_t *p, char *value, uint64_t *out)
{
    size_t len;
    char *tok = single_token(p, value, &len, "a single integer");
    if (tok == NULL) {
        return -1;
    }
    uint64_t v = 0;
    for (size_t k = 0; k < len; ++k) {
        if (tok[k] < '0' || tok[k] > '9') {
            return fail(p, tok, "expected an unsigned integer, got '%.*s'", SHOWN(len), tok);
        }
        const uint64_t digit = (uint64_t)(tok[k] - '0');
        if (v > (UINT64_MAX - digit) / 10u) {
            return fail(p, tok, "seed out of range (at most 18446744073709551615)");
        }
        v = v * 10u + digit;
    }
    *out = v;
    return 0;
}

static int parse_choice(parser_t *p, const choice_t *choices, char *value, int *out)
{
    char expected[96] = "";
    size_t used = 0;
    for (int i = 0; choices[i].name != NULL; ++i) {
        const char *sep = (i == 0) ? "" : (choices[i + 1].name == NULL ? " or " : ", ");
        used += (size_t)snprintf(expected + used, sizeof expected - used, "%s%s", sep, choices[i].name);
    }
    size_t len;
    char *tok = single_token(p, value, &len, expected);
    if (tok == NULL) {
        return -1;
    }
    for (int i = 0; choices[i].name != NULL; ++i) {
        if (strlen(choices[i].name) == len && strncmp(choices[i].name, tok, len) == 0) {
            *out = choices[i].value;
            return 0;
        }
    }
    return fail(p, tok, "expected %s, got '%.*s'", expected, SHOWN(len), tok);
}

/* Controller id of a name, or -1. */
static int controller_id(const char *name, size_t len)
{
    for (int i = 0; i < SIM_CTRL_COUNT; ++i) {
        if (strlen(CONTROLLER_NAMES[i]) == len && strncmp(CONTROLLER_NAMES[i], name, len) == 0) {
            return i;
        }
    }
    return -1;
}

static int fail_unknown_controller(parser_t *p, const char *tok, size_t len)
{
    return fail(p, tok, "unknown controller '%.*s' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)",
                SHOWN(len), tok);
}

static int is_list_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

int sim_controller_list_parse(const char *text, sim_controller_id_t ids[SIM_MAX_CONTROLLERS], int *n,
                              size_t *err_at, char *msg, size_t msg_len)
{
    const char *s = text;
    int after_comma = 0;
    *n = 0;
    for (;;) {
        while (is_list_space(*s)) {
            ++s;
        }
        if (*s == '\0' || *s == ',') {
            if (*n > 0 && !after_comma && *s == '\0') {
                return 0;
            }
            *err_at = (size_t)(s - text);
            snprintf(msg, msg_len, "expected a controller name%s", *s == ',' ? " before ','" : "");
            return -1;
        }
        const char *tok = s;
        while (*s != '\0' && *s != ',' && !is_list_space(*s)) {
            ++s;
        }
        const size_t len = (size_t)(s - tok);
        const int id = controller_id(tok, len);
        *err_at = (size_t)(tok - text);
        if (id < 0) {
            snprintf(msg, msg_len,
                     "unknown controller '%.*s' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)",
                     SHOWN(len), tok);
            return -1;
        }
        for (int i = 0; i < *n; ++i) {
            if ((int)ids[i] == id) {
                snprintf(msg, msg_len, "controller '%s' listed twice", CONTROLLER_NAMES[id]);
                return -1;
            }
        }
        /* distinct names fit: SIM_MAX_CONTROLLERS >= SIM_CTRL_COUNT */
        ids[(*n)++] = (sim_controller_id_t)id;
        while (is_list_space(*s)) {
            ++s;
        }
        after_comma = *s == ',';
        if (after_comma) {
            ++s;
        }
    }
}

static int parse_controllers(parser_t *p, char *value)
{
    sim_scenario_t *sc = p->sc;
    char msg[160];
    size_t at = 0;
    sim_controller_id_t ids[SIM_MAX_CONTROLLERS];
    int n = 0;
    if (sim_controller_list_parse(value, ids, &n, &at, msg, sizeof msg) != 0) {
        return fail(p, value + at, "%s", msg);
    }
    memcpy(sc->controllers, ids, sizeof ids);
    sc->n_controllers = n;
    return 0;
}

static int parse_window(parser_t *p, const key_def_t *def, char *value, double *from, double *to)
{
    char *s = value;
    size_t len[3];
    char *tok[3];
    double v[2] = {0.0, 0.0};
    for (int i = 0; i < 3; ++i) {
        tok[i] = next_token(&s, &len[i]);
    }
    if (len[1] == 0 || len[2] > 0) {
        return fail(p, len[1] == 0 ? tok[1] : tok[2], "expected two numbers FROM TO");
    }
    for (int i = 0; i < 2; ++i) {
        if (parse_number(p, tok[i], len[i], &v[i]) != 0) {
            return -1;
        }
    }
    if (v[0] < 0.0) {
        return fail(p, tok[0], "%s must start at or after 0", def->name);
    }
    if (v[0] >= v[1]) {
        return fail(p, tok[0], "%s: window start must be before its end", def->name);
    }
    *from = v[0];
    *to = v[1];
    return 0;
}

/* One end of a piece's window: empty is unbounded. */
static int parse_bound(parser_t *p, char *text, double unbounded, double *out)
{
    char *tok = skip_space(text);
    trim_end(tok);
    if (*tok == '\0') {
        *out = unbounded;
        return 0;
    }
    return parse_number(p, tok, strlen(tok), out);
}

static int parse_signal(parser_t *p, int key, sim_signal_t *sig, char *value, int key_col)
{
    double from = -INFINITY;
    double to = INFINITY;
    char *text = value;
    char *colon = strchr(value, ':');
    if (colon != NULL) {
        *colon = '\0';
        char *dots = strstr(value, "..");
        if (dots == NULL) {
            return fail(p, value, "expected 'FROM .. TO' before ':'");
        }
        *dots = '\0';
        if (parse_bound(p, value, -INFINITY, &from) != 0 || parse_bound(p, dots + 2, INFINITY, &to) != 0) {
            return -1;
        }
        if (!(from < to)) {
            return fail(p, value, "window start must be before its end");
        }
        text = skip_space(colon + 1);
        if (*text == '\0') {
            return fail(p, text, "expected an expression after ':'");
        }
    } else {
        char *dots = strstr(value, "..");
        if (dots != NULL) {
            return fail(p, dots, "expected ':' between the window and the expression");
        }
    }
    if (sig->n_pieces >= SIM_MAX_PIECES) {
        return fail_at(p, p->line, key_col, "more than %d pieces for '%s'", SIM_MAX_PIECES, KEYS[key].name);
    }
    for (int i = 0; i < sig->n_pieces; ++i) {
        if (from < sig->to_s[i] && sig->from_s[i] < to) {
            if (p->first_set_line > 0) {
                return fail(p, value, "window (%g, %g] overlaps another setting of '%s' on the command line", from,
                            to, KEYS[key].name);
            }
            return fail(p, value, "window (%g, %g] overlaps the one given on line %d", from, to,
                        p->piece_line[key][i]);
        }
    }
    sim_expr_error_t e;
    const int n = sig->n_pieces;
    if (sim_expr_compile(&sig->expr[n], text, &e) != 0) {
        return fail_at(p, p->line, column(p, text) + e.column - 1, "%s", e.message);
    }
    sig->from_s[n] = from;
    sig->to_s[n] = to;
    p->piece_line[key][n] = p->line;
    sig->n_pieces = n + 1;
    return 0;
}

static int set_value(parser_t *p, int key, char *base, char *value, int key_col)
{
    const key_def_t *def = &KEYS[key];
    void *field = base + def->offset;
    switch (def->type) {
    case V_REAL:
        return parse_reals(p, def, value, (double *)field, 1);
    case V_VEC3:
        return parse_reals(p, def, value, (double *)field, 3);
    case V_INT:
        return parse_int(p, def, value, (int *)field);
    case V_SEED:
        return parse_seed(p, value, (uint64_t *)field);
    case V_CHOICE:
        return parse_choice(p, def->choices, value, (int *)field);
    case V_KIND: {
        int kind;
        if (parse_choice(p, def->choices, value, &kind) != 0) {
            return -1;
        }
        p->sc->kind = (sim_kind_t)kind;
        return 0;
    }
    case V_TEXT:
        if (strlen(value) >= SIM_PATH_LEN) {
            return fail(p, value, "%s longer than %d characters", def->name, SIM_PATH_LEN - 1);
        }
        memcpy(field, value, strlen(value) + 1);
        return 0;
    case V_CONTROLLERS:
        return parse_controllers(p, value);
    case V_WINDOW:
        return parse_window(p, def, value, (double *)field, (double *)(void *)(base + def->offset2));
    default:
        return parse_signal(p, key, (sim_signal_t *)field, value, key_col);
    }
}

/* ---- lines ------------------------------------------------------------------ */

static const char *section_title(int sec, char *buf, size_t n)
{
    if (sec >= SEC_CONTROLLER) {
        snprintf(buf, n, "[controller %s]", CONTROLLER_NAMES[sec - SEC_CONTROLLER]);
    } else {
        snprintf(buf, n, "[%s]", SECTION_NAMES[sec]);
    }
    return buf;
}

static int parse_section(parser_t *p, char *s)
{
    char *close = strchr(s, ']');
    if (close == NULL) {
        return fail(p, s + strlen(s), "expected ']'");
    }
    char *after = skip_space(close + 1);
    if (*after != '\0') {
        return fail(p, after, "trailing characters after ']'");
    }
    *close = '\0';
    char *rest = s + 1;
    size_t len;
    char *name = next_token(&rest, &len);
    if (len == 0) {
        return fail(p, name, "expected a section name");
    }
    int sec = -1;
    for (int i = 0; i <= SEC_CONTROLLER; ++i) {
        if (strlen(SECTION_NAMES[i]) == len && strncmp(SECTION_NAMES[i], name, len) == 0) {
            sec = i;
        }
    }
    if (sec < 0) {
        return fail(p, name, "unknown section [%.*s]", SHOWN(len), name);
    }
    if (sec == SEC_CONTROLLER) {
        char *ctrl = next_token(&rest, &len);
        if (len == 0) {
            return fail(p, ctrl, "expected a controller name after 'controller'");
        }
        const int id = controller_id(ctrl, len);
        if (id < 0) {
            return fail_unknown_controller(p, ctrl, len);
        }
        sec += id;
    }
    char *extra = next_token(&rest, &len);
    if (len > 0) {
        return fail(p, extra, "unexpected '%.*s' in the section header", SHOWN(len), extra);
    }
    if (p->section_line[sec] != 0) {
        char title[48];
        return fail(p, s, "section %s already given on line %d", section_title(sec, title, sizeof title),
                    p->section_line[sec]);
    }
    p->section_line[sec] = p->line;
    p->section = sec;
    return 0;
}

static int parse_key_line(parser_t *p, char *s);
static int is_key_char(char c);

/* One command-line setting SECTION.KEY=VALUE as a line of SECTION. */
static int parse_setting(parser_t *p, char *s)
{
    p->line_start = s;
    char *eq = strchr(s, '=');
    char *dot = strchr(s, '.');
    if (eq == NULL || dot == NULL || dot > eq) {
        return fail(p, s, "expected SECTION.KEY=VALUE, got '%.*s'", SHOWN(strlen(s)), s);
    }
    char *name = skip_space(s);
    size_t len = 0;
    while (name + len < dot && is_key_char(name[len])) {
        ++len;
    }
    int sec = -1;
    for (int i = 0; i <= SEC_CONTROLLER; ++i) {
        if (strlen(SECTION_NAMES[i]) == len && strncmp(SECTION_NAMES[i], name, len) == 0) {
            sec = i;
        }
    }
    char *rest = name + len;
    if (sec < 0 || (sec != SEC_CONTROLLER && skip_space(rest) != dot)) {
        return fail(p, name, "unknown section '%.*s'", SHOWN((size_t)(dot - name)), name);
    }
    if (sec == SEC_CONTROLLER) {
        if (*rest == ':') {
            ++rest;
        }
        char *ctrl = skip_space(rest);
        char *end = ctrl;
        while (end < dot && !is_space(*end)) {
            ++end;
        }
        if (end == ctrl) {
            return fail(p, ctrl, "expected a controller name after 'controller' ('controller:NAME.KEY=VALUE')");
        }
        const int id = controller_id(ctrl, (size_t)(end - ctrl));
        if (id < 0) {
            return fail_unknown_controller(p, ctrl, (size_t)(end - ctrl));
        }
        if (skip_space(end) != dot) {
            return fail(p, skip_space(end), "expected '.' after the controller's name");
        }
        sec += id;
    }
    if (p->section_line[sec] == 0) {
        p->section_line[sec] = p->line;
    }
    p->section = sec;
    char *key = skip_space(dot + 1);
    if (key == eq) {
        return fail(p, key, "expected a key after '.'");
    }
    return parse_key_line(p, key);
}

static int find_key(int table, const char *name)
{
    for (int i = 0; i < N_KEYS; ++i) {
        if (KEYS[i].section == table && strcmp(KEYS[i].name, name) == 0) {
            return i;
        }
    }
    return -1;
}

static int is_key_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

static int parse_key_line(parser_t *p, char *s)
{
    char *key = s;
    while (is_key_char(*s)) {
        ++s;
    }
    const size_t key_len = (size_t)(s - key);
    if (key_len == 0) {
        return fail(p, key, "expected a key or a [section]");
    }
    char *eq = skip_space(s);
    if (*eq != '=') {
        return fail(p, eq, "expected '=' after '%.*s'", SHOWN(key_len), key);
    }
    key[key_len] = '\0'; /* may overwrite '=': eq still points past the key */
    char *value = skip_space(eq + 1);
    const int key_col = column(p, key);
    if (p->section < 0) {
        return fail(p, key, "key '%s' before any [section]", key);
    }
    if (*value == '\0') {
        return fail(p, value, "missing value for '%s'", key);
    }
    const int sec = p->section;
    const int table = sec >= SEC_CONTROLLER ? SEC_CONTROLLER : sec;
    const int k = find_key(table, key);
    if (k < 0) {
        char title[48];
        return fail(p, key, "unknown key '%s' in %s", key, section_title(sec, title, sizeof title));
    }
    if (table == SEC_CONTROLLER && !(KEYS[k].controllers & CTRL_BIT(sec - SEC_CONTROLLER))) {
        return fail(p, key, "'%s' does not apply to %s", key, CONTROLLER_NAMES[sec - SEC_CONTROLLER]);
    }
    loc_t *seen = &p->seen[sec][k];
    char *base = (table == SEC_CONTROLLER) ? (char *)&p->sc->overrides[sec - SEC_CONTROLLER] : (char *)p->sc;
    if (p->first_set_line > 0 && seen->line != 0 && seen->line < p->first_set_line) {
        /* a command-line setting replaces the file's value, every piece of a signal */
        memset(seen, 0, sizeof *seen);
        if (KEYS[k].type == V_SIGNAL) {
            ((sim_signal_t *)(void *)(base + KEYS[k].offset))->n_pieces = 0;
        }
    }
    if (p->first_set_line > 0 && KEYS[k].twin != NULL) {
        loc_t *twin = &p->seen[sec][find_key(table, KEYS[k].twin)];
        if (twin->line != 0 && twin->line < p->first_set_line) {
            memset(twin, 0, sizeof *twin); /* the same field: replaced as well */
        }
    }
    if (seen->line != 0 && KEYS[k].type != V_SIGNAL) {
        if (p->first_set_line > 0) {
            return fail(p, key, "duplicate key '%s' (set twice on the command line)", key);
        }
        return fail(p, key, "duplicate key '%s' (first given on line %d)", key, seen->line);
    }
    if (KEYS[k].twin != NULL) {
        const loc_t *twin = &p->seen[sec][find_key(table, KEYS[k].twin)];
        if (twin->line != 0) {
            if (p->first_set_line > 0) {
                return fail(p, key, "'%s' and '%s' set the same value (both on the command line)", key,
                            KEYS[k].twin);
            }
            return fail(p, key, "'%s' and '%s' (line %d) set the same value", key, KEYS[k].twin, twin->line);
        }
    }
    if (seen->line == 0) {
        seen->line = p->line;
        seen->key_col = key_col;
        seen->value_col = column(p, value);
    }
    return set_value(p, k, base, value, key_col);
}

/* ---- defaults and consistency ----------------------------------------------- */

static void set_defaults(sim_scenario_t *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->kind = SIM_KIND_ATTITUDE;
    sc->duration_s = NAN; /* required */
    sc->control_dt_s = DEFAULT_CONTROL_DT_S;
    sc->plant_substeps = DEFAULT_PLANT_SUBSTEPS;
    sc->seed = DEFAULT_SEED;
    sc->n_controllers = SIM_CTRL_DEFAULT_COUNT;
    for (int i = 0; i < SIM_CTRL_DEFAULT_COUNT; ++i) {
        sc->controllers[i] = (sim_controller_id_t)i;
    }

    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    sc->mass_kg = v.mass_kg;
    memcpy(sc->inertia_kg_m2, v.inertia_kg_m2, sizeof sc->inertia_kg_m2);
    sc->arm_m = v.arm_m;
    sc->thrust_coeff_N_s2 = v.thrust_coeff_N_s2;
    sc->yaw_coeff_Nm_s2 = v.yaw_coeff_Nm_s2;
    sc->rot_drag_Nm_s = v.rot_drag_Nm_s;
    sc->g_m_s2 = v.g_m_s2;
    sc->rotors_ideal = v.rotors_ideal;
    sc->w2_min_rad2_s2 = v.w2_min_rad2_s2;
    sc->w2_max_rad2_s2 = v.w2_max_rad2_s2;
    sc->motor_tau_s = v.motor_tau_s;
    sc->tilt_max_rad = DEFAULT_TILT_MAX_DEG * DEG_TO_RAD;

    sc->use_rate = 1;
    for (int i = 0; i < 3; ++i) {
        sc->inertia_scale[i] = 1.0;
        sc->reference[i].scale = DEG_TO_RAD;
        sc->disturbance[i].scale = 1.0;
    }
    sc->rot_drag_scale = 1.0;

    for (int i = 0; i < SIM_CTRL_COUNT; ++i) {
        sim_overrides_t *o = &sc->overrides[i];
        o->wc_rad_s = o->wo_rad_s = NAN;
        o->leso_method = o->hp_freq_mode = o->coupling_feed = -1;
        o->hp_freq_rad_s = o->hp_freq2_rad_s = o->levant_lipschitz_rad_s4 = o->td_accel_rad_s2 = NAN;
        o->hp_tones = -1;
        o->model_motor_tau_s = NAN;
        o->model_delay_ticks = o->wrap_yaw = -1;
        o->pid_kp = o->pid_ki = o->pid_kd = NAN;
        o->tune = -1;
        o->tune_pm_deg = o->tune_gm_db = NAN;
        o->indi_att_kp_per_s = o->indi_rate_kp_per_s = o->indi_filter_rad_s = NAN;
        o->cas_att_kp = o->cas_rate_max_deg_s = o->cas_rate_kp = o->cas_rate_ki = o->cas_rate_kd = NAN;
        o->cas_d_filter_tau_s = o->cas_i_limit_Nm = NAN;
    }

    sc->settle_band_deg = DEFAULT_SETTLE_BAND_DEG;
    sc->diverge_limit_deg = DEFAULT_DIVERGE_LIMIT_DEG;
    /* the metric windows default to the whole run, set once duration_s is known */

    sc->diff_signal.scale = 1.0;
    sc->diff_derivative.scale = 1.0;
    sc->diff_levant_lipschitz = sc->diff_td_accel = sc->diff_td_h0_s = NAN;
}

static const loc_t *seen_key(const parser_t *p, int sec, const char *name)
{
    const int k = find_key(sec >= SEC_CONTROLLER ? SEC_CONTROLLER : sec, name);
    return &p->seen[sec][k];
}

static int kind_of(int sec, const key_def_t *def)
{
    return def->kind != FOR_BOTH ? def->kind : SECTION_KIND[sec >= SEC_CONTROLLER ? SEC_CONTROLLER : sec];
}

static void check_kind(parser_t *p)
{
    const int kind = p->sc->kind == SIM_KIND_DIFFERENTIATOR ? FOR_DIFFERENTIATOR : FOR_ATTITUDE;
    const char *kind_name = kind == FOR_DIFFERENTIATOR ? "differentiator" : "attitude";
    char title[48];
    for (int sec = 0; sec < SEC_COUNT; ++sec) {
        const int sec_kind = SECTION_KIND[sec >= SEC_CONTROLLER ? SEC_CONTROLLER : sec];
        if (p->section_line[sec] != 0 && sec_kind != FOR_BOTH && sec_kind != kind) {
            check_fail(p, p->section_line[sec], 1, "%s does not apply to kind = %s",
                       section_title(sec, title, sizeof title), kind_name);
        }
        for (int k = 0; k < N_KEYS; ++k) {
            const loc_t *at = &p->seen[sec][k];
            const int key_kind = kind_of(sec, &KEYS[k]);
            /* a key of a section that does not apply is reported with its section */
            if (at->line != 0 && KEYS[k].kind != FOR_BOTH && KEYS[k].kind != kind) {
                check_fail(p, at->line, at->key_col, "'%s' does not apply to kind = %s", KEYS[k].name, kind_name);
            }
            if (KEYS[k].required && KEYS[k].section == sec && at->line == 0 &&
                (key_kind == FOR_BOTH || key_kind == kind)) {
                const int line = p->section_line[sec] != 0 ? p->section_line[sec] : 1;
                check_fail(p, line, 1, "missing required key '%s' in %s", KEYS[k].name,
                           section_title(sec, title, sizeof title));
            }
        }
    }
}

/* The first of the keys of a section that the file gives, or NULL. */
static const loc_t *first_given(const parser_t *p, int sec, const char *const *names, int n)
{
    for (int i = 0; i < n; ++i) {
        const loc_t *at = seen_key(p, sec, names[i]);
        if (at->line != 0) {
            return at;
        }
    }
    return NULL;
}

/* Where a limit on the run's steps is reported: the first key given of
 * plant_substeps (when it takes part), control_dt_s, duration_s. */
static const loc_t *steps_key(const parser_t *p, int with_substeps)
{
    static const char *const keys[] = {"plant_substeps", "control_dt_s", "duration_s"};
    return with_substeps ? first_given(p, SEC_RUN, keys, 3) : first_given(p, SEC_RUN, keys + 1, 2);
}

/* The run's size (control periods and plant steps) and the plant step
 * against the plant's time constants; limits in scenario.h. */
static void check_run_size(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    const double ticks = floor(sc->duration_s / sc->control_dt_s + 0.5); /* sim_run_ticks */
    if (ticks > (double)SIM_RUN_TICKS_MAX) {
        const loc_t *at = steps_key(p, 0);
        check_fail(p, at->line, at->value_col,
                   "the run takes %g control periods (duration_s / control_dt_s), more than %g", ticks,
                   (double)SIM_RUN_TICKS_MAX);
        return;
    }
    if (sc->kind != SIM_KIND_ATTITUDE) {
        return;
    }
    const double steps = ticks * sc->plant_substeps;
    if (steps > SIM_RUN_PLANT_STEPS_MAX) {
        const loc_t *at = steps_key(p, 1);
        check_fail(p, at->line, at->value_col,
                   "the run takes %g plant steps (duration_s / control_dt_s x plant_substeps), more than %g", steps,
                   SIM_RUN_PLANT_STEPS_MAX);
        return;
    }
    /* RK4 is stable on a decay up to 2.8 time constants per step and loses
     * its accuracy well before: the plant's truth resolves its fastest part. */
    const double h = sc->control_dt_s / sc->plant_substeps;
    double tau = INFINITY;
    const char *what = NULL;
    const loc_t *cause = NULL; /* the key that sets the time constant */
    if (sc->motor_tau_s > 0.0) {
        tau = sc->motor_tau_s;
        what = "motor_tau_s";
        cause = seen_key(p, SEC_ROTORS, "motor_tau_s");
    }
    for (int i = 0; i < 3; ++i) {
        if (sc->rot_drag_Nm_s > 0.0 && sc->inertia_kg_m2[i] / sc->rot_drag_Nm_s < tau) {
            tau = sc->inertia_kg_m2[i] / sc->rot_drag_Nm_s;
            what = "the drag time constant J / rot_drag_Nm_s";
            static const char *const vehicle[] = {"inertia_kg_m2", "rot_drag_Nm_s"};
            cause = first_given(p, SEC_VEHICLE, vehicle, 2);
        }
    }
    if (h > tau) {
        static const char *const run[] = {"plant_substeps", "control_dt_s"};
        const loc_t *at = first_given(p, SEC_RUN, run, 2);
        if (at == NULL) {
            at = cause != NULL ? cause : seen_key(p, SEC_RUN, "duration_s");
        }
        const double needed = ceil(sc->control_dt_s / tau);
        char fix[64];
        if (needed <= SIM_PLANT_SUBSTEPS_MAX) {
            snprintf(fix, sizeof fix, "plant_substeps must be at least %.0f", needed);
        } else {
            snprintf(fix, sizeof fix, "more than %d plant_substeps would be needed", SIM_PLANT_SUBSTEPS_MAX);
        }
        check_fail(p, at->line, at->value_col,
                   "the plant step control_dt_s / plant_substeps (%g s) is longer than %s (%g s): %s", h, what, tau,
                   fix);
    }
}

static void check_run(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    if (isnan(sc->duration_s)) {
        return; /* missing, reported by check_kind */
    }
    if (!(sc->control_dt_s <= sc->duration_s)) {
        const loc_t *dt = seen_key(p, SEC_RUN, "control_dt_s");
        const loc_t *at = dt->line != 0 ? dt : seen_key(p, SEC_RUN, "duration_s");
        if (at->line != 0) {
            check_fail(p, at->line, at->value_col, "control_dt_s (%g) must not exceed duration_s (%g)",
                       sc->control_dt_s, sc->duration_s);
        }
    }
    check_run_size(p);
    /* [metrics] windows, and the error window of [differentiator] */
    static const int sections[] = {SEC_METRICS, SEC_METRICS, SEC_METRICS, SEC_DIFFERENTIATOR};
    static const char *const windows[] = {"error_window_s", "steady_window_s", "settle_window_s", "error_window_s"};
    const double ends[] = {sc->error_window_s[1], sc->steady_window_s[1], sc->settle_until_s, sc->error_window_s[1]};
    for (int i = 0; i < 4; ++i) {
        const loc_t *at = seen_key(p, sections[i], windows[i]);
        if (at->line != 0 && ends[i] > sc->duration_s) {
            check_fail(p, at->line, at->value_col, "%s ends after the run (duration_s = %g)", windows[i],
                       sc->duration_s);
        }
    }
}

static void check_rotors(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    const loc_t *min = seen_key(p, SEC_ROTORS, "w2_min_rad2_s2");
    const loc_t *max = seen_key(p, SEC_ROTORS, "w2_max_rad2_s2");
    if (sc->rotors_ideal) {
        const loc_t *limit[2] = {min, max};
        const char *name[2] = {"w2_min_rad2_s2", "w2_max_rad2_s2"};
        for (int i = 0; i < 2; ++i) {
            if (limit[i]->line != 0) {
                check_fail(p, limit[i]->line, limit[i]->key_col, "'%s' does not apply with ideal = yes", name[i]);
            }
        }
        return;
    }
    if (max->line == 0) {
        const loc_t *ideal = seen_key(p, SEC_ROTORS, "ideal");
        check_fail(p, ideal->line, ideal->value_col, "ideal = no needs w2_max_rad2_s2");
    } else if (!(sc->w2_max_rad2_s2 > sc->w2_min_rad2_s2)) {
        check_fail(p, max->line, max->value_col, "w2_max_rad2_s2 must be > w2_min_rad2_s2 (%g)",
                   sc->w2_min_rad2_s2);
    }
}

static void check_differentiator(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    const loc_t *h0 = seen_key(p, SEC_DIFFERENTIATOR, "td_h0_s");
    if (h0->line != 0 && sc->diff_td_h0_s < sc->control_dt_s) {
        check_fail(p, h0->line, h0->value_col, "td_h0_s must be >= control_dt_s (%g)", sc->control_dt_s);
    }
}

/* tune = margins chooses the gains: a gain the file gives as well is an
 * error at that gain; targets without tune = margins are an error too. */
static void check_tuning(parser_t *p)
{
    /* the keys of the gains tune = margins chooses (setup.h, sim_setup_gain_fields) */
    static const char *const gains[] = {"wc_rad_s",          "wo_rad_s",           "pid_kp",
                                        "pid_ki",            "pid_kd",             "cas_att_kp",
                                        "cas_rate_kp",       "cas_rate_ki",        "cas_rate_kd",
                                        "cas_d_filter_tau_s", "indi_att_kp_per_s", "indi_rate_kp_per_s",
                                        "indi_filter_rad_s"};
    static const char *const targets[] = {"tune_phase_margin_deg", "tune_gain_margin_db"};
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        const int sec = SEC_CONTROLLER + id;
        const loc_t *tune = seen_key(p, sec, "tune");
        if (p->sc->overrides[id].tune == SIM_TUNE_MARGINS) {
            for (int g = 0; g < (int)(sizeof gains / sizeof gains[0]); ++g) {
                const loc_t *at = seen_key(p, sec, gains[g]);
                if (at->line != 0) {
                    check_fail(p, at->line, at->key_col,
                               "'%s' conflicts with tune = margins (line %d), which chooses the gains: "
                               "give one of them",
                               gains[g], tune->line);
                }
            }
        } else {
            for (int g = 0; g < 2; ++g) {
                const loc_t *at = seen_key(p, sec, targets[g]);
                if (at->line != 0) {
                    check_fail(p, at->line, at->key_col, "'%s' applies only with tune = margins", targets[g]);
                }
            }
        }
    }
}

/* ---- what the library accepts ------------------------------------------------
 *
 * The controllers, the mixer and the differentiators are initialised once
 * here with the configurations the runner gives them (setup.h), so that a
 * scenario the library refuses is an error of the file, at the key that sets
 * the refused value, and not a failed run. */

typedef struct {
    int sec;          /* SEC_*; -1: the controller's own [controller NAME] */
    const char *name;
} key_ref_t;

#define CTRL_SEC (-1)
#define END_KEYS {0, NULL}

/* The keys behind a refused value, most likely first (the first one the
 * file gives is reported). */
static const key_ref_t *keys_of_status(ladrc_status_t st, int known_freqs)
{
    static const key_ref_t dt[] = {{SEC_RUN, "control_dt_s"}, END_KEYS};
    static const key_ref_t inertia[] = {{SEC_VEHICLE, "inertia_kg_m2"}, {SEC_MISMATCH, "inertia_scale"}, END_KEYS};
    static const key_ref_t drag[] = {{SEC_VEHICLE, "rot_drag_Nm_s"}, {SEC_MISMATCH, "rot_drag_scale"}, END_KEYS};
    static const key_ref_t wc[] = {{CTRL_SEC, "wc_rad_s"}, END_KEYS};
    static const key_ref_t wo[] = {{CTRL_SEC, "wo_rad_s"}, END_KEYS};
    static const key_ref_t euler[] = {
        {CTRL_SEC, "wo_rad_s"}, {SEC_RUN, "control_dt_s"}, {CTRL_SEC, "leso_method"}, END_KEYS};
    static const key_ref_t td_accel[] = {{CTRL_SEC, "td_accel_rad_s2"}, END_KEYS};
    static const key_ref_t levant[] = {{CTRL_SEC, "levant_lipschitz_rad_s4"}, {SEC_RUN, "control_dt_s"}, END_KEYS};
    static const key_ref_t kp[] = {{CTRL_SEC, "pid_kp"}, END_KEYS};
    static const key_ref_t ki[] = {{CTRL_SEC, "pid_ki"}, END_KEYS};
    static const key_ref_t kd[] = {{CTRL_SEC, "pid_kd"}, END_KEYS};
    static const key_ref_t indi_att[] = {{CTRL_SEC, "indi_att_kp_per_s"}, {SEC_RUN, "control_dt_s"}, END_KEYS};
    static const key_ref_t indi_rate[] = {{CTRL_SEC, "indi_rate_kp_per_s"}, {SEC_RUN, "control_dt_s"}, END_KEYS};
    static const key_ref_t indi_filter[] = {{CTRL_SEC, "indi_filter_rad_s"}, {SEC_RUN, "control_dt_s"}, END_KEYS};
    static const key_ref_t cas_att[] = {{CTRL_SEC, "cas_att_kp"}, {SEC_RUN, "control_dt_s"}, END_KEYS};
    static const key_ref_t cas_max[] = {{CTRL_SEC, "cas_rate_max_deg_s"}, END_KEYS};
    static const key_ref_t cas_kp[] = {{CTRL_SEC, "cas_rate_kp"}, END_KEYS};
    static const key_ref_t cas_ki[] = {{CTRL_SEC, "cas_rate_ki"}, END_KEYS};
    static const key_ref_t cas_kd[] = {{CTRL_SEC, "cas_rate_kd"}, END_KEYS};
    static const key_ref_t cas_tau[] = {{CTRL_SEC, "cas_d_filter_tau_s"}, END_KEYS};
    static const key_ref_t cas_i[] = {{CTRL_SEC, "cas_i_limit_Nm"}, END_KEYS};
    static const key_ref_t freqs[] = {
        {CTRL_SEC, "hp_freq_rad_s"}, {CTRL_SEC, "hp_freq2_rad_s"}, {SEC_RUN, "control_dt_s"}, END_KEYS};
    static const key_ref_t tones[] = {
        {CTRL_SEC, "hp_tones"}, {CTRL_SEC, "hp_freq2_rad_s"}, {CTRL_SEC, "hp_freq_mode"}, END_KEYS};
    static const key_ref_t mixer_kl[] = {{SEC_VEHICLE, "thrust_coeff_N_s2"}, END_KEYS};
    static const key_ref_t mixer_arm[] = {{SEC_VEHICLE, "arm_m"}, END_KEYS};
    static const key_ref_t mixer_b[] = {{SEC_VEHICLE, "yaw_coeff_Nm_s2"}, END_KEYS};
    static const key_ref_t mixer_mass[] = {{SEC_VEHICLE, "mass_kg"}, END_KEYS};
    static const key_ref_t mixer_g[] = {{SEC_VEHICLE, "g_m_s2"}, END_KEYS};
    static const key_ref_t w2_min[] = {{SEC_ROTORS, "w2_min_rad2_s2"}, END_KEYS};
    static const key_ref_t w2_max[] = {{SEC_ROTORS, "w2_max_rad2_s2"}, {SEC_ROTORS, "w2_min_rad2_s2"}, END_KEYS};
    static const key_ref_t tilt[] = {{SEC_ROTORS, "tilt_max_deg"}, END_KEYS};
    static const key_ref_t motor_tau[] = {{CTRL_SEC, "model_motor_tau_s"}, {SEC_ROTORS, "motor_tau_s"}, END_KEYS};
    static const key_ref_t delay[] = {{CTRL_SEC, "model_delay_ticks"}, {SEC_SENSORS, "delay_ticks"}, END_KEYS};
    switch (st) {
    case LADRC_ERR_INERTIA_KG_M2:
    case LADRC_ERR_B0: return inertia;
    case LADRC_ERR_DRAG_NMS: return drag;
    case LADRC_ERR_WC_RAD_S: return wc;
    case LADRC_ERR_WO_RAD_S:
    case LADRC_ERR_HP_SAMPLE_LAG: return wo;
    case LADRC_ERR_LESO_EULER_UNSTABLE: return euler;
    case LADRC_ERR_TD_ACCEL_RAD_S2: return td_accel;
    case LADRC_ERR_LEVANT_LIPSCHITZ:
    case LADRC_ERR_LEVANT_RANGE: return levant;
    case LADRC_ERR_PID_KP: return kp;
    case LADRC_ERR_PID_KI: return ki;
    case LADRC_ERR_PID_KD: return kd;
    case LADRC_ERR_INDI_ATT_KP: return indi_att;
    case LADRC_ERR_INDI_RATE_KP: return indi_rate;
    case LADRC_ERR_INDI_FILTER: return indi_filter;
    case LADRC_ERR_CAS_ATT_KP: return cas_att;
    case LADRC_ERR_CAS_RATE_MAX: return cas_max;
    case LADRC_ERR_CAS_RATE_KP: return cas_kp;
    case LADRC_ERR_CAS_RATE_KI: return cas_ki;
    case LADRC_ERR_CAS_RATE_KD: return cas_kd;
    case LADRC_ERR_CAS_D_TAU_S:
    case LADRC_ERR_CAS_RATE_TAU_S: return cas_tau;
    case LADRC_ERR_CAS_I_LIMIT_NM: return cas_i;
    case LADRC_ERR_HP_FREQ_RAD_S: return freqs;
    /* the fastest tone is a known frequency, or else the search range's top */
    case LADRC_ERR_HP_FIT_DECIMATION: return known_freqs ? freqs : dt;
    case LADRC_ERR_HP_N_TONES: return tones;
    case LADRC_ERR_MIXER_KL_N_S2: return mixer_kl;
    case LADRC_ERR_MIXER_ARM_M: return mixer_arm;
    case LADRC_ERR_MIXER_B_NM_S2: return mixer_b;
    case LADRC_ERR_MIXER_MASS_KG: return mixer_mass;
    case LADRC_ERR_MIXER_G_M_S2: return mixer_g;
    case LADRC_ERR_MIXER_W2_MIN: return w2_min;
    case LADRC_ERR_MIXER_W2_MAX: return w2_max;
    case LADRC_ERR_MIXER_TILT_MAX_RAD: return tilt;
    case LADRC_ERR_MOTOR_TAU_S: return motor_tau;
    case LADRC_ERR_DELAY_TICKS: return delay;
    default: return dt; /* the rest depend on the period alone (and library constants) */
    }
}

static const key_ref_t *keys_of_differentiator_status(ladrc_status_t st)
{
    static const key_ref_t levant[] = {
        {SEC_DIFFERENTIATOR, "levant_lipschitz_rad_s4"}, {SEC_RUN, "control_dt_s"}, END_KEYS};
    static const key_ref_t td_accel[] = {{SEC_DIFFERENTIATOR, "td_accel_rad_s2"}, END_KEYS};
    static const key_ref_t td_h0[] = {{SEC_DIFFERENTIATOR, "td_h0_s"}, {SEC_RUN, "control_dt_s"}, END_KEYS};
    switch (st) {
    case LADRC_ERR_LEVANT_LIPSCHITZ:
    case LADRC_ERR_LEVANT_RANGE: return levant;
    case LADRC_ERR_TD_ACCEL_RAD_S2: return td_accel;
    case LADRC_ERR_TD_H0_S: return td_h0;
    default: return keys_of_status(st, 0);
    }
}

/* The first key of keys the file gives (errors point at its value); else
 * the controller's section header (ctrl_sec >= 0), else line 1. */
static loc_t locate(const parser_t *p, const key_ref_t *keys, int ctrl_sec)
{
    for (const key_ref_t *k = keys; k->name != NULL; ++k) {
        const int sec = k->sec == CTRL_SEC ? ctrl_sec : k->sec;
        if (sec < 0) {
            continue;
        }
        const loc_t *at = seen_key(p, sec, k->name);
        if (at->line != 0) {
            return *at;
        }
    }
    const loc_t header = {ctrl_sec >= 0 && p->section_line[ctrl_sec] != 0 ? p->section_line[ctrl_sec] : 1, 1, 1};
    return header;
}

static void PRINTF_LIKE(4, 5) set_error(sim_parse_error_t *err, const char *path, loc_t at, const char *format, ...)
{
    memset(err, 0, sizeof *err);
    snprintf(err->path, sizeof err->path, "%s", path);
    va_list ap;
    va_start(ap, format);
    vset_error(err, at.line, at.value_col, format, ap);
    va_end(ap);
}

/* Each controller on the scenario: an error for a listed one, kept in
 * controller_error for the others (sim_scenario_set_controllers). */
static void check_controllers(parser_t *p)
{
    sim_scenario_t *sc = p->sc;
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        ladrc_attitude_config_t cfg;
        ladrc_attitude_t att;
        sim_setup_attitude(sc, (sim_controller_id_t)id, &cfg);
        const ladrc_status_t st = ladrc_attitude_init(&att, &cfg, NULL);
        int listed = 0;
        for (int i = 0; i < sc->n_controllers; ++i) {
            listed |= (int)sc->controllers[i] == id;
        }
        if (st == LADRC_OK && sim_controller_needs_rate((sim_controller_id_t)id) && !sc->use_rate) {
            static const key_ref_t use_rate[] = {{SEC_SENSORS, "use_rate"}, END_KEYS};
            const loc_t at = locate(p, use_rate, -1);
            if (listed) {
                check_fail(p, at.line, at.value_col, "INDI needs the measured rate ([sensors] use_rate = yes)");
            } else {
                set_error(&sc->controller_error[id], sc->path, at,
                          "INDI needs the measured rate ([sensors] use_rate = yes)");
            }
            continue;
        }
        if (st == LADRC_OK) {
            continue;
        }
        const int known = cfg.axis[0].hp_freq_mode == LADRC_HP_FREQ_KNOWN;
        const loc_t at = locate(p, keys_of_status(st, known), SEC_CONTROLLER + id);
        if (listed) {
            check_fail(p, at.line, at.value_col, "%s does not start: %s", CONTROLLER_NAMES[id], ladrc_status_str(st));
        } else {
            set_error(&sc->controller_error[id], sc->path, at, "%s does not start: %s", CONTROLLER_NAMES[id],
                      ladrc_status_str(st));
        }
    }
    ladrc_mixer_config_t mix;
    ladrc_mixer_t mixer;
    sim_setup_mixer(sc, &mix);
    const ladrc_status_t st = ladrc_mixer_init(&mixer, &mix);
    if (st != LADRC_OK) {
        const loc_t at = locate(p, keys_of_status(st, 0), -1);
        check_fail(p, at.line, at.value_col, "the mixer does not start: %s", ladrc_status_str(st));
    }
}

static void check_differentiators(parser_t *p)
{
    ladrc_levant_config_t lcfg;
    ladrc_td_config_t tcfg;
    ladrc_levant_t lev;
    ladrc_td_t td;
    sim_setup_differentiators(p->sc, &lcfg, &tcfg);
    ladrc_status_t st = ladrc_levant_init(&lev, &lcfg);
    const char *which = "Levant's differentiator";
    if (st == LADRC_OK) {
        st = ladrc_td_init(&td, &tcfg);
        which = "the tracking differentiator";
    }
    if (st != LADRC_OK) {
        const loc_t at = locate(p, keys_of_differentiator_status(st), -1);
        check_fail(p, at.line, at.value_col, "%s does not start: %s", which, ladrc_status_str(st));
    }
}

/* Fills what depends on other keys: metric windows, controllers, output directory. */
static void finish(parser_t *p)
{
    sim_scenario_t *sc = p->sc;
    if (seen_key(p, SEC_METRICS, "error_window_s")->line == 0 &&
        seen_key(p, SEC_DIFFERENTIATOR, "error_window_s")->line == 0) {
        sc->error_window_s[0] = 0.0;
        sc->error_window_s[1] = sc->duration_s;
    }
    if (seen_key(p, SEC_METRICS, "steady_window_s")->line == 0) {
        sc->steady_window_s[0] = 0.0;
        sc->steady_window_s[1] = sc->duration_s;
    }
    if (seen_key(p, SEC_METRICS, "settle_window_s")->line == 0) {
        sc->settle_after_s = 0.0;
        sc->settle_until_s = sc->duration_s;
    }
    if (sc->kind == SIM_KIND_DIFFERENTIATOR) {
        sc->n_controllers = 0; /* it runs the two differentiators, no controller */
    }
    if (sc->output_dir[0] == '\0') {
        snprintf(sc->output_dir, sizeof sc->output_dir, "out/%s", sc->name);
    }
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        const loc_t *tune = seen_key(p, SEC_CONTROLLER + id, "tune");
        sc->tune_line[id] = tune->line;
        sc->tune_column[id] = tune->value_col;
    }
}

/* name = the file name without directories and its last extension */
static void set_name(sim_scenario_t *sc, const char *path)
{
    const char *base = path;
    for (const char *s = path; *s != '\0'; ++s) {
        if (*s == '/' || *s == '\\') {
            base = s + 1;
        }
    }
    size_t len = strlen(base);
    const char *dot = strrchr(base, '.');
    if (dot != NULL && dot != base) {
        len = (size_t)(dot - base);
    }
    if (len == 0) {
        base = "scenario";
        len = strlen(base);
    }
    if (len >= SIM_NAME_LEN) {
        len = SIM_NAME_LEN - 1;
    }
    memcpy(sc->name, base, len);
    sc->name[len] = '\0';
}

static void copy_path(char *dst, const char *path)
{
    snprintf(dst, SIM_PATH_LEN, "%s", path);
}

static int parse_lines(parser_t *p, char *text)
{
    if (strncmp(text, "\xEF\xBB\xBF", 3) == 0) {
        text += 3; /* UTF-8 byte order mark */
    }
    char *next = text;
    while (next != NULL) {
        char *line = next;
        char *nl = strchr(line, '\n');
        next = NULL;
        if (nl != NULL) {
            *nl = '\0';
            next = nl + 1;
        }
        ++p->line;
        p->line_start = line;
        char *hash = strchr(line, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        trim_end(line);
        char *s = skip_space(line);
        if (*s == '\0') {
            continue;
        }
        const int rc = (*s == '[') ? parse_section(p, s) : parse_key_line(p, s);
        if (rc != 0) {
            return -1;
        }
    }
    return 0;
}

/* 1-based line and column of data[at] */
static void position_of(const char *data, size_t at, int *line, int *column)
{
    size_t line_start = 0;
    *line = 1;
    for (size_t i = 0; i < at; ++i) {
        if (data[i] == '\n') {
            ++*line;
            line_start = i + 1;
        }
    }
    *column = (int)(at - line_start) + 1;
}

int sim_scenario_parse_buffer(sim_scenario_t *sc, const char *data, size_t len, const char *path,
                              sim_parse_error_t *err)
{
    return sim_scenario_parse_buffer_with(sc, data, len, path, NULL, 0, err);
}

/* The command line's settings, after the file's lines. */
static int parse_settings(parser_t *p, const char *const *sets, int n_sets)
{
    p->first_set_line = p->line + 1;
    p->sc->first_set_line = p->first_set_line;
    for (int i = 0; i < n_sets; ++i) {
        p->line = p->first_set_line + i;
        const size_t n = strlen(sets[i]);
        char *copy = malloc(n + 1);
        if (copy == NULL) {
            return fail_at(p, p->line, 1, "out of memory");
        }
        memcpy(copy, sets[i], n + 1);
        const int rc = parse_setting(p, copy);
        free(copy);
        if (rc != 0) {
            return -1;
        }
    }
    return 0;
}

int sim_scenario_parse_buffer_with(sim_scenario_t *sc, const char *data, size_t len, const char *path,
                                   const char *const *sets, int n_sets, sim_parse_error_t *err)
{
    sim_parse_error_t ignored;
    if (err == NULL) {
        err = &ignored;
    }
    if (path == NULL) {
        path = "";
    }
    memset(err, 0, sizeof *err);
    copy_path(err->path, path);
    if (sc == NULL || data == NULL) {
        snprintf(err->message, sizeof err->message, "no scenario or no text");
        return -1;
    }
    const char *nul = memchr(data, '\0', len);
    if (nul != NULL) {
        position_of(data, (size_t)(nul - data), &err->line, &err->column);
        snprintf(err->message, sizeof err->message, "unexpected NUL byte");
        return -1;
    }
    set_defaults(sc);
    copy_path(sc->path, path);
    set_name(sc, path);

    parser_t *p = calloc(1, sizeof *p);
    char *copy = malloc(len + 1);
    if (p == NULL || copy == NULL) {
        free(p);
        free(copy);
        snprintf(err->message, sizeof err->message, "out of memory");
        return -1;
    }
    memcpy(copy, data, len);
    copy[len] = '\0';
    p->sc = sc;
    p->err = err;
    p->section = -1;

    int rc = parse_lines(p, copy);
    if (rc == 0 && n_sets > 0) {
        rc = parse_settings(p, sets, n_sets);
    }
    if (rc == 0) {
        check_kind(p);
        check_run(p);
        if (sc->kind == SIM_KIND_ATTITUDE) {
            check_rotors(p);
            check_tuning(p);
        } else {
            check_differentiator(p);
        }
        /* the library's own checks, once the file is consistent */
        if (!p->checked) {
            if (sc->kind == SIM_KIND_ATTITUDE) {
                check_controllers(p);
            } else {
                check_differentiators(p);
            }
        }
        rc = p->checked ? -1 : 0;
    }
    if (rc == 0) {
        finish(p);
    }
    err->first_set_line = p->first_set_line;
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        sc->controller_error[id].first_set_line = p->first_set_line;
    }
    free(copy);
    free(p);
    return rc;
}

int sim_scenario_parse(sim_scenario_t *sc, const char *text, const char *path, sim_parse_error_t *err)
{
    return sim_scenario_parse_buffer(sc, text, text != NULL ? strlen(text) : 0u, path, err);
}

int sim_scenario_set_controllers(sim_scenario_t *sc, const sim_controller_id_t *ids, int n, sim_parse_error_t *err)
{
    sim_parse_error_t ignored;
    if (err == NULL) {
        err = &ignored;
    }
    memset(err, 0, sizeof *err);
    if (sc == NULL || ids == NULL || n < 1 || n > SIM_MAX_CONTROLLERS) {
        snprintf(err->message, sizeof err->message, "expected 1 to %d controllers", SIM_MAX_CONTROLLERS);
        return -1;
    }
    copy_path(err->path, sc->path);
    for (int i = 0; i < n; ++i) {
        if ((int)ids[i] < 0 || ids[i] >= SIM_CTRL_COUNT) {
            snprintf(err->message, sizeof err->message, "unknown controller %d", (int)ids[i]);
            return -1;
        }
        for (int k = 0; k < i; ++k) {
            if (ids[k] == ids[i]) {
                snprintf(err->message, sizeof err->message, "controller '%s' listed twice", CONTROLLER_NAMES[ids[i]]);
                return -1;
            }
        }
        if (sc->kind == SIM_KIND_ATTITUDE && sc->controller_error[ids[i]].line != 0) {
            *err = sc->controller_error[ids[i]];
            return -1;
        }
    }
    for (int i = 0; i < n; ++i) {
        sc->controllers[i] = ids[i];
    }
    sc->n_controllers = n;
    return 0;
}

int sim_scenario_load(sim_scenario_t *sc, const char *path, sim_parse_error_t *err)
{
    return sim_scenario_load_with(sc, path, NULL, 0, err);
}

int sim_scenario_load_with(sim_scenario_t *sc, const char *path, const char *const *sets, int n_sets,
                           sim_parse_error_t *err)
{
    sim_parse_error_t ignored;
    if (err == NULL) {
        err = &ignored;
    }
    memset(err, 0, sizeof *err);
    copy_path(err->path, path != NULL ? path : "");
    FILE *f = (path != NULL) ? fopen(path, "rb") : NULL;
    if (f == NULL) {
        snprintf(err->message, sizeof err->message, "cannot open: %s", path != NULL ? strerror(errno) : "no path");
        return -1;
    }
    size_t cap = 4096;
    size_t len = 0;
    char *text = malloc(cap);
    while (text != NULL) {
        len += fread(text + len, 1, cap - 1 - len, f);
        if (len < cap - 1) {
            break;
        }
        char *grown = realloc(text, cap * 2);
        if (grown == NULL) {
            free(text);
            text = NULL;
        } else {
            text = grown;
            cap *= 2;
        }
    }
    const int read_error = ferror(f);
    fclose(f);
    if (text == NULL || read_error) {
        snprintf(err->message, sizeof err->message, text == NULL ? "out of memory" : "read error");
        free(text);
        return -1;
    }
    const int rc = sim_scenario_parse_buffer_with(sc, text, len, path, sets, n_sets, err);
    free(text);
    return rc;
}
