/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The message formats of a PX4 ULog ('F' messages: "name:type field;...",
 * types the basic ones, arrays `type[n]`, or another format nested) and a
 * logged topic's layout: its fields flattened into the columns ulog2csv
 * writes (`timestamp` first, then in the format's order: `xyz[0]`,
 * `esc[0].esc_rpm`; a char array is one text column named without its
 * index; fields whose name starts with `_padding` are skipped), each with
 * its byte offset in a 'D' message's data. Formats are held as their text
 * and parsed when a topic asked for is subscribed, so a malformed format
 * that no such topic uses is never an error.
 */
#ifndef LADRC_SIM_LOG_ULOG_FORMAT_H
#define LADRC_SIM_LOG_ULOG_FORMAT_H

#include <stddef.h>
#include <stdint.h>

/* Bytes of a 'D' message's data at most: a message's 65535 less its msg_id. */
#define SIM_ULOG_DATA_MAX 65533u

typedef enum {
    SIM_ULOG_INT8,
    SIM_ULOG_UINT8,
    SIM_ULOG_INT16,
    SIM_ULOG_UINT16,
    SIM_ULOG_INT32,
    SIM_ULOG_UINT32,
    SIM_ULOG_INT64,
    SIM_ULOG_UINT64,
    SIM_ULOG_FLOAT,
    SIM_ULOG_DOUBLE,
    SIM_ULOG_BOOL, /* written as ulog2csv does: the byte as a signed number */
    SIM_ULOG_CHAR, /* alone: a signed number; an array: one text column */
    SIM_ULOG_TEXT  /* a column of `count` chars, up to the first NUL */
} sim_ulog_type_t;

typedef struct {
    char *name; /* "name:fields", NUL-terminated; name_len bytes of name */
    size_t name_len;
} sim_ulog_format_t;

typedef struct {
    sim_ulog_format_t *f;
    int n, cap;
    size_t bytes; /* of text held */
} sim_ulog_formats_t;

/* Keeps the format text[0, len) ("name:fields"), replacing one of the same
 * name. 0; -1 with msg set: no ':' or an empty name, or the formats would
 * hold more than SIM_ULOG_FORMATS_BYTES_MAX bytes. */
#define SIM_ULOG_FORMATS_BYTES_MAX (16u << 20) /* real logs hold some 100-300 KB */
int sim_ulog_formats_add(sim_ulog_formats_t *fs, const char *text, size_t len, char *msg, size_t msg_len);

void sim_ulog_formats_free(sim_ulog_formats_t *fs);

typedef struct {
    uint32_t offset; /* in the data */
    uint16_t count;  /* chars of a text column; 1 otherwise */
    uint8_t type;    /* sim_ulog_type_t */
} sim_ulog_column_t;

typedef struct {
    sim_ulog_column_t *col; /* in the CSV's order: the timestamp first */
    int n_col;
    char *header; /* the CSV's header line, its LF included */
    size_t header_len;
    uint32_t size_min; /* data bytes: without the top level's trailing padding */
    uint32_t size_max; /* with it */
    size_t row_max;    /* the longest row's text, its LF included */
} sim_ulog_layout_t;

/* The layout of format `name`. 0; -1 with msg set: the format or a nested
 * one missing or malformed, nesting deeper than 32 (or circular), larger
 * than SIM_ULOG_DATA_MAX bytes, no `timestamp` field of an unsigned
 * integer type at the top level. */
int sim_ulog_layout_build(const sim_ulog_formats_t *fs, const char *name, size_t name_len, sim_ulog_layout_t *l,
                          char *msg, size_t msg_len);

void sim_ulog_layout_free(sim_ulog_layout_t *l);

/* Bytes of a value of a basic type (TEXT: of one char). */
uint32_t sim_ulog_type_size(sim_ulog_type_t t);

#endif
