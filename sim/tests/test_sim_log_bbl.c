/* SPDX-License-Identifier: BSD-3-Clause */
/* The Betaflight blackbox decoder (log/log_bbl.h) on logs this test writes
 * as the firmware does: a header, I and P frames through every encoding and
 * predictor, slow frames, events, a corrupt frame, two logs in a file, a log
 * cut at every byte, and the decoded CSV through the reader's Betaflight
 * form. Every value written is read back exactly (integers: tolerance 0). */
#define _POSIX_C_SOURCE 200809L /* fmemopen, open_memstream, mkstemp */
#include "unity.h"
#include "log/log.h"
#include "log/bbl_stream.h"
#include "log/log_bbl.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846
#define FRAMES 64 /* main frames of the synthetic log */
#define I_INTERVAL 8
#define MINMOTOR 158
#define MINTHROTTLE 1070
#define VBATREF 1650
#define DT_US 500          /* 2 kHz */
#define T0_US 4294957296LL /* 10 ms before the logger's 32-bit clock wraps: frame 20 is past it */
/* The reader's command is a sum of three integers over 1000 and its gyro an
 * integer times pi/180: a few ulps of each. */
#define ROUND_TOL 1e-12

void setUp(void)
{
}
void tearDown(void)
{
}

/* --- a writer of the format, as the firmware lays it out ------------------ */

typedef struct {
    unsigned char *b;
    size_t n, cap;
    int nibble_held; /* TAG8_4S16: a high nibble written, its low half next */
} buf_t;

static void put(buf_t *w, unsigned c)
{
    if (w->n == w->cap) {
        w->cap = w->cap ? 2 * w->cap : 4096;
        w->b = realloc(w->b, w->cap);
        TEST_ASSERT_NOT_NULL(w->b);
    }
    w->b[w->n++] = (unsigned char)c;
}

static void put_text(buf_t *w, const char *s)
{
    while (*s != '\0') {
        put(w, (unsigned char)*s++);
    }
}

static void put_uvb(buf_t *w, uint32_t u)
{
    while (u >= 0x80u) {
        put(w, (u & 0x7Fu) | 0x80u);
        u >>= 7;
    }
    put(w, u);
}

static void put_svb(buf_t *w, int32_t v)
{
    put_uvb(w, ((uint32_t)v << 1) ^ (uint32_t)(v >> 31)); /* zigzag */
}

static int fits(int64_t v, int bits)
{
    return v >= -(1LL << (bits - 1)) && v < (1LL << (bits - 1));
}

/* Selector 3 of TAG2_3S32 and TAG2_3SVARIABLE: each value in 1-4 bytes. */
static void put_sized3(buf_t *w, const int64_t v[3])
{
    unsigned lead = 0xC0u;
    int bytes[3];
    for (int i = 0; i < 3; ++i) {
        bytes[i] = fits(v[i], 8) ? 1 : fits(v[i], 16) ? 2 : fits(v[i], 24) ? 3 : 4;
        lead |= (unsigned)(bytes[i] - 1) << (2 * i);
    }
    put(w, lead);
    for (int i = 0; i < 3; ++i) {
        for (int b = 0; b < bytes[i]; ++b) {
            put(w, (unsigned)((uint64_t)v[i] >> (8 * b)) & 0xFFu);
        }
    }
}

static void put_tag2_3s32(buf_t *w, const int64_t v[3])
{
    if (fits(v[0], 2) && fits(v[1], 2) && fits(v[2], 2)) {
        put(w, ((unsigned)(v[0] & 3) << 4) | ((unsigned)(v[1] & 3) << 2) | (unsigned)(v[2] & 3));
    } else if (fits(v[0], 4) && fits(v[1], 4) && fits(v[2], 4)) {
        put(w, 0x40u | (unsigned)(v[0] & 0xF));
        put(w, ((unsigned)(v[1] & 0xF) << 4) | (unsigned)(v[2] & 0xF));
    } else if (fits(v[0], 6) && fits(v[1], 6) && fits(v[2], 6)) {
        put(w, 0x80u | (unsigned)(v[0] & 0x3F));
        put(w, (unsigned)(v[1] & 0x3F));
        put(w, (unsigned)(v[2] & 0x3F));
    } else {
        put_sized3(w, v);
    }
}

