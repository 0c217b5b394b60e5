/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The scenario schema, internal to the parser (scenario.h is the interface):
 * the sections, every key with where it goes, its type, unit factor, range,
 * the kind and the controllers it applies to; the per-key checks; the
 * defaults of every key. The lexer (lexer.c) turns a value into numbers and
 * words, the reader (reader.c) files them by this table.
 */
#ifndef LADRC_SIM_SCHEMA_H
#define LADRC_SIM_SCHEMA_H

#include <stddef.h>

#include "scenario.h"

#define DEG_TO_RAD (3.14159265358979323846 / 180.0)
#define SCHEMA_LIST_MAX 4

/* Sections. */
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
    SEC_WIND,
    SEC_VIBRATION,
    SEC_FILTER,
    SEC_PHASES,
    SEC_EXCITATION,
    SEC_CONTROLLER, /* + controller id: one slot per [controller NAME] */
    SEC_COUNT = SEC_CONTROLLER + SIM_CTRL_COUNT
};

/* The key table of a section slot: every [controller NAME] shares one. */
#define SCHEMA_TABLE(sec) ((sec) >= SEC_CONTROLLER ? SEC_CONTROLLER : (sec))

/* The kind a section or key belongs to. */
enum { FOR_BOTH, FOR_ATTITUDE, FOR_DIFFERENTIATOR };

typedef enum {
    V_REAL,        /* one number */
    V_VEC3,        /* three numbers */
    V_VEC2,        /* two numbers */
    V_INT,         /* an integer */
    V_SEED,        /* an unsigned 64-bit integer */
    V_CHOICE,      /* one word of `choices`, stored as int */
    V_KIND,        /* attitude | differentiator */
    V_TEXT,        /* the rest of the line */
    V_CONTROLLERS, /* controller names */
    V_WINDOW,      /* FROM TO, 0 <= FROM < TO, into offset and offset2 */
    V_LIST,        /* 1 to SCHEMA_LIST_MAX numbers, their count (int) into offset2 */
    V_FLAGS,       /* words of `choices`, separated by commas, spaces or both, each once: their values or'ed (int) */
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
    R_TUNE_STEP,    /* 0 .. LADRC_MARGINS_MAX_STEP_RAD, in degrees */
    R_DURATION,     /* > 0, <= SIM_DURATION_MAX_S */
    R_CONTROL_DT,   /* SIM_CONTROL_DT_MIN_S .. SIM_CONTROL_DT_MAX_S */
    R_SUBSTEPS,     /* 1 .. SIM_PLANT_SUBSTEPS_MAX */
    R_FRACTION,     /* 0 <= v < 1 */
    R_LPF_ORDER,    /* 0, 1 or 2 */
    R_HARMONICS,    /* 0 .. 4 */
    R_ALTITUDE,     /* > 0, <= 1000 ft in m */
    R_SIGMA,        /* 0 .. 30 m/s */
    R_WIND,         /* 0 .. 50 m/s */
    R_ORDER,        /* SIM_VIB_ORDER_MIN .. SIM_VIB_ORDER_MAX */
    R_VIB_GYRO,     /* 0 .. SIM_VIB_GYRO_MAX_RAD_S (deg/s in the file) */
    R_VIB_ACCEL,    /* 0 .. SIM_VIB_ACCEL_MAX_M_S2 */
    R_VIB_GAIN,     /* 0 .. SIM_VIB_AXIS_GAIN_MAX */
    R_Q,            /* 0.1 .. 100 */
    R_HEADING,      /* 0 <= v < 360 (deg in the file) */
    R_WEIGHT,       /* 0 < v <= 1 */
    R_SLOPE,        /* -30 < v < 30 (deg in the file) */
    R_UNIT          /* 0 <= v <= 1 */
} range_t;

typedef struct {
    const char *name; /* NULL ends a list */
    int value;
} choice_t;

typedef struct {
    int section; /* SEC_*; SEC_CONTROLLER for every [controller NAME] */
    const char *name;
    value_type_t type;
    size_t offset;  /* in sim_scenario_t, or in sim_overrides_t for [controller] */
    size_t offset2; /* V_WINDOW: where TO goes */
    range_t range;
    double scale; /* file unit -> stored unit (1 when 0) */
    int variance; /* stores sqrt(value) * scale */
    const choice_t *choices;
    int kind;             /* FOR_*; FOR_BOTH: the section's */
    int required;         /* in a scenario of the key's kind */
    unsigned controllers; /* [controller]: the controllers it applies to */
    const char *twin;     /* another key that sets the same field */
} key_def_t;

/* The key table; key indices are positions in it. SCHEMA_MAX_KEYS bounds
 * the table (checked at compile time in schema.c) for the reader's arrays. */
#define SCHEMA_MAX_KEYS 160
extern const key_def_t SCHEMA_KEYS[];
extern const int SCHEMA_N_KEYS;

/* Index of key `name` of table SEC_* (SCHEMA_TABLE), or -1. */
int schema_find_key(int table, const char *name);

/* SEC_* of the section named by name[0..len-1] (SEC_CONTROLLER for
 * "controller"), or -1. */
int schema_find_section(const char *name, size_t len);

/* "[run]", "[controller PID]"... of a section slot, into buf. */
const char *schema_section_title(int sec, char *buf, size_t n);

/* FOR_* of a section slot, and of a key in a section slot (its own, or its section's). */
int schema_section_kind(int sec);
int schema_key_kind(int sec, const key_def_t *def);

/* Controller id of name[0..len-1], or -1. */
int schema_controller_id(const char *name, size_t len);

/* 1 when [controller NAME] key def applies to controller id. */
int schema_applies_to(const key_def_t *def, int id);

/* The per-key check of value v (in the file's unit): 0, or -1 with the
 * message in msg. */
int schema_check_range(const key_def_t *def, double v, char *msg, size_t msg_len);

/* Every field of sc at its default (docs/scenario-format.md); duration_s,
 * required, NaN. */
void schema_set_defaults(sim_scenario_t *sc);

#endif
