/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The bytes of a blackbox log and its value encodings: a window over a
 * FILE* that holds at least BBL_WINDOW bytes from the current frame's start
 * (so that a corrupt frame can be re-read from its second byte, and a
 * frame's next marker seen) and refills itself between frames, never in a
 * frame; reads past the window or the log's end give 0 and set a flag.
 */
#ifndef LADRC_SIM_LOG_BBL_STREAM_H
#define LADRC_SIM_LOG_BBL_STREAM_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* Bytes held from a frame's start: more than any frame of 128 fields
 * (at most 5 bytes each, 41 for a group of 8), and its next marker. */
#define BBL_WINDOW 4096
#define BBL_BUFFER (256 * 1024)

typedef struct {
    FILE *f;
    unsigned char *buf;
    size_t cap, len, pos; /* bytes of buf, held, the next one's index */
    long long base;       /* file offset of buf[0] */
    long long end;        /* the log's end offset (exclusive) */
    int file_done;        /* f gave its last byte */
    int past_end;         /* a read went past the log's end */
    int past_window;      /* a read went past the bytes held (a frame too long) */
    int read_error;
} bbl_stream_t;

/* The value encodings (the header's `H Field X encoding` numbers). */
enum {
    BBL_ENC_SIGNED_VB = 0,
    BBL_ENC_UNSIGNED_VB = 1,
    BBL_ENC_NEG_14BIT = 3,
    BBL_ENC_TAG8_8SVB = 6,
    BBL_ENC_TAG2_3S32 = 7,
    BBL_ENC_TAG8_4S16 = 8,
    BBL_ENC_NULL = 9,
    BBL_ENC_TAG2_3SVARIABLE = 10
};

/* Starts at offset `start` of f (seeked), reading up to `end`. 0, or -1 when
 * out of memory or f cannot seek there. */
int bbl_stream_init(bbl_stream_t *s, FILE *f, long long start, long long end);
void bbl_stream_free(bbl_stream_t *s);

/* The offset of the next byte. */
static inline long long bbl_stream_offset(const bbl_stream_t *s)
{
    return s->base + (long long)s->pos;
}

/* Holds BBL_WINDOW bytes from here (or up to the end); clears the flags. */
void bbl_stream_frame_start(bbl_stream_t *s);

/* Moves back to an offset within the window (a corrupt frame's second byte). */
void bbl_stream_seek_back(bbl_stream_t *s, long long offset);

/* The next byte, or -1 at the end (no flag set: peeking is no read). */
int bbl_stream_peek(const bbl_stream_t *s);

/* The next byte (0 and a flag past the window or the end). */
static inline uint8_t bbl_read_byte(bbl_stream_t *s)
{
    if (s->pos < s->len && bbl_stream_offset(s) < s->end) {
        return s->buf[s->pos++];
    }
    if (bbl_stream_offset(s) >= s->end) {
        s->past_end = 1;
    } else {
        s->past_window = 1;
    }
    ++s->pos; /* the frame's length counts what it tried to read */
    return 0;
}

/* The encodings, as the format's writer lays them out. */
uint32_t bbl_read_unsigned_vb(bbl_stream_t *s);
int32_t bbl_read_signed_vb(bbl_stream_t *s);
int32_t bbl_read_neg_14bit(bbl_stream_t *s);
void bbl_read_tag8_8svb(bbl_stream_t *s, int count, int64_t v[8]);
void bbl_read_tag2_3s32(bbl_stream_t *s, int64_t v[3]);
void bbl_read_tag2_3svariable(bbl_stream_t *s, int64_t v[3]);
/* data_version: the header's `Data version` (1: the first layout of it). */
void bbl_read_tag8_4s16(bbl_stream_t *s, int data_version, int64_t v[4]);

#endif