static void put_tag2_3svariable(buf_t *w, const int64_t v[3])
{
    if (fits(v[0], 2) && fits(v[1], 2) && fits(v[2], 2)) {
        put(w, ((unsigned)(v[0] & 3) << 4) | ((unsigned)(v[1] & 3) << 2) | (unsigned)(v[2] & 3));
    } else if (fits(v[0], 5) && fits(v[1], 5) && fits(v[2], 4)) { /* 5-5-4 */
        put(w, 0x40u | ((unsigned)(v[0] & 0x1F) << 1) | ((unsigned)(v[1] & 0x1F) >> 4));
        put(w, ((unsigned)(v[1] & 0xF) << 4) | (unsigned)(v[2] & 0xF));
    } else if (fits(v[0], 8) && fits(v[1], 7) && fits(v[2], 7)) { /* 8-7-7 */
        put(w, 0x80u | ((unsigned)(v[0] & 0xFF) >> 2));
        put(w, ((unsigned)(v[0] & 3) << 6) | ((unsigned)(v[1] & 0x7F) >> 1));
        put(w, ((unsigned)(v[1] & 1) << 7) | (unsigned)(v[2] & 0x7F));
    } else {
        put_sized3(w, v);
    }
}

static void put_nibble(buf_t *w, unsigned x)
{
    if (w->nibble_held) {
        w->b[w->n - 1] |= (unsigned char)(x & 0xFu);
    } else {
        put(w, (x & 0xFu) << 4);
    }
    w->nibble_held = !w->nibble_held;
}

/* Data version 2: a selector, then the values as nibbles, high first. */
static void put_tag8_4s16(buf_t *w, const int64_t v[4])
{
    unsigned selector = 0;
    int nibbles[4];
    for (int i = 0; i < 4; ++i) {
        const unsigned code = v[i] == 0 ? 0u : fits(v[i], 4) ? 1u : fits(v[i], 8) ? 2u : 3u;
        TEST_ASSERT_TRUE(fits(v[i], 16));
        nibbles[i] = code == 0 ? 0 : code == 1 ? 1 : code == 2 ? 2 : 4;
        selector |= code << (2 * i);
    }
    put(w, selector);
    w->nibble_held = 0;
    for (int i = 0; i < 4; ++i) {
        for (int k = nibbles[i] - 1; k >= 0; --k) {
            put_nibble(w, (unsigned)((uint64_t)v[i] >> (4 * k)));
        }
    }
    w->nibble_held = 0;
}

static void put_tag8_8svb(buf_t *w, const int64_t *v, int count)
{
    unsigned header = 0;
    for (int i = 0; i < count; ++i) {
        header |= v[i] != 0 ? 1u << i : 0u;
    }
    put(w, header);
    for (int i = 0; i < count; ++i) {
        if (v[i] != 0) {
            put_svb(w, (int32_t)v[i]);
        }
    }
}

/* --- the synthetic log -------------------------------------------------- */

/* The main fields, their I and P predictors and encodings. */
enum {
    F_ITER,
    F_TIME,
    F_AXP0,
    F_AXP1,
    F_AXP2,
    F_AXI0,
    F_AXI1,
    F_AXI2,
    F_AXF0,
    F_AXF1,
    F_AXF2,
    F_SP0,
    F_SP1,
    F_SP2,
    F_SP3,
    F_RC0,
    F_RC3,
    F_VBAT,
    F_DEBUG,
    F_G0,
    F_G1,
    F_G2,
    F_M0,
    F_M1,
    F_M2,
    F_M3,
    N_FIELDS
};

static const char NAMES[] = "loopIteration,time,axisP[0],axisP[1],axisP[2],axisI[0],axisI[1],axisI[2],axisF[0],"
                            "axisF[1],axisF[2],setpoint[0],setpoint[1],setpoint[2],setpoint[3],rcCommand[0],"
                            "rcCommand[3],vbatLatest,debug[0],gyroADC[0],gyroADC[1],gyroADC[2],motor[0],motor[1],"
                            "motor[2],motor[3]";
