/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The field kinds of ArduPilot's DataFlash format (log_dataflash.h):
 * their sizes, their little-endian values, and each field as CSV text.
 * Internal to the decoder.
 */
#ifndef LADRC_SIM_LOG_DATAFLASH_FIELDS_H
#define LADRC_SIM_LOG_DATAFLASH_FIELDS_H

#include <stdint.h>

#define DF_ARRAY_N 32  /* the int16 values of an 'a' field */
#define DF_CELL_MAX 40 /* characters of one number's text */

typedef struct {
    char kind; /* the format character */
    unsigned char size, offset;
    int exp10;   /* integers: the value is raw * 10^exp10, written exactly */
    double mult; /* floats, and integers whose multiplier is no power of ten: raw * mult */
    int name_at; /* the name's start in the type's names */
} field_t;

/* The kind's size in bytes; 0: not a kind. */
int df_kind_size(char k);
int df_is_integer_kind(char k); /* b B M h H i I q Q c C e E L */
int df_is_text_kind(char k);    /* n N Z */

/* The little-endian unsigned value of size bytes. */
uint64_t df_get_le(const unsigned char *p, int size);
double df_get_double(const unsigned char *p);

/* An integer field's magnitude and sign. */
void df_get_integer(const unsigned char *p, char kind, int size, uint64_t *mag, int *neg);

/* The field of message m as text at p (no NUL): the characters written,
 * at most DF_CELL_MAX, or DF_ARRAY_N cells of 7 for an 'a'. */
int df_put_field(char *p, const field_t *f, const unsigned char *m);

#endif
