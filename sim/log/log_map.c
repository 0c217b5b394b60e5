/* SPDX-License-Identifier: BSD-3-Clause */
/* Mapping items and the forms' presets (log_map.h). */
#include "log_map.h"

#include "log_csv.h"

#include <stdio.h>
#include <string.h>

#define DEG_TO_RAD (3.14159265358979323846 / 180.0)
#define SHOWN_ITEM 100 /* characters of an item quoted in a message */
#define SHOWN 60       /* of a part of it */

static const struct {
    const char *name;
    int count;
} GROUPS[SIM_LOG_G_COUNT] = {
    {"time", 1},
    {"gyro", 3},
    {"gyro_raw", 3},
    {"angle", 3},
    {"quat", 4},
    {"ref_angle", 3},
    {"ref_quat", 4},
    {"ref_rate", 3},
    {"command", 3},
    {"throttle", 1},
    {"motor", SIM_LOG_MAX_MOTORS},
    {"rotor_hz", SIM_LOG_MAX_MOTORS},
};

/* A preset: each item with '#' standing for the component, for 0..n-1. */
typedef struct {
    const char *text;
    int n;
} preset_item_t;

/* blackbox_decode names the unit of the time and the gyro by its flags
 * (--unit-frame-time us|ms|s, --unit-rotation raw|deg/s|rad/s): a term's
 * `(unit)` reads the column in any of them, converted (log_units.h); the
 * raw gyro, unsuffixed, is deg/s in Betaflight (its header's gyro_scale 1). */
static const preset_item_t BETAFLIGHT[] = {
    {"time=time (us)*us", 1},
    {"gyro[#]=gyroADC[#] (deg/s)*deg", 3},
    {"gyro_raw[#]=?gyroUnfilt[#]*deg", 3},
    {"ref_rate[#]=?setpoint[#]*deg", 3},
    /* yaw's axisD[2] is usually not logged */
    {"command[#]=axisP[#]+?axisI[#]+?axisD[#]+?axisF[#]*0.001", 3},
    {"throttle=?setpoint[3]*0.001", 1},
    {"motor[#]=?motor[#]", SIM_LOG_MAX_MOTORS},
    /* eRPM/100 logged, 14 poles: Hz = eRPM * 100 / 60 / 7 */
    {"rotor_hz[#]=?eRPM[#]*0.238095238", SIM_LOG_MAX_MOTORS},
};

/* Each topic's `timestamp` is its time: no time item. */
static const preset_item_t PX4[] = {
    {"gyro[#]=vehicle_angular_velocity.xyz[#]", 3},
    {"gyro_raw[#]=?sensor_combined.gyro_rad[#]", 3},
    {"quat[#]=vehicle_attitude.q[#]", 4},
    {"ref_quat[#]=?vehicle_attitude_setpoint.q_d[#]", 4},
    {"ref_rate[0]=?vehicle_rates_setpoint.roll", 1},
    {"ref_rate[1]=?vehicle_rates_setpoint.pitch", 1},
    {"ref_rate[2]=?vehicle_rates_setpoint.yaw", 1},
    {"command[#]=vehicle_torque_setpoint.xyz[#]", 3},
    {"throttle=?vehicle_attitude_setpoint.thrust_body[2]*-1", 1}, /* thrust is along -z */
    {"motor[#]=?actuator_motors.control[#]", SIM_LOG_MAX_MOTORS},
    {"rotor_hz[#]=?esc_status.esc[#].esc_rpm*0.0166666667", SIM_LOG_MAX_MOTORS},
};

/* How a Betaflight log gets each column the preset reads (the switches are
 * Betaflight 4.3's and later's; before, each group was always logged). */