static const char I_SIGNED[] = "0,0,1,1,1,1,1,1,1,1,1,1,1,1,0,1,0,0,1,1,1,1,0,0,0,0";
/* vbat from vbatref, NEG_14BIT; rcCommand from 1500 and minthrottle; motor[0] from minmotor, the others from motor[0] */
static const char I_PRED[] = "0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,8,4,9,0,0,0,0,11,5,5,5";
static const char I_ENC[] = "1,1,0,0,0,0,0,0,0,0,0,0,0,0,1,0,1,3,0,0,0,0,1,0,0,0";
/* iteration: increment; time: straight line; axisP, axisI, setpoint, rcCommand, vbat, debug, motors: previous;
 * axisF and gyro: average of two */
static const char P_PRED[] = "6,2,1,1,1,1,1,1,3,3,3,1,1,1,1,1,1,1,1,3,3,3,1,1,1,1";
/* axisP: signed VB; axisI: TAG2_3S32; axisF: TAG2_3SVARIABLE; setpoint: TAG8_4S16; rcCommand[0], rcCommand[3]:
 * signed VB; vbat: signed VB; debug: NULL; gyro and motors: one TAG8_8SVB group of 7 */
static const char P_ENC[] = "9,0,0,0,0,7,7,7,10,10,10,8,8,8,8,0,0,0,9,6,6,6,6,6,6,6";

/* Deltas of every size the encodings have layouts for, by frame and field. */
static int64_t wiggle(int k, int f)
{
    static const int64_t STEPS[] = {0, 1, -2, 7, -8, 15, -16, 31, -32, 63, -64, 100, -128, 127, 300, -3000, 40000};
    return STEPS[(k * 7 + f * 3) % (int)(sizeof STEPS / sizeof STEPS[0])];
}

/* The true value of field f in main frame k. */
static int64_t value(int k, int f)
{
    switch (f) {
    case F_ITER:
        return 100 + k;
    case F_TIME: /* a little jitter on the period */
        return (T0_US + (int64_t)k * DT_US + (k % 3)) % 4294967296LL;
    case F_SP3:
        return 1000 + 3 * k;
    case F_RC0:
        return 1500 + wiggle(k, f) / 4;
    case F_RC3:
        return MINTHROTTLE + 20 + k;
    case F_VBAT:
        return VBATREF - 40 + k % 5;
    case F_DEBUG: /* NULL in P frames: the I frame's value held */
        return 77 + (k / I_INTERVAL);
    case F_M0:
        return MINMOTOR + 500 + 10 * k;
    case F_M1:
    case F_M2:
    case F_M3:
        return MINMOTOR + 500 + 10 * k + (f - F_M0) * 5 - 3;
    case F_SP0:
    case F_SP1:
    case F_SP2: /* TAG8_4S16 takes 16-bit deltas */
        return 200 * ((k * (f + 1)) % 7) - 600 + wiggle(k, f) % 300;
    default:
        return (int64_t)((k * (f + 3)) % 11) * 37 - 150 + wiggle(k, f);
    }
}

static int64_t v_true(int k, int f)
{
    return f == F_DEBUG ? 77 + (k / I_INTERVAL) : value(k, f);
}

/* The time as the decoder gives it: unwrapped past 2^32 us. */
static int64_t time_unwrapped(int k)
{
    return T0_US + (int64_t)k * DT_US + (k % 3);
}

static void header(buf_t *w, int data_version_line)
{
    char line[512];
    put_text(w, "H Product:Blackbox flight data recorder by Nicholas Sherlock\n");
    if (data_version_line) {
        put_text(w, "H Data version:2\n");
    }
    snprintf(line, sizeof line, "H I interval:%d\nH P interval:1/1\n", I_INTERVAL);
    put_text(w, line);
    put_text(w, "H Firmware type:Cleanflight\nH Firmware revision:Betaflight 4.4.2 (test) TEST\n");
    snprintf(line, sizeof line, "H minthrottle:%d\nH motorOutput:%d,2047\nH vbatref:%d\nH gyro_scale:0x3f800000\n",
             MINTHROTTLE, MINMOTOR, VBATREF);
    put_text(w, line);
    snprintf(line, sizeof line, "H Field I name:%s\nH Field I signed:%s\nH Field I predictor:%s\n", NAMES, I_SIGNED,
             I_PRED);
    put_text(w, line);
    snprintf(line, sizeof line, "H Field I encoding:%s\nH Field P predictor:%s\nH Field P encoding:%s\n", I_ENC, P_PRED,
             P_ENC);
    put_text(w, line);
    put_text(w, "H Field S name:flightModeFlags,stateFlags\nH Field S signed:0,0\n"
                "H Field S predictor:0,0\nH Field S encoding:1,1\n");
}

