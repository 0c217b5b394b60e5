/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ArduPilot logs as sim_log_dataflash_to_csv writes them: one CSV per
 * message type and instance, BASE_<TYPE>_<n>.csv. A preset's topic names
 * the type (`IMU`), or the type and instance (`ESC[2]`: BASE_ESC_2.csv).
 */
#ifndef LADRC_SIM_LOG_ARDUPILOT_H
#define LADRC_SIM_LOG_ARDUPILOT_H

#include <stddef.h>

/* BASE from the path given: a type file's (BASE_<TYPE>_<n>.csv, TYPE
 * letters and digits), a .bin's name without its extension, or the path. */
void sim_log_ardupilot_base(const char *path, char *base, size_t len);

/* BASE_<TYPE>_<n>.csv of the topic `TYPE` (n = 0) or `TYPE[n]`: 0, or -1
 * when longer than len or not of that form. */
int sim_log_ardupilot_topic_path(const char *base, const char *topic, char *out, size_t len);

/* What makes ArduPilot log the message type (a LOG_BITMASK bit, a
 * parameter), for a refusal's message; "" for a type it does not know. */
const char *sim_log_ardupilot_enabled_by(const char *topic);

/* The type times its rows by SampleUS, the sensor's sample, not TimeUS:
 * GYR and ACC (written in bursts, TimeUS their write's time up to 4.4). */
int sim_log_ardupilot_sample_timed(const char *topic);

#define SIM_LOG_ARDUPILOT_TOPICS_MAX 48 /* the preset's types and those of the caller's items */
#define SIM_LOG_ARDUPILOT_TYPE_LEN 8    /* a type's name (4 characters) and its NUL, with room */

/* The message types the form reads, for the decoder: those of the preset
 * (both its RATE and its PID commands) and of the caller's map items, once
 * each. Their count; names[i] holds each, topics[i] points at it. */
int sim_log_ardupilot_topics(const char *const *map, int n_map, char names[][SIM_LOG_ARDUPILOT_TYPE_LEN],
                             const char **topics);

#endif