static const struct {
    const char *base;
    const char *hint;
} HINTS[] = {
    {"time", "blackbox_decode writes 'time (us)' under every --unit-frame-time (us, ms, s)"},
    {"gyroADC", "logged unless blackbox_disable_gyro = ON; blackbox_decode names it 'gyroADC[i] (deg/s)' or "
                "'(rad/s)' under --unit-rotation, plain under raw"},
    {"axisP", "logged unless blackbox_disable_pids = ON"},
    {"axisI", "logged unless blackbox_disable_pids = ON"},
    {"axisD", "logged unless blackbox_disable_pids = ON"},
    {"axisF", "logged unless blackbox_disable_pids = ON"},
    {"setpoint", "logged unless blackbox_disable_setpoint = ON"},
    {"gyroUnfilt", "logged by Betaflight 4.3 and later unless blackbox_disable_gyrounfilt = ON; before, "
                   "debug_mode = GYRO_SCALED logs it as debug[0..2]"},
    {"motor", "logged unless blackbox_disable_motors = ON"},
    {"eRPM", "logged with dshot_bidir = ON unless blackbox_disable_rpm = ON"},
    {"debug", "logged unless blackbox_disable_debug = ON; what it holds is the log's debug_mode"},
};

const char *sim_log_column_hint(const char *column)
{
    for (size_t i = 0; i < sizeof HINTS / sizeof HINTS[0]; ++i) {
        const size_t n = strlen(HINTS[i].base);
        if (strncmp(column, HINTS[i].base, n) == 0 && (column[n] == '[' || column[n] == ' ' || column[n] == '\0')) {
            return HINTS[i].hint;
        }
    }
    return NULL;
}

/* ArduPilot (docs/flight-logs.md has the table): the units ArduPilot logs
 * these fields in (IMU rad/s, ATT deg, RATE deg/s, RCOU us, ESC rpm), the
 * same from Copter 3.6 to 4.6; each topic's TimeUS is its time. */
static const preset_item_t ARDUPILOT[] = {
    {"gyro[0]=IMU.GyrX", 1},
    {"gyro[1]=IMU.GyrY", 1},
    {"gyro[2]=IMU.GyrZ", 1},
    {"gyro_raw[0]=?GYR.GyrX", 1},
    {"gyro_raw[1]=?GYR.GyrY", 1},
    {"gyro_raw[2]=?GYR.GyrZ", 1},
    {"angle[0]=ATT.Roll*deg", 1},
    {"angle[1]=ATT.Pitch*deg", 1},
    {"angle[2]=ATT.Yaw*deg", 1},
    {"ref_angle[0]=ATT.DesRoll*deg", 1},
    {"ref_angle[1]=ATT.DesPitch*deg", 1},
    {"ref_angle[2]=ATT.DesYaw*deg", 1},
    {"motor[0]=?RCOU.C1", 1},
    {"motor[1]=?RCOU.C2", 1},
    {"motor[2]=?RCOU.C3", 1},
    {"motor[3]=?RCOU.C4", 1},
    {"motor[4]=?RCOU.C5", 1},
    {"motor[5]=?RCOU.C6", 1},
    {"motor[6]=?RCOU.C7", 1},
    {"motor[7]=?RCOU.C8", 1},
    {"rotor_hz[#]=?ESC[#].RPM*0.0166666667", SIM_LOG_MAX_MOTORS}, /* rpm / 60 */
};

/* The rate loop's setpoint and output (-1..1) and the throttle (0..1). */
static const preset_item_t ARDUPILOT_RATE[] = {
    {"ref_rate[0]=?RATE.RDes*deg", 1}, {"ref_rate[1]=?RATE.PDes*deg", 1}, {"ref_rate[2]=?RATE.YDes*deg", 1},
    {"command[0]=RATE.ROut", 1},       {"command[1]=RATE.POut", 1},       {"command[2]=RATE.YOut", 1},
    {"throttle=?RATE.AOut", 1},
};

/* Logs without RATE (Copter before 3.6): the rate PIDs' terms, whose sum is
 * what the rate loop gave the motors (FF from 3.5 on), and CTUN's throttle. */
static const preset_item_t ARDUPILOT_PID[] = {
    {"command[0]=PIDR.P+PIDR.I+PIDR.D+?PIDR.FF", 1},
    {"command[1]=PIDP.P+PIDP.I+PIDP.D+?PIDP.FF", 1},
    {"command[2]=PIDY.P+PIDY.I+PIDY.D+?PIDY.FF", 1},
    {"throttle=?CTUN.ThO", 1},
};