static void intra_frame(buf_t *w, int k)
{
    put(w, 'I');
    for (int f = 0; f < N_FIELDS; ++f) {
        const int64_t v = v_true(k, f);
        switch (f) {
        case F_ITER:
        case F_TIME:
        case F_SP3:
            put_uvb(w, (uint32_t)v);
            break;
        case F_RC0:
            put_svb(w, (int32_t)(v - 1500));
            break;
        case F_RC3:
            put_uvb(w, (uint32_t)(v - MINTHROTTLE));
            break;
        case F_VBAT: /* NEG_14BIT: the negated value in 14 bits */
            put_uvb(w, (uint32_t)(-(v - VBATREF)) & 0x3FFFu);
            break;
        case F_M0:
            put_uvb(w, (uint32_t)(v - MINMOTOR));
            break;
        case F_M1:
        case F_M2:
        case F_M3:
            put_svb(w, (int32_t)(v - v_true(k, F_M0)));
            break;
        default:
            put_svb(w, (int32_t)v);
            break;
        }
    }
}

/* P frame k: residuals from frames k-1 and k-2 (k-2 is k-1 after an I frame). */
static void inter_frame(buf_t *w, int k, int last_intra)
{
    const int k2 = k - 1 == last_intra ? k - 1 : k - 2;
    int64_t r[N_FIELDS], g[8];
    for (int f = 0; f < N_FIELDS; ++f) {
        const int64_t a = f == F_TIME ? time_unwrapped(k - 1) : v_true(k - 1, f);
        const int64_t b = f == F_TIME ? time_unwrapped(k2) : v_true(k2, f);
        const int64_t v = f == F_TIME ? time_unwrapped(k) : v_true(k, f);
        switch (P_PRED[2 * f] - '0') {
        case 2:
            r[f] = v - (2 * a - b);
            break;
        case 3:
            r[f] = v - (a + b) / 2;
            break;
        default:
            r[f] = v - a;
            break;
        }
    }
    put(w, 'P');
    put_svb(w, (int32_t)r[F_TIME]);
    for (int f = F_AXP0; f <= F_AXP2; ++f) {
        put_svb(w, (int32_t)r[f]);
    }
    put_tag2_3s32(w, &r[F_AXI0]);
    put_tag2_3svariable(w, &r[F_AXF0]);
    put_tag8_4s16(w, &r[F_SP0]);
    put_svb(w, (int32_t)r[F_RC0]);
    put_svb(w, (int32_t)r[F_RC3]);
    put_svb(w, (int32_t)r[F_VBAT]);
    for (int i = 0; i < 7; ++i) {
        g[i] = r[F_G0 + i];
    }
    put_tag8_8svb(w, g, 7);
}

/* A log of `frames` main frames; corrupt_at >= 0: garbage before that frame. */
static void write_log(buf_t *w, int frames, int corrupt_at)
{
    int last_intra = 0;
    header(w, 1);
    for (int k = 0; k < frames; ++k) {
        if (k == corrupt_at) { /* a P marker, then bytes a P frame reads 111 of and that hold no marker */
            put(w, 'P');
            for (int i = 0; i < 200; ++i) {
                put(w, 0xFF);
            }
        }
        if (k % I_INTERVAL == 0) {
            intra_frame(w, k);
            last_intra = k;
        } else {
            inter_frame(w, k, last_intra);
        }
        if (k == 1) { /* slow fields, then events: a sync beep and a flight mode change */
            put(w, 'S');
            put_uvb(w, 5);
            put_uvb(w, 300);
            put(w, 'E');
            put(w, 0);
            put_uvb(w, 123456);
            put(w, 'E');
            put(w, 30);
            put_uvb(w, 5);
            put_uvb(w, 1);
        }
    }
    put(w, 'E');
    put(w, 255);
    put_text(w, "End of log");
    put(w, 0);
}

