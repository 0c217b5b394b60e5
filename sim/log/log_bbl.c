/* SPDX-License-Identifier: BSD-3-Clause */
/* Betaflight's blackbox log to blackbox_decode's CSV (log_bbl.h). */
#include "log_bbl.h"

#include "bbl_decoder.h"
#include "log_digits.h"
#include "log_file.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define LOG_MARKER "H Product:Blackbox flight data recorder"
#define FRAME_MAX_BYTES 256 /* a longer frame is corrupt */
#define ITERATION_JUMP_MAX 5000u
#define TIME_JUMP_MAX_US 10000000LL
#define SCAN_BLOCK (1 << 20)
#define PROGRESS_BYTES (1LL << 20)

enum {
    EVENT_SYNC_BEEP = 0,
    EVENT_INFLIGHT_ADJUSTMENT = 13,
    EVENT_LOGGING_RESUME = 14,
    EVENT_DISARM = 15,
    EVENT_FLIGHT_MODE = 30,
    EVENT_LOG_END = 255
};

int bbl_fail_at(sim_log_error_t *err, const decoder_t *d, long long offset, const char *message)
{
    return sim_log_fail(err, d->name, 0, 0, "offset %lld: %s", offset, message);
}

/* --- the logs in the file ------------------------------------------------ */

typedef struct {
    long long *begin;
    int n, cap;
} log_list_t;

static int add_log(log_list_t *l, long long offset)
{
    if (l->n == l->cap) {
        const int cap = l->cap == 0 ? 16 : 2 * l->cap;
        long long *b = realloc(l->begin, (size_t)cap * sizeof *b);
        if (b == NULL) {
            return -1;
        }
        l->begin = b;
        l->cap = cap;
    }
    l->begin[l->n++] = offset;
    return 0;
}

/* Every log's first byte (its product line), in one pass; the file's size. */
static int find_logs(FILE *f, log_list_t *l, long long *size)
{
    const size_t m = sizeof LOG_MARKER - 1;
    size_t block = SCAN_BLOCK; /* or the file's size, when smaller */
    if (fseek(f, 0, SEEK_END) == 0) {
        const long end = ftell(f);
        block = end >= 0 && (unsigned long)end < block ? (size_t)end + 1 : block;
    }
    unsigned char *buf = malloc(block + m);
    size_t held = 0;
    long long base = 0; /* offset of buf[0] */
    if (buf == NULL || fseek(f, 0, SEEK_SET) != 0) {
        free(buf);
        return -1;
    }
    for (;;) {
        const size_t n = fread(buf + held, 1, block, f);
        const size_t len = held + n;
        size_t i = 0;
        while (len >= m && i + m <= len) {
            const unsigned char *p = memchr(buf + i, 'H', len - m + 1 - i);
            if (p == NULL) {
                break;
            }
            i = (size_t)(p - buf);
            if (memcmp(p, LOG_MARKER, m) == 0 && add_log(l, base + (long long)i) != 0) {
                free(buf);
                return -1;
            }
            ++i;
        }
        if (n == 0) {
            *size = base + (long long)len;
            break;
        }
        held = len < m - 1 ? len : m - 1; /* a marker across the blocks' seam */
        memmove(buf, buf + len - held, held);
        base += (long long)(len - held);
    }
    free(buf);
    return ferror(f) ? -1 : 0;
}

/* --- frames -------------------------------------------------------------- */

static int64_t add_u(int64_t a, int64_t b)
{
    return (int64_t)((uint64_t)a + (uint64_t)b); /* wraps as the logger's integers do */
}