/* The same fields from the topics of older PX4 releases, each read when
 * the preset's topic file is missing and its own is there (log_px4.h). */
static const preset_item_t PX4_FALLBACK[] = {
    /* older releases' vehicle_attitude carried the body rates (v1.6 did, v1.11 does not) */
    {"gyro[0]=vehicle_attitude.rollspeed", 1},
    {"gyro[1]=vehicle_attitude.pitchspeed", 1},
    {"gyro[2]=vehicle_attitude.yawspeed", 1},
    /* before v1.13: actuator_controls_0's roll, pitch, yaw (thrust is control[3]) */
    {"command[#]=actuator_controls_0.control[#]", 3},
    /* before v1.13: the outputs (PWM, us) */
    {"motor[#]=?actuator_outputs.output[#]", SIM_LOG_MAX_MOTORS},
};

/* Each group's first slot: the counts of GROUPS summed. */
static const int FIRST[SIM_LOG_G_COUNT + 1] = {0, 1, 4, 7, 10, 14, 17, 21, 24, 27, 28, 36, SIM_LOG_N_SLOTS};

int sim_log_group_first(sim_log_group_t g)
{
    return FIRST[g];
}

int sim_log_group_count(sim_log_group_t g)
{
    return GROUPS[g].count;
}

sim_log_group_t sim_log_slot_group(int slot)
{
    int g = 0;
    while (g + 1 < SIM_LOG_G_COUNT && slot >= FIRST[g + 1]) {
        ++g;
    }
    return (sim_log_group_t)g;
}

void sim_log_slot_name(int slot, char *buf, size_t len)
{
    const sim_log_group_t g = sim_log_slot_group(slot);
    if (GROUPS[g].count == 1) {
        snprintf(buf, len, "%s", GROUPS[g].name);
    } else {
        snprintf(buf, len, "%s[%d]", GROUPS[g].name, slot - sim_log_group_first(g));
    }
}

static int is_blank(char ch)
{
    return ch == ' ' || ch == '\t';
}

/* [*start, *end) without the blanks around it. */
static void trim(const char **start, const char **end)
{
    while (*start < *end && is_blank(**start)) {
        ++*start;
    }
    while (*end > *start && is_blank((*end)[-1])) {
        --*end;
    }
}

static int item_error(char *msg, size_t len, const char *text, const char *what, const char *p, size_t n)
{
    snprintf(msg, len, "map item '%.*s': %s '%.*s'", SHOWN_ITEM, text, what, (int)(n > SHOWN ? SHOWN : n), p);
    return -1;
}

/* FIELD or FIELD[i], into a slot. */
static int parse_field(const char *text, const char *p, const char *end, int *slot, char *msg, size_t len)
{
    trim(&p, &end);
    const char *bracket = memchr(p, '[', (size_t)(end - p));
    const char *name_end = bracket != NULL ? bracket : end;
    int g = 0;
    while (g < SIM_LOG_G_COUNT && !(strlen(GROUPS[g].name) == (size_t)(name_end - p) &&
                                    memcmp(GROUPS[g].name, p, (size_t)(name_end - p)) == 0)) {
        ++g;
    }
    if (g == SIM_LOG_G_COUNT) {
        return item_error(msg, len, text, "unknown field", p, (size_t)(end - p));
    }
    int index = 0;
    if (bracket != NULL) {
        const char *q = bracket + 1;
        index = -1;
        if (q < end && *q >= '0' && *q <= '9' && end - q == 2 && end[-1] == ']') {
            index = *q - '0';
        }
        if (GROUPS[g].count == 1 || index < 0 || index >= GROUPS[g].count) {
            return item_error(msg, len, text, "no such component of the field:", p, (size_t)(end - p));
        }
    } else if (GROUPS[g].count > 1) {
        return item_error(msg, len, text, "the field needs its component, [0] and up:", p, (size_t)(end - p));
    }
    *slot = sim_log_group_first((sim_log_group_t)g) + index;
    return 0;
}