/* --- decoding ------------------------------------------------------------ */

typedef struct {
    char *text;
    size_t len;
    int rc;
    sim_log_bbl_stats_t st;
    sim_log_error_t err;
} decoded_t;

static decoded_t decode(const buf_t *w, int index)
{
    decoded_t d;
    memset(&d, 0, sizeof d);
    FILE *in = fmemopen(w->b, w->n, "rb");
    FILE *out = open_memstream(&d.text, &d.len);
    TEST_ASSERT_NOT_NULL(in);
    TEST_ASSERT_NOT_NULL(out);
    d.rc = sim_log_bbl_decode(in, "t.bbl", out, index, NULL, NULL, &d.st, &d.err);
    fclose(in);
    fclose(out);
    return d;
}

/* The CSV's rows as integers (the header checked); their count. */
static int parse_rows(const char *text, int64_t rows[][N_FIELDS + 2], int max)
{
    const char *p = strchr(text, '\n');
    TEST_ASSERT_NOT_NULL(p);
    TEST_ASSERT_EQUAL_INT(0, strncmp(text, "loopIteration, time (us), axisP[0], axisP[1], axisP[2], axisI[0]", 64));
    TEST_ASSERT_NOT_NULL(strstr(text, "motor[3], flightModeFlags, stateFlags\n"));
    int n = 0;
    for (++p; *p != '\0' && n < max; ++n) {
        for (int c = 0; c < N_FIELDS + 2; ++c) {
            char *end;
            rows[n][c] = strtoll(p, &end, 10);
            TEST_ASSERT_TRUE(end != p);
            p = end;
            if (c < N_FIELDS + 1) {
                TEST_ASSERT_EQUAL_INT(',', *p);
                p += 2;
            }
        }
        TEST_ASSERT_EQUAL_INT('\n', *p);
        ++p;
    }
    return n;
}

static void check_row(const int64_t *row, int k, int64_t flight_mode, int64_t state)
{
    char msg[64];
    for (int f = 0; f < N_FIELDS; ++f) {
        snprintf(msg, sizeof msg, "frame %d field %d", k, f);
        const int64_t want = f == F_TIME ? time_unwrapped(k) : v_true(k, f);
        TEST_ASSERT_TRUE_MESSAGE(row[f] == want, msg);
    }
    TEST_ASSERT_TRUE(row[N_FIELDS] == flight_mode);
    TEST_ASSERT_TRUE(row[N_FIELDS + 1] == state);
}

static void test_every_encoding_and_predictor_reads_back_exactly(void)
{
    buf_t w = {0};
    static int64_t rows[FRAMES + 8][N_FIELDS + 2];
    write_log(&w, FRAMES, -1);
    decoded_t d = decode(&w, 1);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, d.rc, d.err.message);
    TEST_ASSERT_EQUAL_INT(FRAMES, parse_rows(d.text, rows, FRAMES + 8));
    for (int k = 0; k < FRAMES; ++k) {
        check_row(rows[k], k, k < 2 ? 0 : 5, k < 2 ? 0 : 300); /* the slow frame follows frame 1 */
    }
    TEST_ASSERT_EQUAL_INT(FRAMES / I_INTERVAL, (int)d.st.frames[0]);
    TEST_ASSERT_EQUAL_INT(FRAMES - FRAMES / I_INTERVAL, (int)d.st.frames[1]);
    TEST_ASSERT_EQUAL_INT(1, (int)d.st.frames[2]);
    TEST_ASSERT_EQUAL_INT(3, (int)d.st.frames[5]); /* sync beep, flight mode, end */
    TEST_ASSERT_EQUAL_INT(0, (int)d.st.corrupt);
    TEST_ASSERT_EQUAL_INT(1, d.st.ended);
    TEST_ASSERT_EQUAL_INT(0, d.st.truncated);
    char said[400];
    TEST_ASSERT_EQUAL_INT(0, sim_log_bbl_stats_describe(&d.st, said, sizeof said)); /* a clean log: nothing to say */
    free(d.text);
    free(w.b);
}

