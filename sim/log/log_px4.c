/* SPDX-License-Identifier: BSD-3-Clause */
/* Finding a PX4 log's topic files (log_px4.h). */
#include "log_px4.h"

#include <stdio.h>
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
