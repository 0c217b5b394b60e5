/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit suffixes of column names (log_units.h). */
#include "log_units.h"

#include <string.h>

#define PI 3.14159265358979323846

typedef enum { Q_TIME, Q_RATE, Q_VOLTAGE, Q_CURRENT, Q_LENGTH, Q_ACCELERATION, Q_SPEED, Q_ANGLE } quantity_t;

/* The units blackbox_decode's flags name (its --unit-* options), each with
 * its size in the smallest of its quantity listed, so that the time's
 * factors to microseconds are whole and exact. */
static const struct {
    const char *name;
    quantity_t q;
    double size;
} UNITS[] = {
    {"us", Q_TIME, 1.0},
    {"ms", Q_TIME, 1e3},
    {"s", Q_TIME, 1e6},
    {"deg/s", Q_RATE, 1.0},
    {"rad/s", Q_RATE, 180.0 / PI},
    {"mV", Q_VOLTAGE, 1.0},
    {"V", Q_VOLTAGE, 1e3},
    {"mA", Q_CURRENT, 1.0},
    {"A", Q_CURRENT, 1e3},
    {"cm", Q_LENGTH, 1.0},
    {"m", Q_LENGTH, 100.0},
    {"ft", Q_LENGTH, 30.48},
    {"m/s/s", Q_ACCELERATION, 1.0},
    {"g", Q_ACCELERATION, 9.80665},
    {"m/s", Q_SPEED, 1.0},
    {"km/h", Q_SPEED, 1.0 / 3.6},
    {"mi/h", Q_SPEED, 0.44704},
    {"deg", Q_ANGLE, 1.0},
};

void sim_log_unit_split(const char *name, size_t len, size_t *base_len, const char **unit, size_t *unit_len)
{
    *base_len = len;
    *unit = name + len;
    *unit_len = 0;
    if (len < 3 || name[len - 1] != ')') {
        return;
    }
    const char *open = NULL;
    for (size_t i = len - 1; i-- > 0;) {
        if (name[i] == '(') {
            open = name + i;
            break;
        }
    }
    if (open == NULL || open == name || open[-1] != ' ') {
        return;
    }
    *unit = open + 1;
    *unit_len = (size_t)(name + len - 1 - *unit);
    *base_len = (size_t)(open - 1 - name);
}

static int find_unit(const char *u, size_t len)
{
    for (size_t i = 0; i < sizeof UNITS / sizeof UNITS[0]; ++i) {
        if (strlen(UNITS[i].name) == len && memcmp(UNITS[i].name, u, len) == 0) {
            return (int)i;
        }
    }
    return -1;
}

int sim_log_unit_factor(const char *from, size_t from_len, const char *to, size_t to_len, double *factor)
{
    const int a = find_unit(from, from_len), b = find_unit(to, to_len);
    if (a < 0 || b < 0 || UNITS[a].q != UNITS[b].q) {
        return -1;
    }
    *factor = a == b ? 1.0 : UNITS[a].size / UNITS[b].size;
    return 0;
}