static void test_a_corrupt_frame_is_skipped_counted_and_decoding_resumes_at_the_next_i_frame(void)
{
    buf_t w = {0};
    static int64_t rows[FRAMES + 8][N_FIELDS + 2];
    const int bad = 2 * I_INTERVAL + 3; /* before a P frame: P frames lost until the next I frame */
    write_log(&w, FRAMES, bad);
    decoded_t d = decode(&w, 1);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, d.rc, d.err.message);
    const int lost = I_INTERVAL - bad % I_INTERVAL;
    const int n = parse_rows(d.text, rows, FRAMES + 8);
    TEST_ASSERT_EQUAL_INT(FRAMES - lost, n);
    TEST_ASSERT_EQUAL_INT(1, (int)d.st.corrupt);
    TEST_ASSERT_EQUAL_INT(lost, (int)d.st.dropped);
    char said[400], want[200];
    TEST_ASSERT_TRUE(sim_log_bbl_stats_describe(&d.st, said, sizeof said) > 0);
    snprintf(want, sizeof want, "corrupt frames skipped: 1, bytes of no frame skipped: 200; main frames dropped");
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(said, want), said);
    for (int r = 0, k = 0; r < n; ++r, ++k) {
        if (k == bad) {
            k += lost;
        }
        check_row(rows[r], k, k < 2 ? 0 : 5, k < 2 ? 0 : 300);
    }
    free(d.text);
    free(w.b);
}

static void test_a_log_cut_anywhere_decodes_up_to_the_cut(void)
{
    buf_t w = {0};
    static int64_t full[FRAMES + 8][N_FIELDS + 2], rows[FRAMES + 8][N_FIELDS + 2];
    write_log(&w, FRAMES, -1);
    /* the first frame: the header ends before it */
    const size_t data_at = (size_t)((const unsigned char *)strstr((const char *)w.b, "\nI") - w.b) + 1;
    decoded_t whole = decode(&w, 1);
    const int n_full = parse_rows(whole.text, full, FRAMES + 8);
    int cut_in_frame = 0;
    for (size_t cut = data_at; cut < w.n; ++cut) {
        buf_t part = w;
        part.n = cut;
        decoded_t d = decode(&part, 1);
        if (d.rc != 0) { /* before the first main frame is whole: refused, at an offset */
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(d.err.message, "offset "), d.err.message);
            TEST_ASSERT_TRUE(cut < data_at + 80);
            free(d.text);
            continue;
        }
        const int n = parse_rows(d.text, rows, FRAMES + 8);
        TEST_ASSERT_TRUE(n >= 1 && n <= n_full);
        TEST_ASSERT_EQUAL_INT(0, memcmp(rows, full, (size_t)n * sizeof rows[0])); /* a prefix of the whole */
        TEST_ASSERT_EQUAL_INT(0, d.st.ended);
        cut_in_frame += d.st.truncated;
        if (d.st.truncated) {
            char said[400];
            TEST_ASSERT_TRUE(sim_log_bbl_stats_describe(&d.st, said, sizeof said) > 0);
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(said, "cut within a frame at offset "), said);
            TEST_ASSERT_TRUE(d.st.truncated_at >= (long long)data_at && d.st.truncated_at < (long long)cut);
        }
        free(d.text);
    }
    TEST_ASSERT_TRUE(cut_in_frame > (int)(w.n - data_at) / 2); /* most cuts fall inside a frame */
    free(whole.text);
    free(w.b);
}