/* `*0.001`, `*deg`, `*us`, `*ms`, `*-1`, and their products. */
static int parse_scale(const char *text, const char *p, const char *end, double *scale, char *msg, size_t len)
{
    *scale = 1.0;
    for (;;) {
        const char *star = memchr(p, '*', (size_t)(end - p));
        const char *f_end = star != NULL ? star : end;
        const char *f = p;
        double v;
        trim(&f, &f_end);
        const size_t n = (size_t)(f_end - f);
        if (n == 3 && memcmp(f, "deg", 3) == 0) {
            v = DEG_TO_RAD;
        } else if (n == 2 && memcmp(f, "us", 2) == 0) {
            v = 1e-6;
        } else if (n == 2 && memcmp(f, "ms", 2) == 0) {
            v = 1e-3;
        } else if (sim_log_number(f, n, &v) != 0) {
            return item_error(msg, len, text, "bad scale (a number, deg, us or ms):", f, n);
        }
        *scale *= v;
        if (star == NULL) {
            return 0;
        }
        p = star + 1;
    }
}

/* One term; with topics, its topic must be the item's (the first term's). */
static int parse_term(const char *text, const char *p, const char *end, int topics, sim_log_item_t *it, char *msg,
                      size_t len)
{
    sim_log_term_t *t = &it->term[it->n_terms - 1];
    trim(&p, &end);
    if (p < end && *p == '?') {
        t->optional = 1;
        ++p;
        trim(&p, &end);
    }
    const char *column = p;
    if (topics) {
        const char *dot = memchr(p, '.', (size_t)(end - p));
        if (dot == NULL || dot == p || dot + 1 == end) {
            return item_error(msg, len, text, "a source is topic.column, not", p, (size_t)(end - p));
        }
        const size_t n = (size_t)(dot - p);
        if (n >= SIM_LOG_NAME_LEN) {
            return item_error(msg, len, text, "topic name too long:", p, n);
        }
        if (it->n_terms == 1) {
            memcpy(it->topic, p, n);
        } else if (strlen(it->topic) != n || memcmp(it->topic, p, n) != 0) {
            return item_error(msg, len, text, "the columns of an item are of one topic, not", p, n);
        }
        column = dot + 1;
    }
    if (column == end) {
        return item_error(msg, len, text, "empty column name", p, 0);
    }
    if ((size_t)(end - column) >= SIM_LOG_NAME_LEN) {
        return item_error(msg, len, text, "column name too long:", column, (size_t)(end - column));
    }
    memcpy(t->column, column, (size_t)(end - column));
    return 0;
}

int sim_log_item_parse(const char *text, int topics, sim_log_item_t *it, char *msg, size_t len)
{
    memset(it, 0, sizeof *it);
    const char *eq = strchr(text, '=');
    const char *end = text + strlen(text);
    if (eq == NULL) {
        return item_error(msg, len, text, "no '=' (FIELD=SOURCE) in", text, (size_t)(end - text));
    }
    if (parse_field(text, text, eq, &it->slot, msg, len) != 0) {
        return -1;
    }
    const char *star = memchr(eq + 1, '*', (size_t)(end - eq - 1));
    const char *terms_end = star != NULL ? star : end;
    if (star != NULL && parse_scale(text, star + 1, end, &it->scale, msg, len) != 0) {
        return -1;
    }
    if (star == NULL) {
        it->scale = 1.0;
    }
    for (const char *p = eq + 1;;) {
        const char *plus = memchr(p, '+', (size_t)(terms_end - p));
        const char *t_end = plus != NULL ? plus : terms_end;
        if (it->n_terms == SIM_LOG_TERMS_MAX) {
            return item_error(msg, len, text, "more than 8 columns summed in", text, (size_t)(end - text));
        }
        ++it->n_terms;
        if (parse_term(text, p, t_end, topics, it, msg, len) != 0) {
            return -1;
        }
        if (plus == NULL) {
            break;
        }
        p = plus + 1;
    }
    if (topics && it->slot == sim_log_group_first(SIM_LOG_G_TIME)) {
        return item_error(msg, len, text, "a topic form's time is each topic's own (timestamp, TimeUS), not", eq + 1,
                          (size_t)(end - eq - 1));
    }
    return 0;
}