static int64_t predict(const decoder_t *d, int field, int predictor, int64_t v, const int64_t *cur, const int64_t *prev,
                       const int64_t *prev2)
{
    switch (predictor) {
    case PRED_PREVIOUS:
        return prev != NULL ? add_u(v, prev[field]) : v;
    case PRED_STRAIGHT_LINE:
        return prev != NULL ? add_u(v, (int64_t)(2u * (uint64_t)prev[field] - (uint64_t)prev2[field])) : v;
    case PRED_AVERAGE_2:
        return prev != NULL ? add_u(v, add_u(prev[field], prev2[field]) / 2) : v;
    case PRED_MINTHROTTLE:
        return add_u(v, d->minthrottle);
    case PRED_MOTOR_0:
        return d->motor0 >= 0 ? add_u(v, cur[d->motor0]) : v;
    case PRED_HOME_COORD:
        return d->home[0] >= 0 ? add_u(v, d->home_valid[d->home[0]]) : v;
    case PRED_HOME_COORD_1:
        return d->home[1] >= 0 ? add_u(v, d->home_valid[d->home[1]]) : v;
    case PRED_1500:
        return add_u(v, 1500);
    case PRED_VBATREF:
        return add_u(v, d->vbatref);
    case PRED_LAST_MAIN_FRAME_TIME:
        return d->prev >= 0 ? add_u(v, d->hist[d->prev][1]) : v;
    case PRED_MINMOTOR:
        return add_u(v, d->motor_low);
    default: /* none; an increment inside a group adds nothing */
        return v;
    }
}

/* A frame's fields into v, predicted from prev and prev2 (NULL: none). */
static void parse_fields(decoder_t *d, const frame_def_t *def, int64_t *v, const int64_t *prev, const int64_t *prev2,
                         uint32_t skipped)
{
    bbl_stream_t *s = &d->in;
    int64_t g[8];
    if (prev2 == NULL) {
        prev2 = prev;
    }
    for (int i = 0; i < def->n;) {
        const int e = def->encoding[i];
        if (def->predictor[i] == PRED_INC) { /* no bits: the iterations since the last frame */
            v[i] = add_u((int64_t)skipped + 1, prev != NULL ? prev[i] : 0);
            ++i;
            continue;
        }
        if (bbl_is_group(e)) {
            int count = 3;
            if (e == BBL_ENC_TAG8_8SVB) { /* this field and the following of the same encoding, up to 8 */
                count = 1;
                while (count < 8 && i + count < def->n && def->encoding[i + count] == BBL_ENC_TAG8_8SVB) {
                    ++count;
                }
                bbl_read_tag8_8svb(s, count, g);
            } else if (e == BBL_ENC_TAG8_4S16) {
                count = 4;
                bbl_read_tag8_4s16(s, d->data_version, g);
            } else if (e == BBL_ENC_TAG2_3S32) {
                bbl_read_tag2_3s32(s, g);
            } else {
                bbl_read_tag2_3svariable(s, g);
            }
            /* a group's values are not cut to 32 bits (blackbox_decode's rule) */
            for (int k = 0; k < count && i < def->n; ++k, ++i) {
                v[i] = predict(d, i, def->predictor[i], g[k], v, prev, prev2);
            }
            continue;
        }
        int64_t x;
        switch (e) {
        case BBL_ENC_SIGNED_VB:
            x = bbl_read_signed_vb(s);
            break;
        case BBL_ENC_UNSIGNED_VB:
            x = bbl_read_unsigned_vb(s);
            break;
        case BBL_ENC_NEG_14BIT:
            x = bbl_read_neg_14bit(s);
            break;
        default: /* NULL: nothing written, 0 */
            x = 0;
            break;
        }
        x = predict(d, i, def->predictor[i], x, v, prev, prev2);
        v[i] = def->is_signed[i] ? (int64_t)(int32_t)(uint32_t)(uint64_t)x : (int64_t)(uint32_t)(uint64_t)x;
        ++i;
    }
}

/* Should iteration k have a main frame, by the I interval and P ratio? */
static int should_have_frame(const decoder_t *d, uint32_t k)
{
    return ((long)(k % (uint32_t)d->i_interval) + d->p_num - 1) % d->p_denom < d->p_num;
}

/* Iterations the sampling skipped since the last main frame. */
static uint32_t skipped_iterations(const decoder_t *d)
{
    uint32_t count = 0;
    if (d->last_iteration == UINT32_MAX) {
        return 0;
    }
    for (uint32_t k = d->last_iteration + 1u; !should_have_frame(d, k) && count < (uint32_t)INTERVAL_MAX; ++k) {
        ++count;
    }
    return count;
}

