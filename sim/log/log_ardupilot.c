/* SPDX-License-Identifier: BSD-3-Clause */
/* Finding an ArduPilot log's type files (log_ardupilot.h). */
#include "log_ardupilot.h"

#include "log_map.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int is_alnum(char ch)
{
    return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9');
}

static int ends_with_ci(const char *s, size_t n, const char *suffix)
{
    const size_t k = strlen(suffix);
    if (n < k) {
        return 0;
    }
    for (size_t i = 0; i < k; ++i) {
        char a = s[n - k + i];
        a = (a >= 'A' && a <= 'Z') ? (char)(a - 'A' + 'a') : a;
        if (a != suffix[i]) {
            return 0;
        }
    }
    return 1;
}

void sim_log_ardupilot_base(const char *path, char *base, size_t len)
{
    size_t n = strlen(path);
    if (ends_with_ci(path, n, ".csv")) {
        size_t i = n - 4;
        while (i > 0 && path[i - 1] >= '0' && path[i - 1] <= '9') {
            --i;
        }
        if (i < n - 4 && i > 0 && path[i - 1] == '_') {
            size_t j = i - 1; /* the '_' before the instance */
            size_t k = j;
            while (k > 0 && j - k < 4 && is_alnum(path[k - 1])) {
                --k;
            }
            if (k < j && k >= 2 && path[k - 1] == '_') { /* a BASE of one character at least */
                n = k - 1;
            }
        }
    } else if (ends_with_ci(path, n, ".bin")) {
        n -= 4;
    }
    snprintf(base, len, "%.*s", (int)n, path);
}

int sim_log_ardupilot_topic_path(const char *base, const char *topic, char *out, size_t len)
{
    const char *bracket = strchr(topic, '[');
    int name_len = (int)strlen(topic), instance = 0;
    if (bracket != NULL) {
        char end = 0;
        name_len = (int)(bracket - topic);
        if (sscanf(bracket, "[%3d%c", &instance, &end) != 2 || end != ']' || instance < 0 || instance > 255 ||
            strchr(bracket, ']')[1] != '\0') {
            return -1;
        }
    }
    const int n = snprintf(out, len, "%s_%.*s_%d.csv", base, name_len, topic, instance);
    return (n < 0 || (size_t)n >= len) ? -1 : 0;
}

/* ArduCopter's LOG_BITMASK bits, and the parameters of the rest. */
static const struct {
    const char *type;
    const char *by;
} ENABLED_BY[] = {
    {"IMU", "LOG_BITMASK bit 7 IMU (or 18 IMU_FAST)"},
    {"ATT", "LOG_BITMASK bit 0 ATTITUDE_FAST or bit 1 ATTITUDE_MED"},
    {"RATE", "LOG_BITMASK bit 0 ATTITUDE_FAST or bit 1 ATTITUDE_MED (Copter 3.6 and up)"},
    {"PIDR", "LOG_BITMASK bit 12 PID"},
    {"PIDP", "LOG_BITMASK bit 12 PID"},
    {"PIDY", "LOG_BITMASK bit 12 PID"},
    {"RCOU", "LOG_BITMASK bit 10 RCOUT"},
    {"CTUN", "LOG_BITMASK bit 4 CTUN"},
    {"GYR", "LOG_BITMASK bit 19 IMU_RAW, or INS_RAW_LOG_OPT (4.5 and up)"},
    {"ESC", "ESC telemetry (DShot or BLHeli telemetry, SERVO_BLH_* / SERVO_DSHOT_*)"},
};

const char *sim_log_ardupilot_enabled_by(const char *topic)
{
    const size_t n = strcspn(topic, "[");
    for (size_t i = 0; i < sizeof ENABLED_BY / sizeof ENABLED_BY[0]; ++i) {
        if (strlen(ENABLED_BY[i].type) == n && strncmp(ENABLED_BY[i].type, topic, n) == 0) {
            return ENABLED_BY[i].by;
        }
    }
    return "";
}

static int add_topic(const char *topic, char names[][SIM_LOG_ARDUPILOT_TYPE_LEN], const char **topics, int n)
{
    const size_t len = strcspn(topic, "[");
    if (len == 0 || len >= SIM_LOG_ARDUPILOT_TYPE_LEN || n == SIM_LOG_ARDUPILOT_TOPICS_MAX) {
        return n; /* no such type: the reader refuses the item */
    }
    for (int i = 0; i < n; ++i) {
        if (strlen(names[i]) == len && strncmp(names[i], topic, len) == 0) {
            return n;
        }
    }
    memcpy(names[n], topic, len);
    names[n][len] = '\0';
    topics[n] = names[n];
    return n + 1;
}

int sim_log_ardupilot_topics(const char *const *map, int n_map, char names[][SIM_LOG_ARDUPILOT_TYPE_LEN],
                             const char **topics)
{
    sim_log_map_t *m = malloc(sizeof *m);
    char msg[256];
    int n = 0;
    for (int with_rate = 0; m != NULL && with_rate <= 1; ++with_rate) {
        /* bad items are the reader's to refuse: the preset's types then */
        if (sim_log_map_build_ardupilot(m, with_rate, map, n_map, msg, sizeof msg) != 0 &&
            sim_log_map_build_ardupilot(m, with_rate, NULL, 0, msg, sizeof msg) != 0) {
            continue;
        }
        for (int s = 0; s < SIM_LOG_N_SLOTS; ++s) {
            if (m->mapped[s]) {
                n = add_topic(m->item[s].topic, names, topics, n);
            }
        }
    }
    free(m);
    return n;
}

int sim_log_ardupilot_sample_timed(const char *topic)
{
    const size_t n = strcspn(topic, "[");
    return n == 3 && (strncmp(topic, "GYR", 3) == 0 || strncmp(topic, "ACC", 3) == 0);
}
