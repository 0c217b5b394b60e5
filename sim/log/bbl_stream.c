/* SPDX-License-Identifier: BSD-3-Clause */
/* The bytes of a blackbox log and its value encodings (bbl_stream.h). */
#include "bbl_stream.h"

#include <stdlib.h>
#include <string.h>

int bbl_stream_init(bbl_stream_t *s, FILE *f, long long start, long long end)
{
    memset(s, 0, sizeof *s);
    s->f = f;
    s->base = start;
    s->end = end;
    /* a small log gets a small buffer: at least two windows, so that a refill holds one */
    const long long want = end - start + 1;
    s->cap = want < 2 * BBL_WINDOW ? 2 * BBL_WINDOW : (want > BBL_BUFFER ? BBL_BUFFER : (size_t)want);
    s->buf = malloc(s->cap);
    if (s->buf == NULL) {
        return -1;
    }
    if (fseek(f, (long)start, SEEK_SET) != 0) {
        return -1;
    }
    return 0;
}

void bbl_stream_free(bbl_stream_t *s)
{
    free(s->buf);
    s->buf = NULL;
}

/* Moves the held bytes from pos to the front and reads more behind them. */
static void refill(bbl_stream_t *s)
{
    const size_t keep = s->len > s->pos ? s->len - s->pos : 0;
    memmove(s->buf, s->buf + s->pos, keep);
    s->base += (long long)s->pos;
    s->pos = 0;
    s->len = keep;
    while (!s->file_done && s->len < s->cap) {
        const size_t n = fread(s->buf + s->len, 1, s->cap - s->len, s->f);
        s->len += n;
        if (n == 0) {
            s->file_done = 1;
            s->read_error = ferror(s->f) != 0;
        }
    }
    if (s->file_done && s->base + (long long)s->len < s->end) {
        s->end = s->base + (long long)s->len; /* the file is shorter than it was */
    }
}

void bbl_stream_frame_start(bbl_stream_t *s)
{
    if (s->pos > s->len) { /* a read past the bytes held: none left */
        s->pos = s->len;
    }
    if (s->len - s->pos < BBL_WINDOW && !s->file_done) {
        refill(s);
    }
    s->past_end = s->past_window = 0;
}

void bbl_stream_seek_back(bbl_stream_t *s, long long offset)
{
    s->pos = (size_t)(offset - s->base);
}

int bbl_stream_peek(const bbl_stream_t *s)
{
    return s->pos < s->len && bbl_stream_offset(s) < s->end ? s->buf[s->pos] : -1;
}

uint32_t bbl_read_unsigned_vb(bbl_stream_t *s)
{
    uint32_t v = 0;
    for (int i = 0; i < 5; ++i) { /* 5 bytes of 7 bits hold 32 */
        const uint8_t c = bbl_read_byte(s);
        v |= (uint32_t)(c & 0x7Fu) << (7 * i);
        if (c < 0x80u) {
            return v;
        }
    }
    return 0; /* longer than a 32-bit value: the writer never makes one */
}

static int32_t zigzag(uint32_t u)
{
    return (int32_t)(u >> 1) ^ -(int32_t)(u & 1u);
}

int32_t bbl_read_signed_vb(bbl_stream_t *s)
{
    return zigzag(bbl_read_unsigned_vb(s));
}

/* The low `bits` bits of u as a two's complement number. */
static int32_t sign_extend(uint32_t u, int bits)
{
    const uint32_t m = 1u << (bits - 1);
    u &= (m << 1) - 1u;
    return (int32_t)(u ^ m) - (int32_t)m;
}

int32_t bbl_read_neg_14bit(bbl_stream_t *s)
{
    /* 16 bits kept; bit 13 set: the sign, filling bits 14 and 15 */
    const uint32_t w = bbl_read_unsigned_vb(s) & 0xFFFFu;
    const int32_t x = (w & 0x2000u) ? (int32_t)(w | 0xC000u) - 65536 : (int32_t)w;
    return -x;
}

void bbl_read_tag8_8svb(bbl_stream_t *s, int count, int64_t v[8])
{
    if (count == 1) { /* a group of one is a plain signed VB */
        v[0] = bbl_read_signed_vb(s);
        return;
    }
    const uint8_t header = bbl_read_byte(s);
    for (int i = 0; i < 8; ++i) { /* a bit per value, 1: written */
        v[i] = (header >> i) & 1u ? bbl_read_signed_vb(s) : 0;
    }
}

/* Little-endian values of 1, 2, 3 or 4 bytes, by 2-bit selectors from the lowest. */
static void read_sized(bbl_stream_t *s, uint8_t selectors, int64_t v[3])
{
    for (int i = 0; i < 3; ++i, selectors >>= 2) {
        const int bytes = (selectors & 3) + 1;
        uint32_t u = 0;
        for (int b = 0; b < bytes; ++b) {
            u |= (uint32_t)bbl_read_byte(s) << (8 * b);
        }
        v[i] = bytes == 4 ? (int32_t)u : sign_extend(u, 8 * bytes);
    }
}

