/* SPDX-License-Identifier: BSD-3-Clause */
/* Finding a PX4 log's topic files (log_px4.h). */
#include "log_px4.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int ends_with(const char *s, size_t n, const char *suffix)
{
    const size_t k = strlen(suffix);
    return n >= k && memcmp(s + n - k, suffix, k) == 0;
}

/* [0, n) ends in "_<topic>_<digits>": the length before it, or 0. */
static size_t strip_topic(const char *s, size_t n, const char *topic)
{
    size_t i = n;
    while (i > 0 && s[i - 1] >= '0' && s[i - 1] <= '9') {
        --i;
    }
    if (i == n || i == 0 || s[i - 1] != '_') {
        return 0;
    }
    const size_t k = strlen(topic);
    i -= 1;
    if (i < k + 2 || memcmp(s + i - k, topic, k) != 0 || s[i - k - 1] != '_') {
        return 0; /* + 2: a BASE of one character at least, and its '_' */
    }
    return i - k - 1;
}

void sim_log_px4_base(const char *path, const char *const *topics, int n_topics, char *base, size_t len)
{
    size_t n = strlen(path);
    if (ends_with(path, n, ".csv")) {
        for (int t = 0; t < n_topics; ++t) {
            const size_t b = strip_topic(path, n - 4, topics[t]);
            if (b > 0) {
                n = b;
                break;
            }
        }
    } else if (ends_with(path, n, ".ulg")) {
        n -= 4;
    }
    snprintf(base, len, "%.*s", (int)n, path);
}

int sim_log_px4_topic_path(const char *base, const char *topic, char *out, size_t len)
{
    const int n = snprintf(out, len, "%s_%s_0.csv", base, topic);
    return (n < 0 || (size_t)n >= len) ? -1 : 0;
}

int sim_log_px4_map_topics(const sim_log_map_t *m, int with_fallbacks, const char **topics)
{
    int n = 0;
    for (int pass = 0; pass <= (with_fallbacks ? 1 : 0); ++pass) {
        for (int s = 1; s < SIM_LOG_N_SLOTS; ++s) {
            const sim_log_item_t *it = pass == 0 ? &m->item[s] : &m->fallback[s];
            int seen = pass == 0 ? !m->mapped[s] : !m->has_fallback[s];
            for (int i = 0; !seen && i < n; ++i) {
                seen = strcmp(topics[i], it->topic) == 0;
            }
            if (!seen) {
                topics[n++] = it->topic;
            }
        }
    }
    return n;
}

/* The topic's file under base can be read. */
static int topic_file_exists(const char *base, const char *topic)
{
    char path[SIM_LOG_PATH_LEN + SIM_LOG_NAME_LEN + 16];
    FILE *f = sim_log_px4_topic_path(base, topic, path, sizeof path) == 0 ? fopen(path, "rb") : NULL;
    if (f != NULL) {
        fclose(f);
    }
    return f != NULL;
}

void sim_log_px4_choose(sim_log_map_t *m, const char *base)
{
    for (int s = 1; s < SIM_LOG_N_SLOTS; ++s) {
        if (m->mapped[s] && m->has_fallback[s] && !topic_file_exists(base, m->item[s].topic) &&
            topic_file_exists(base, m->fallback[s].topic)) {
            const sim_log_item_t newer = m->item[s];
            m->item[s] = m->fallback[s];
            m->fallback[s] = newer; /* named when neither is there */
        }
    }
}

int sim_log_px4_topics(const char *const *items, int n_items, sim_log_px4_topics_t *t, char *msg, size_t len)
{
    sim_log_map_t *m = malloc(sizeof *m); /* some 80 KB */
    const char *topics[SIM_LOG_PX4_TOPICS_MAX];
    memset(t, 0, sizeof *t);
    if (m == NULL) {
        snprintf(msg, len, "out of memory");
        return -1;
    }
    if (sim_log_map_build(m, SIM_LOG_PX4, items, n_items, msg, len) != 0) {
        free(m);
        return -1;
    }
    t->n = sim_log_px4_map_topics(m, 1, topics);
    for (int i = 0; i < t->n; ++i) {
        snprintf(t->name[i], sizeof t->name[i], "%s", topics[i]);
        t->list[i] = t->name[i];
    }
    free(m);
    return 0;
}