/* The logger's 32-bit microsecond clock, unwrapped. */
static int64_t unwrap_time(decoder_t *d, int64_t t)
{
    const uint32_t now = (uint32_t)(uint64_t)t;
    if (d->last_time_us >= 0) {
        const uint32_t last = (uint32_t)(uint64_t)d->last_time_us;
        if (now < last && (uint32_t)(now - last) < (uint32_t)TIME_JUMP_MAX_US) {
            d->rollover_us += (int64_t)1 << 32;
        }
    }
    return (int64_t)now + d->rollover_us;
}

/* The frame's iteration and time follow the last valid one's. */
static int in_line(const decoder_t *d, const int64_t *v)
{
    const uint32_t it = (uint32_t)(uint64_t)v[0];
    return it >= d->last_iteration && it < d->last_iteration + ITERATION_JUMP_MAX && v[1] >= d->last_time_us &&
           v[1] < d->last_time_us + TIME_JUMP_MAX_US;
}

static void invalidate(decoder_t *d)
{
    d->stream_valid = 0;
    d->prev = d->prev2 = -1;
}

/* --- the CSV -------------------------------------------------------------- */

static int write_header(decoder_t *d)
{
    const frame_def_t *in = &d->def[T_I];
    for (int i = 0; i < in->n; ++i) {
        const char *name = in->names + in->name_at[i];
        const char *unit = "";
        if (i == 1) {
            unit = " (us)";
        } else if (d->convert_gyro && (i == d->gyro[0] || i == d->gyro[1] || i == d->gyro[2])) {
            unit = " (deg/s)";
        } else if (strcmp(name, "BaroAlt") == 0) {
            unit = " (cm)"; /* blackbox_decode's default height unit: as logged */
        }
        fprintf(d->out, "%s%s%s", i > 0 ? ", " : "", name, unit);
    }
    for (int i = 0; i < d->def[T_S].n; ++i) {
        fprintf(d->out, ", %s", d->def[T_S].names + d->def[T_S].name_at[i]);
    }
    fputc('\n', d->out);
    return ferror(d->out) ? -1 : 0;
}

static void write_row(decoder_t *d, const int64_t *v)
{
    const frame_def_t *in = &d->def[T_I];
    char *p = d->row;
    for (int i = 0; i < in->n; ++i) {
        if (i > 0) {
            *p++ = ',';
            *p++ = ' ';
        }
        if (i == 1) {
            p = sim_log_put_i64(p, v[1]);
        } else if (d->convert_gyro && (i == d->gyro[0] || i == d->gyro[1] || i == d->gyro[2])) {
            const int n = snprintf(p, 32, "%.2f", (double)(int32_t)(uint32_t)(uint64_t)v[i] * d->gyro_deg_s_per_unit);
            p += n > 0 && n < 32 ? n : 0; /* a scale beyond any gyro's: the cell left empty */
        } else if (in->is_signed[i]) {
            p = sim_log_put_i64(p, (int32_t)(uint32_t)(uint64_t)v[i]);
        } else {
            p = sim_log_put_u64(p, (uint32_t)(uint64_t)v[i]);
        }
    }
    for (int i = 0; i < d->def[T_S].n; ++i) {
        *p++ = ',';
        *p++ = ' ';
        p = sim_log_put_u64(p, (uint64_t)d->slow[i]);
    }
    *p++ = '\n';
    fwrite(d->row, 1, (size_t)(p - d->row), d->out);
}

/* --- completing frames ----------------------------------------------------- */

static void next_buffer(decoder_t *d)
{
    for (int k = 0; k < 3; ++k) {
        if (k != d->prev && k != d->prev2) {
            d->cur = k;
            return;
        }
    }
}