static void test_several_logs_in_a_file_by_index_or_the_longest(void)
{
    buf_t w = {0};
    static int64_t rows[FRAMES + 8][N_FIELDS + 2];
    write_log(&w, 16, -1);
    write_log(&w, FRAMES, -1);
    write_log(&w, 24, -1);
    const int want[4] = {FRAMES, 16, FRAMES, 24}; /* index 0: the longest */
    for (int index = 0; index <= 3; ++index) {
        decoded_t d = decode(&w, index);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, d.rc, d.err.message);
        TEST_ASSERT_EQUAL_INT(3, d.st.n_logs);
        TEST_ASSERT_EQUAL_INT(index == 0 ? 2 : index, d.st.index);
        TEST_ASSERT_EQUAL_INT(want[index], parse_rows(d.text, rows, FRAMES + 8));
        free(d.text);
    }
    decoded_t d = decode(&w, 4);
    TEST_ASSERT_EQUAL_INT(-1, d.rc);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(d.err.message, "offset 0: log 4 asked for, the file has 3"), d.err.message);
    free(d.text);
    free(w.b);
}

static void expect_header_refusal(const char *from, const char *to, const char *needle)
{
    buf_t w = {0};
    write_log(&w, 16, -1);
    char *at = strstr((char *)w.b, from); /* header text: a same-length substitute */
    TEST_ASSERT_NOT_NULL(at);
    TEST_ASSERT_EQUAL_INT(strlen(from), strlen(to));
    memcpy(at, to, strlen(to));
    decoded_t d = decode(&w, 1);
    TEST_ASSERT_EQUAL_INT(-1, d.rc);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(d.err.message, needle), d.err.message);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(d.err.message, "offset "), d.err.message);
    free(d.text);
    free(w.b);
}

static void test_bad_headers_are_refused_at_an_offset(void)
{
    expect_header_refusal("H Field P encoding:9,0", "H Field P encoding:9,5", "encoding 5 is none of the format's");
    expect_header_refusal("H Field I predictor:0,0,0", "H Field I predictor:0,-13", "predictor -13");
    expect_header_refusal("loopIteration,time", "loopIteration,tame", "loopIteration,time");
    buf_t w = {0};
    put_text(&w, "not a log at all\n");
    decoded_t d = decode(&w, 0);
    TEST_ASSERT_EQUAL_INT(-1, d.rc);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(d.err.message, "offset 0: no 'H Product"), d.err.message);
    free(d.text);
    free(w.b);
}

static void test_through_the_readers_betaflight_form(void)
{
    buf_t w = {0};
    char dir[] = "/tmp/test_bbl_XXXXXX", in_path[64], base[64], csv[80];
    write_log(&w, FRAMES, -1);
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    snprintf(in_path, sizeof in_path, "%s/log.bbl", dir);
    snprintf(base, sizeof base, "%s/log", dir);
    snprintf(csv, sizeof csv, "%s.csv", base);
    FILE *f = fopen(in_path, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_INT(w.n, fwrite(w.b, 1, w.n, f));
    fclose(f);
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_bbl_to_csv(in_path, base, NULL, 0, 0, NULL, NULL, &err), err.message);
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = SIM_LOG_BETAFLIGHT;
    snprintf(o.path, sizeof o.path, "%s", csv);
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    sim_log_sample_t s;
    int k = 0;
    /* the jittered period's median: ticks on no row, so only the first tick is compared exactly */
    TEST_ASSERT_EQUAL_INT(1, sim_log_next(log, &s, &err));
    for (int i = 0; i < 3; ++i) {
        const double cmd = (double)(v_true(k, F_AXP0 + i) + v_true(k, F_AXI0 + i) + v_true(k, F_AXF0 + i)) * 1e-3;
        TEST_ASSERT_TRUE(fabs(s.gyro_rad_s[i] - (double)v_true(k, F_G0 + i) * PI / 180.0) <= ROUND_TOL);
        TEST_ASSERT_TRUE(fabs(s.ref_rate_rad_s[i] - (double)v_true(k, F_SP0 + i) * PI / 180.0) <= ROUND_TOL);
        TEST_ASSERT_TRUE(fabs(s.command[i] - cmd) <= ROUND_TOL);
    }
    TEST_ASSERT_TRUE(fabs(s.motor[3] - (double)v_true(k, F_M3)) <= ROUND_TOL);
    sim_log_close(log);
    /* a refusal leaves no CSV behind */
    TEST_ASSERT_EQUAL_INT(0, remove(csv));
    TEST_ASSERT_EQUAL_INT(-1, sim_log_bbl_to_csv(in_path, base, NULL, 0, 2, NULL, NULL, &err));
    TEST_ASSERT_EQUAL_INT(-1, access(csv, F_OK));
    remove(in_path);
    rmdir(dir);
    free(w.b);
}

