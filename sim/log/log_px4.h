/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * PX4 logs as ulog2csv writes them: one CSV per topic, BASE_<topic>_<n>.csv
 * (instance n; this reader takes instance 0).
 */
#ifndef LADRC_SIM_LOG_PX4_H
#define LADRC_SIM_LOG_PX4_H

#include <stddef.h>

#include "log_map.h"

/* BASE from the path given: a topic file's (BASE_<topic>_<n>.csv, topic one
 * of topics), a .ulg's name without its extension, or the path itself. */
void sim_log_px4_base(const char *path, const char *const *topics, int n_topics, char *base, size_t len);

/* BASE_<topic>_0.csv: 0, or -1 when longer than len. */
int sim_log_px4_topic_path(const char *base, const char *topic, char *out, size_t len);

/* The topics of the map's items (each once, in slot order), and with
 * with_fallbacks those of its fallbacks after them; topics has room for
 * 2 SIM_LOG_N_SLOTS. Returns their count. */
int sim_log_px4_map_topics(const sim_log_map_t *m, int with_fallbacks, const char **topics);

/* Each item with a fallback (log_map.h) becomes its fallback when the
 * item's topic file is missing under base and the fallback's is there:
 * vehicle_torque_setpoint or actuator_controls_0, actuator_motors or
 * actuator_outputs, as the log's PX4 release logged them. */
void sim_log_px4_choose(sim_log_map_t *m, const char *base);

#define SIM_LOG_PX4_TOPICS_MAX (2 * SIM_LOG_N_SLOTS)

typedef struct {
    char name[SIM_LOG_PX4_TOPICS_MAX][SIM_LOG_NAME_LEN];
    const char *list[SIM_LOG_PX4_TOPICS_MAX]; /* list[i] is name[i]: a decoder's topics */
    int n;
} sim_log_px4_topics_t;

/* Every topic the px4 form may read with the caller's mapping items (the
 * preset's, their fallbacks, the items' own): what a ULog decoder writes.
 * 0, or -1 with msg naming a bad item. */
int sim_log_px4_topics(const char *const *items, int n_items, sim_log_px4_topics_t *t, char *msg, size_t len);

#endif
