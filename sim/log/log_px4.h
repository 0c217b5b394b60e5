/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * PX4 logs as ulog2csv writes them: one CSV per topic, BASE_<topic>_<n>.csv
 * (instance n; this reader takes instance 0).
 */
#ifndef LADRC_SIM_LOG_PX4_H
#define LADRC_SIM_LOG_PX4_H

#include <stddef.h>

/* BASE from the path given: a topic file's (BASE_<topic>_<n>.csv, topic one
 * of topics), a .ulg's name without its extension, or the path itself. */
void sim_log_px4_base(const char *path, const char *const *topics, int n_topics, char *base, size_t len);

/* BASE_<topic>_0.csv: 0, or -1 when longer than len. */
int sim_log_px4_topic_path(const char *base, const char *topic, char *out, size_t len);

#endif