/* A gyro_scale other than 1 (sensor counts, as Cleanflight logged): the
 * gyro written converted, `gyroADC[i] (deg/s)`, which the reader takes. */
static void test_a_gyro_in_counts_is_written_in_deg_s(void)
{
    buf_t w = {0};
    write_log(&w, 16, -1);
    char *at = strstr((char *)w.b, "H gyro_scale:0x3f800000");
    TEST_ASSERT_NOT_NULL(at);
    memcpy(at, "H gyro_scale:0x3f000000", 23); /* 0.5 deg/s per count */
    decoded_t d = decode(&w, 1);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, d.rc, d.err.message);
    TEST_ASSERT_NOT_NULL(strstr(d.text, ", gyroADC[0] (deg/s), gyroADC[1] (deg/s), gyroADC[2] (deg/s), motor[0]"));
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = SIM_LOG_BETAFLIGHT;
    FILE *f = fmemopen(d.text, d.len, "r");
    sim_log_error_t err;
    sim_log_t *log = sim_log_open_stream(f, "t.csv", &o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    sim_log_sample_t s;
    TEST_ASSERT_EQUAL_INT(1, sim_log_next(log, &s, &err));
    for (int i = 0; i < 3; ++i) { /* half a count is a multiple of 0.5: printed exactly with 2 decimals */
        TEST_ASSERT_TRUE(fabs(s.gyro_rad_s[i] - 0.5 * (double)v_true(0, F_G0 + i) * PI / 180.0) <= ROUND_TOL);
    }
    sim_log_close(log);
    fclose(f);
    free(d.text);
    free(w.b);
}

/* TAG8_4S16 in both data versions, from bytes laid out by hand: a 4-bit
 * pair, an 8-bit and a 16-bit value (selector 0xE5: fields 1, 1, 2, 3). */
static void test_tag8_4s16_in_both_data_versions(void)
{
    static const unsigned char v1[] = {0xE5, 0x2F, 0x80, 0x34, 0x12}; /* low nibble first; 16 bits little-endian */
    static const unsigned char v2[] = {0xE5, 0xF2, 0x80, 0x12, 0x34}; /* a stream of nibbles, high first */
    static const int64_t want[4] = {-1, 2, -128, 0x1234};
    const unsigned char *bytes[2] = {v1, v2};
    for (int version = 1; version <= 2; ++version) {
        FILE *f = fmemopen((void *)(uintptr_t)bytes[version - 1], sizeof v1, "rb");
        bbl_stream_t s;
        int64_t got[4];
        TEST_ASSERT_EQUAL_INT(0, bbl_stream_init(&s, f, 0, (long long)sizeof v1));
        bbl_stream_frame_start(&s);
        bbl_read_tag8_4s16(&s, version, got);
        for (int i = 0; i < 4; ++i) {
            TEST_ASSERT_TRUE(got[i] == want[i]);
        }
        TEST_ASSERT_EQUAL_INT((int)sizeof v1, (int)bbl_stream_offset(&s));
        TEST_ASSERT_EQUAL_INT(0, s.past_end);
        bbl_stream_free(&s);
        fclose(f);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_encoding_and_predictor_reads_back_exactly);
    RUN_TEST(test_a_corrupt_frame_is_skipped_counted_and_decoding_resumes_at_the_next_i_frame);
    RUN_TEST(test_a_log_cut_anywhere_decodes_up_to_the_cut);
    RUN_TEST(test_several_logs_in_a_file_by_index_or_the_longest);
    RUN_TEST(test_bad_headers_are_refused_at_an_offset);
    RUN_TEST(test_through_the_readers_betaflight_form);
    RUN_TEST(test_tag8_4s16_in_both_data_versions);
    RUN_TEST(test_a_gyro_in_counts_is_written_in_deg_s);
    return UNITY_END();
}