static void main_frame_done(decoder_t *d, int intra)
{
    int64_t *v = d->hist[d->cur];
    if (!intra && !d->stream_valid) { /* predicted from frames lost: its time is no time to unwrap */
        ++d->st.dropped;
        return;
    }
    v[1] = unwrap_time(d, v[1]);
    if (intra) {
        if (d->last_iteration != UINT32_MAX && !in_line(d, v)) {
            invalidate(d);
        } else {
            d->stream_valid = 1;
        }
    } else if (d->stream_valid && !in_line(d, v)) {
        invalidate(d);
    }
    if (!d->stream_valid) {
        ++d->st.dropped;
        return;
    }
    d->last_iteration = (uint32_t)(uint64_t)v[0];
    d->last_time_us = v[1];
    if (v[1] > d->last_row_us) {
        write_row(d, v);
        d->last_row_us = v[1];
        ++d->st.rows;
    } else {
        ++d->st.time_repeats;
    }
    d->prev2 = intra ? d->cur : d->prev;
    d->prev = d->cur;
    next_buffer(d);
}

/* An event: 1 when it is one of the format's, 0 otherwise (then corrupt). */
static int parse_event(decoder_t *d)
{
    bbl_stream_t *s = &d->in;
    static const char END[] = "End of log"; /* and its NUL */
    switch (bbl_read_byte(s)) {
    case EVENT_SYNC_BEEP:
    case EVENT_DISARM:
        (void)bbl_read_unsigned_vb(s);
        return 1;
    case EVENT_INFLIGHT_ADJUSTMENT:
        if (bbl_read_byte(s) > 127) { /* a float's 4 bytes */
            for (int k = 0; k < 4; ++k) {
                (void)bbl_read_byte(s);
            }
        } else {
            (void)bbl_read_signed_vb(s);
        }
        return 1;
    case EVENT_LOGGING_RESUME:
        d->resume_iteration = bbl_read_unsigned_vb(s);
        d->resume_time_us = bbl_read_unsigned_vb(s);
        d->resumed = 1;
        return 1;
    case EVENT_FLIGHT_MODE:
        (void)bbl_read_unsigned_vb(s); /* the flags and the last flags */
        (void)bbl_read_unsigned_vb(s);
        return 1;
    case EVENT_LOG_END:
        for (size_t k = 0; k < sizeof END; ++k) {
            if (bbl_read_byte(s) != (uint8_t)END[k]) {
                return 0;
            }
        }
        d->end_read = 1;
        return 1;
    default:
        return 0;
    }
}

/* One frame from its marker; its completion or its corruption. */
static void frame(decoder_t *d, int t)
{
    bbl_stream_t *s = &d->in;
    const long long start = bbl_stream_offset(s);
    int event_ok = 1;
    d->resumed = d->end_read = 0;
    int64_t *v = d->hist[d->cur];
    (void)bbl_read_byte(s);
    switch (t) {
    case T_I:
        parse_fields(d, &d->def[T_I], v, d->prev >= 0 ? d->hist[d->prev] : NULL, NULL, 0);
        break;
    case T_P:
        parse_fields(d, &d->def[T_P], v, d->prev >= 0 ? d->hist[d->prev] : NULL,
                     d->prev2 >= 0 ? d->hist[d->prev2] : NULL, skipped_iterations(d));
        break;
    case T_S:
        parse_fields(d, &d->def[T_S], d->slow, NULL, NULL, 0);
        break;
    case T_G:
        parse_fields(d, &d->def[T_G], d->gps, NULL, NULL, 0);
        break;
    case T_H:
        parse_fields(d, &d->def[T_H], d->home_now, NULL, NULL, 0);
        break;
    default:
        event_ok = parse_event(d);
        break;
    }
    const long long size = bbl_stream_offset(s) - start - 1;
    const int at_end = d->end_read || bbl_stream_offset(s) >= s->end; /* nothing of the log after its end */
    const int whole = !s->past_end && !s->past_window && size <= FRAME_MAX_BYTES && event_ok &&
                      (at_end || bbl_type_of(bbl_stream_peek(s)) >= 0);
    if (!whole) {
        ++d->st.corrupt;
        if (s->past_end) {
            d->st.truncated = 1;
            d->st.truncated_at = start;
        }
        invalidate(d);
        bbl_stream_seek_back(s, start + 1); /* look for a frame from its second byte */
        return;
    }
    ++d->st.frames[t];
    if (t == T_I || t == T_P) {
        main_frame_done(d, t == T_I);
    } else if (t == T_H) {
        memcpy(d->home_valid, d->home_now, sizeof d->home_valid);
    } else if (d->resumed) { /* the frames resume here: their iteration and time jump to it */
        d->last_iteration = d->resume_iteration;
        d->last_time_us = (int64_t)d->resume_time_us + d->rollover_us;
    } else if (d->end_read) {
        d->st.ended = 1;
        s->end = bbl_stream_offset(s);
    }
}