void bbl_read_tag2_3s32(bbl_stream_t *s, int64_t v[3])
{
    const uint8_t lead = bbl_read_byte(s);
    switch (lead >> 6) {
    case 0: /* 2 bits each in the lead byte */
        v[0] = sign_extend(lead >> 4, 2);
        v[1] = sign_extend(lead >> 2, 2);
        v[2] = sign_extend(lead, 2);
        break;
    case 1: { /* 4 bits each: the lead's low nibble, then a byte */
        const uint8_t b = bbl_read_byte(s);
        v[0] = sign_extend(lead, 4);
        v[1] = sign_extend(b >> 4, 4);
        v[2] = sign_extend(b, 4);
        break;
    }
    case 2: { /* 6 bits each: the lead's low bits, then two bytes' */
        const uint8_t b1 = bbl_read_byte(s);
        const uint8_t b2 = bbl_read_byte(s);
        v[0] = sign_extend(lead, 6);
        v[1] = sign_extend(b1, 6);
        v[2] = sign_extend(b2, 6);
        break;
    }
    default:
        read_sized(s, lead, v);
        break;
    }
}

void bbl_read_tag2_3svariable(bbl_stream_t *s, int64_t v[3])
{
    const uint8_t lead = bbl_read_byte(s);
    switch (lead >> 6) {
    case 0: /* 2 bits each */
        v[0] = sign_extend(lead >> 4, 2);
        v[1] = sign_extend(lead >> 2, 2);
        v[2] = sign_extend(lead, 2);
        break;
    case 1: { /* 5, 5 and 4 bits: ss11 1112 2222 3333 */
        const uint8_t b = bbl_read_byte(s);
        v[0] = sign_extend((uint32_t)lead >> 1, 5);
        v[1] = sign_extend(((uint32_t)(lead & 1u) << 4) | ((uint32_t)b >> 4), 5);
        v[2] = sign_extend(b, 4);
        break;
    }
    case 2: { /* 8, 7 and 7 bits: ss11 1111 1122 2222 2333 3333 */
        const uint8_t b1 = bbl_read_byte(s);
        const uint8_t b2 = bbl_read_byte(s);
        v[0] = sign_extend(((uint32_t)(lead & 0x3Fu) << 2) | ((uint32_t)b1 >> 6), 8);
        v[1] = sign_extend(((uint32_t)(b1 & 0x3Fu) << 1) | ((uint32_t)b2 >> 7), 7);
        v[2] = sign_extend(b2, 7);
        break;
    }
    default:
        read_sized(s, lead, v);
        break;
    }
}

/* Data version 1: nibbles in the byte's low then high half, bytes whole. */
static void tag8_4s16_v1(bbl_stream_t *s, uint8_t selector, int64_t v[4])
{
    for (int i = 0; i < 4; ++i, selector >>= 2) {
        switch (selector & 3) {
        case 0:
            v[i] = 0;
            break;
        case 1: { /* two 4-bit values in one byte: this one and the next */
            const uint8_t b = bbl_read_byte(s);
            v[i] = sign_extend(b, 4);
            if (i < 3) {
                ++i;
                selector >>= 2;
                v[i] = sign_extend((uint32_t)b >> 4, 4);
            }
            break;
        }
        case 2:
            v[i] = (int8_t)bbl_read_byte(s);
            break;
        default: {
            const uint32_t lo = bbl_read_byte(s);
            const uint32_t hi = bbl_read_byte(s);
            v[i] = sign_extend(lo | (hi << 8), 16);
            break;
        }
        }
    }
}

/* Data version 2: a stream of nibbles, high half first, 16-bit values big-endian. */
static void tag8_4s16_v2(bbl_stream_t *s, uint8_t selector, int64_t v[4])
{
    uint32_t held = 0; /* the byte whose low nibble is next, when odd */
    int odd = 0;
    for (int i = 0; i < 4; ++i, selector >>= 2) {
        const int nibbles = (selector & 3) == 0 ? 0 : ((selector & 3) == 1 ? 1 : ((selector & 3) == 2 ? 2 : 4));
        uint32_t u = 0;
        for (int k = 0; k < nibbles; ++k) {
            if (odd) {
                u = (u << 4) | (held & 0xFu);
            } else {
                held = bbl_read_byte(s);
                u = (u << 4) | (held >> 4);
            }
            odd = !odd;
        }
        v[i] = nibbles == 0 ? 0 : sign_extend(u, 4 * nibbles);
    }
}

void bbl_read_tag8_4s16(bbl_stream_t *s, int data_version, int64_t v[4])
{
    const uint8_t selector = bbl_read_byte(s);
    if (data_version < 2) {
        tag8_4s16_v1(s, selector, v);
    } else {
        tag8_4s16_v2(s, selector, v);
    }
}