/* text with each '#' replaced by the digit k. */
static void expand(const char *text, int k, char *out, size_t len)
{
    size_t j = 0;
    for (const char *p = text; *p != '\0' && j + 1 < len; ++p) {
        out[j++] = *p == '#' ? (char)('0' + k) : *p;
    }
    out[j] = '\0';
}

/* The preset's items into m's items, or (fallback) into its fallbacks. */
static int add_items(sim_log_map_t *m, const preset_item_t *preset, int n, int topics, int fallback, char *msg,
                     size_t len)
{
    char text[160];
    sim_log_item_t it;
    for (int i = 0; i < n; ++i) {
        for (int k = 0; k < preset[i].n; ++k) {
            expand(preset[i].text, k, text, sizeof text);
            if (sim_log_item_parse(text, topics, &it, msg, len) != 0) {
                return -1;
            }
            if (fallback) {
                m->fallback[it.slot] = it;
                m->has_fallback[it.slot] = 1;
            } else {
                m->item[it.slot] = it;
                m->mapped[it.slot] = 1;
            }
        }
    }
    return 0;
}

/* Generic: every field optional under its own name, the time required. */
static int add_generic(sim_log_map_t *m, char *msg, size_t len)
{
    char name[32], text[80];
    for (int slot = 0; slot < SIM_LOG_N_SLOTS; ++slot) {
        sim_log_slot_name(slot, name, sizeof name);
        snprintf(text, sizeof text, "%s=%s%s", name, slot == 0 ? "" : "?", name);
        if (sim_log_item_parse(text, 0, &m->item[slot], msg, len) != 0) {
            return -1;
        }
        m->mapped[slot] = 1;
    }
    return 0;
}

#define N_ITEMS(a) ((int)(sizeof(a) / sizeof((a)[0])))

static int build(sim_log_map_t *m, sim_log_format_t format, int with_rate, const char *const *items, int n_items,
                 char *msg, size_t len)
{
    const int topics = sim_log_format_has_topics(format);
    int rc;
    memset(m, 0, sizeof *m);
    if (format == SIM_LOG_BETAFLIGHT) {
        rc = add_items(m, BETAFLIGHT, N_ITEMS(BETAFLIGHT), 0, 0, msg, len);
    } else if (format == SIM_LOG_PX4) {
        rc = add_items(m, PX4, N_ITEMS(PX4), 1, 0, msg, len);
        rc = rc == 0 ? add_items(m, PX4_FALLBACK, N_ITEMS(PX4_FALLBACK), 1, 1, msg, len) : rc;
    } else if (format == SIM_LOG_ARDUPILOT) {
        rc = add_items(m, ARDUPILOT, N_ITEMS(ARDUPILOT), 1, 0, msg, len);
        if (rc == 0) {
            rc = with_rate ? add_items(m, ARDUPILOT_RATE, N_ITEMS(ARDUPILOT_RATE), 1, 0, msg, len)
                           : add_items(m, ARDUPILOT_PID, N_ITEMS(ARDUPILOT_PID), 1, 0, msg, len);
        }
    } else {
        rc = add_generic(m, msg, len);
    }
    for (int i = 0; rc == 0 && i < n_items; ++i) {
        sim_log_item_t it;
        if (items[i] == NULL) {
            snprintf(msg, len, "map item %d is NULL", i + 1);
            return -1;
        }
        rc = sim_log_item_parse(items[i], topics, &it, msg, len);
        if (rc == 0) {
            m->item[it.slot] = it;
            m->mapped[it.slot] = 1;
            m->has_fallback[it.slot] = 0; /* the caller's item is the one read */
        }
    }
    return rc;
}

int sim_log_map_build(sim_log_map_t *m, sim_log_format_t format, const char *const *items, int n_items, char *msg,
                      size_t len)
{
    return build(m, format, 1, items, n_items, msg, len);
}

int sim_log_map_build_ardupilot(sim_log_map_t *m, int with_rate, const char *const *items, int n_items, char *msg,
                                size_t len)
{
    return build(m, SIM_LOG_ARDUPILOT, with_rate, items, n_items, msg, len);
}