static void report(decoder_t *d)
{
    const long long at = bbl_stream_offset(&d->in);
    if (d->progress != NULL && at >= d->next_progress) {
        d->progress(d->progress_ctx, at, d->file_bytes);
        d->next_progress = at + PROGRESS_BYTES;
    }
}

static int decode_data(decoder_t *d, sim_log_error_t *err)
{
    bbl_stream_t *s = &d->in;
    for (;;) {
        bbl_stream_frame_start(s);
        const int c = bbl_stream_peek(s);
        if (c < 0 || d->st.ended) {
            break;
        }
        const int t = bbl_type_of(c);
        if (t < 0) { /* no frame starts here: the main stream has lost its thread */
            (void)bbl_read_byte(s);
            ++d->st.skipped_bytes;
            invalidate(d);
        } else {
            frame(d, t);
        }
        report(d);
    }
    if (s->read_error) {
        return bbl_fail_at(err, d, bbl_stream_offset(s), "read error");
    }
    if (ferror(d->out)) {
        return sim_log_fail(err, d->name, 0, 0, "cannot write the CSV: %s", strerror(errno));
    }
    if (d->st.rows == 0) {
        return bbl_fail_at(err, d, d->st.log_offset, "no main frame decoded in the log");
    }
    return 0;
}

static void decoder_defaults(decoder_t *d)
{
    d->data_version = 2;
    d->minthrottle = d->motor_low = 1150;
    d->vbatref = 4095;
    d->i_interval = 32;
    d->p_num = d->p_denom = 1;
    d->prev = d->prev2 = -1;
    d->last_iteration = UINT32_MAX;
    d->last_time_us = -1;
    d->last_row_us = INT64_MIN;
    d->motor0 = d->home[0] = d->home[1] = -1;
}

/* The log to decode: index 1.., or 0 for the longest. */
static int choose_log(const log_list_t *l, long long size, int index)
{
    if (index > 0) {
        return index - 1;
    }
    int best = 0;
    for (int i = 1; i < l->n; ++i) {
        const long long len_i = (i + 1 < l->n ? l->begin[i + 1] : size) - l->begin[i];
        const long long len_b = (best + 1 < l->n ? l->begin[best + 1] : size) - l->begin[best];
        best = len_i > len_b ? i : best;
    }
    return best;
}

int sim_log_bbl_decode(FILE *in, const char *name, FILE *out, int index, sim_log_convert_progress_fn progress,
                       void *progress_ctx, sim_log_bbl_stats_t *stats, sim_log_error_t *err)
{
    log_list_t logs = {NULL, 0, 0};
    long long size = 0;
    int rc = -1;
    decoder_t *d = calloc(1, sizeof *d);
    if (d == NULL) {
        return sim_log_fail(err, name, 0, 0, "out of memory");
    }
    d->name = name;
    d->out = out;
    d->progress = progress;
    d->progress_ctx = progress_ctx;
    decoder_defaults(d);
    if (find_logs(in, &logs, &size) != 0) {
        sim_log_fail(err, name, 0, 0, "cannot read the log: %s", ferror(in) ? strerror(errno) : "out of memory");
    } else if (logs.n == 0) {
        bbl_fail_at(err, d, 0, "no '" LOG_MARKER "' line: not a blackbox log");
    } else if (index < 0 || index > logs.n) {
        char msg[96];
        snprintf(msg, sizeof msg, "log %d asked for, the file has %d (1 to %d; 0: the longest)", index, logs.n, logs.n);
        bbl_fail_at(err, d, 0, msg);
    } else {
        const int k = choose_log(&logs, size, index);
        const long long end = k + 1 < logs.n ? logs.begin[k + 1] : size;
        d->file_bytes = size;
        d->st.n_logs = logs.n;
        d->st.index = k + 1;
        d->st.log_offset = logs.begin[k];
        d->st.log_bytes = end - logs.begin[k];
        if (bbl_stream_init(&d->in, in, logs.begin[k], end) != 0) {
            sim_log_fail(err, name, 0, 0, "cannot seek in the log or out of memory");
        } else {
            bbl_stream_frame_start(&d->in);
            rc = bbl_read_header(d, err);
            if (rc == 0 && write_header(d) != 0) {
                rc = sim_log_fail(err, name, 0, 0, "cannot write the CSV: %s", strerror(errno));
            }
            if (rc == 0) {
                rc = decode_data(d, err);
            }
        }
        if (rc == 0 && progress != NULL) {
            progress(progress_ctx, size, size);
        }
        bbl_stream_free(&d->in);
    }
    if (stats != NULL) {
        *stats = d->st;
    }
    free(logs.begin);
    free(d);
    return rc;
}

