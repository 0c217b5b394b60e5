/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Mapping items "FIELD=SOURCE" (log.h): the sample's fields as slots, the
 * items' parser, and each form's preset, itself a table of items in the
 * same syntax so that the caller's items replace them one for one.
 */
#ifndef LADRC_SIM_LOG_MAP_H
#define LADRC_SIM_LOG_MAP_H

#include <stddef.h>

#include "log.h"

/* The fields, in the order of sim_log_sample_t; each component is a slot. */
typedef enum {
    SIM_LOG_G_TIME,
    SIM_LOG_G_GYRO,
    SIM_LOG_G_GYRO_RAW,
    SIM_LOG_G_ANGLE,
    SIM_LOG_G_QUAT,
    SIM_LOG_G_REF_ANGLE,
    SIM_LOG_G_REF_QUAT,
    SIM_LOG_G_REF_RATE,
    SIM_LOG_G_COMMAND,
    SIM_LOG_G_THROTTLE,
    SIM_LOG_G_MOTOR,
    SIM_LOG_G_ROTOR_HZ,
    SIM_LOG_G_COUNT
} sim_log_group_t;

#define SIM_LOG_N_SLOTS 44  /* components of every field */
#define SIM_LOG_TERMS_MAX 8 /* columns summed by one item */
#define SIM_LOG_NAME_LEN 96 /* a column's or topic's name, its NUL included */

/* The group's first slot and component count. */
int sim_log_group_first(sim_log_group_t g);
int sim_log_group_count(sim_log_group_t g);
sim_log_group_t sim_log_slot_group(int slot);

/* "gyro[1]", "time": the slot's name as items write it. */
void sim_log_slot_name(int slot, char *buf, size_t len);

typedef struct {
    char column[SIM_LOG_NAME_LEN];
    int optional; /* `?`: 0 when the log lacks it */
} sim_log_term_t;

typedef struct {
    int slot;
    char topic[SIM_LOG_NAME_LEN]; /* PX4: the topic file of every term; "" otherwise */
    int n_terms;
    sim_log_term_t term[SIM_LOG_TERMS_MAX];
    double scale; /* to SI */
} sim_log_item_t;

typedef struct {
    sim_log_item_t item[SIM_LOG_N_SLOTS];
    int mapped[SIM_LOG_N_SLOTS]; /* item[slot] holds an item */
    /* PX4: the preset's item from another topic, taken when item's topic
     * file is missing and its is there (older PX4 releases; log_px4.h) */
    sim_log_item_t fallback[SIM_LOG_N_SLOTS];
    int has_fallback[SIM_LOG_N_SLOTS];
} sim_log_map_t;

/* One item; `topics`: sources are topic.column (PX4). 0, or -1 with a
 * message naming the item. */
int sim_log_item_parse(const char *text, int topics, sim_log_item_t *it, char *msg, size_t len);

/* The form's preset, then the caller's items over it. 0, or -1 with a
 * message naming the bad item. */
int sim_log_map_build(sim_log_map_t *m, sim_log_format_t format, const char *const *items, int n_items, char *msg,
                      size_t len);

/* How a Betaflight log gets the column (`gyroADC[0]`, `time (us)`): the
 * firmware's switch or blackbox_decode's flag, or NULL for a column the
 * preset does not read. */
const char *sim_log_column_hint(const char *column);

/* The ArduPilot preset with the commands from RATE (with_rate) or from
 * PIDR/PIDP/PIDY (logs without RATE), then the caller's items. */
int sim_log_map_build_ardupilot(sim_log_map_t *m, int with_rate, const char *const *items, int n_items, char *msg,
                                size_t len);

#endif