int sim_log_bbl_stats_describe(const sim_log_bbl_stats_t *st, char *buf, size_t len)
{
    size_t n = 0;
    buf[0] = '\0';
#define SAY(...)                                                                                                       \
    do {                                                                                                               \
        if (n < len) {                                                                                                 \
            const int k = snprintf(buf + n, len - n, __VA_ARGS__);                                                     \
            n += k > 0 ? (size_t)k : 0;                                                                                \
        }                                                                                                              \
    } while (0)
    if (st->n_logs > 1) {
        SAY("log %d of %d (offset %lld, %lld bytes)", st->index, st->n_logs, st->log_offset, st->log_bytes);
    }
    if (st->corrupt > 0 || st->skipped_bytes > 0) {
        SAY("%scorrupt frames skipped: %lld, bytes of no frame skipped: %lld", n > 0 ? "; " : "", st->corrupt,
            st->skipped_bytes);
    }
    if (st->dropped > 0) {
        SAY("%smain frames dropped (after a corrupt frame until the next I frame, or out of line): %lld",
            n > 0 ? "; " : "", st->dropped);
    }
    if (st->time_repeats > 0) {
        SAY("%smain frames left out, their time not increasing: %lld", n > 0 ? "; " : "", st->time_repeats);
    }
    if (st->truncated) {
        SAY("%scut within a frame at offset %lld", n > 0 ? "; " : "", st->truncated_at);
    }
#undef SAY
    return n < len ? (int)n : (int)len - 1;
}

int sim_log_bbl_to_csv(const char *in_path, const char *out_base, const char *const *topics, int n_topics, int index,
                       sim_log_convert_progress_fn progress, void *progress_ctx, sim_log_error_t *err)
{
    (void)topics; /* one CSV of every main field: nothing to choose */
    (void)n_topics;
    return sim_log_bbl_to_csv_stats(in_path, out_base, index, progress, progress_ctx, NULL, err);
}

int sim_log_bbl_to_csv_stats(const char *in_path, const char *out_base, int index, sim_log_convert_progress_fn progress,
                             void *progress_ctx, sim_log_bbl_stats_t *stats, sim_log_error_t *err)
{
    char out_path[SIM_LOG_PATH_LEN];
    if (snprintf(out_path, sizeof out_path, "%s.csv", out_base) >= (int)sizeof out_path) {
        return sim_log_fail(err, in_path, 0, 0, "output path longer than %d bytes", SIM_LOG_PATH_LEN - 1);
    }
    FILE *in = fopen(in_path, "rb");
    if (in == NULL) {
        return sim_log_fail(err, in_path, 0, 0, "cannot open: %s", strerror(errno));
    }
    FILE *out = fopen(out_path, "wb");
    if (out == NULL) {
        const int e = errno;
        fclose(in);
        return sim_log_fail(err, out_path, 0, 0, "cannot create: %s", strerror(e));
    }
    int rc = sim_log_bbl_decode(in, in_path, out, index, progress, progress_ctx, stats, err);
    fclose(in);
    if (fclose(out) != 0 && rc == 0) {
        rc = sim_log_fail(err, out_path, 0, 0, "cannot write: %s", strerror(errno));
    }
    if (rc != 0) {
        remove(out_path); /* nothing written on a refusal */
    }
    return rc;
}
