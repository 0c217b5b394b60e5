/* SPDX-License-Identifier: BSD-3-Clause */
/* PX4 ULog decoded as a stream into ulog2csv's CSVs (log_ulog.h). The
 * message layout is the PX4 documentation's "ULog File Format". */
#include "log_ulog.h"

#include "log_digits.h"
#include "log_file.h"
#include "log_ulog_format.h"
#include "run/numfmt.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define HEADER_BYTES 16
#define MSG_HEADER 3      /* uint16_t msg_size, uint8_t msg_type */
#define FLAG_BITS_MIN 40u /* compat[8], incompat[8], appended_offsets[3] */
#define APPENDED_MAX 3
#define READ_CHUNK (1u << 20)         /* bytes read at once (fewer for a smaller log) */
#define MSG_MAX (65535u + MSG_HEADER) /* a whole message */
#define PROGRESS_EVERY (4LL << 20)    /* bytes between progress calls */
#define OUT_BUFFER 32768              /* each CSV's stdio buffer */
#define SUB_NONE 0                    /* msg_id: no subscription */
#define SUB_FILTERED (-1)             /* subscribed, a topic not asked for */
/* Columns of every topic read: PX4 logs have 300 to 2,600 in all (over
 * every topic of the pyulog samples); the bound keeps a hostile log's
 * layouts to some 8 MB. */
#define COLUMNS_MAX 1000000
#define SHOWN 60                                               /* characters of a name quoted */
#define PATH_MAX_LEN (SIM_LOG_PATH_LEN + 4 * SIM_LOG_PATH_LEN) /* an output file's path */

static const unsigned char MAGIC[7] = {'U', 'L', 'o', 'g', 0x01, 0x12, 0x35};
static const unsigned char SYNC[8] = {0x2F, 0x73, 0x13, 0x20, 0x25, 0x0C, 0xBB, 0x12};

/* Little-endian fields, whatever the host. */
static uint16_t le16(const unsigned char *p)
{
    return (uint16_t)(p[0] | (unsigned)p[1] << 8);
}

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t le64(const unsigned char *p)
{
    return (uint64_t)le32(p) | (uint64_t)le32(p + 4) << 32;
}

/* The log through a buffer: [start, end) of buf not consumed yet, buf[0] at
 * the log's offset base. */
typedef struct {
    FILE *f;
    unsigned char *buf;
    size_t chunk, cap; /* read at once; held: a chunk and a whole message */
    size_t start, end;
    long long base;
    int eof, error;
} reader_t;

static long long reader_pos(const reader_t *r)
{
    return r->base + (long long)r->start;
}

/* At least n (<= the chunk or a message) bytes at the cursor: 1; 0 when the log ends first. */
static int reader_fill(reader_t *r, size_t n)
{
    while (r->end - r->start < n && !r->eof) {
        if (r->start > 0) {
            memmove(r->buf, r->buf + r->start, r->end - r->start);
            r->base += (long long)r->start;
            r->end -= r->start;
            r->start = 0;
        }
        const size_t want = r->cap - r->end < r->chunk ? r->cap - r->end : r->chunk;
        const size_t got = fread(r->buf + r->end, 1, want, r->f);
        r->end += got;
        if (got < want) {
            r->eof = 1;
            r->error = ferror(r->f);
        }
    }
    return r->end - r->start >= n;
}

/* Consumes n bytes, reading through those not in the buffer: the bytes
 * consumed (fewer when the log ends). */
static long long reader_skip(reader_t *r, long long n)
{
    long long done = 0;
    while (done < n) {
        if (r->start == r->end && !reader_fill(r, 1)) {
            break;
        }
        const size_t have = r->end - r->start;
        const size_t step = (long long)have < n - done ? have : (size_t)(n - done);
        r->start += step;
        done += (long long)step;
    }
    return done;
}

/* Consumes up to and including the next sync magic: 1 when found, 0 when
 * the log ends first (all consumed). *skipped: the bytes consumed. */
static int reader_find_sync(reader_t *r, long long *skipped)
{
    const long long from = reader_pos(r);
    for (;;) {
        if (!reader_fill(r, sizeof SYNC)) {
            r->start = r->end;
            *skipped = reader_pos(r) - from;
            return 0;
        }
        const unsigned char *p = r->buf + r->start, *last = r->buf + r->end - sizeof SYNC;
        while (p <= last) {
            p = memchr(p, SYNC[0], (size_t)(last - p) + 1);
            if (p == NULL) {
                break;
            }
            if (memcmp(p, SYNC, sizeof SYNC) == 0) {
                r->start = (size_t)(p - r->buf) + sizeof SYNC;
                *skipped = reader_pos(r) - from;
                return 1;
            }
            ++p;
        }
        r->start = r->end - (sizeof SYNC - 1); /* a magic may start in the last 7 bytes */
        if (!reader_fill(r, r->chunk) && r->end - r->start < sizeof SYNC) {
            r->start = r->end;
            *skipped = reader_pos(r) - from;
            return 0;
        }
    }
}

/* A topic asked for, subscribed at least once: its layout. */
typedef struct {
    char *name;
    size_t len;
    sim_ulog_layout_t layout;
} topic_t;

/* One CSV: a topic's instance. */
typedef struct {
    int topic;
    int multi_id;
    char *path;
    FILE *f; /* NULL until its first row */
    long long rows;
    uint64_t last_us; /* the last row's timestamp */
    uint64_t ts_high; /* narrow timestamps: the wraps so far, in the field's unit */
    uint64_t ts_raw;  /* and the last raw value */
    int ts_seen;
    int created; /* the file exists */
} out_t;

typedef struct {
    const char *name; /* the log's, in messages */
    const char *out_base;
    const char *const *topics;
    int n_topics;
    reader_t r;
    sim_ulog_formats_t formats;
    topic_t *topic;
    int n_topic, cap_topic;
    out_t *out;
    int n_out, cap_out;
    int *sub;  /* by msg_id: SUB_NONE, SUB_FILTERED, or the out's index + 1 */
    char *row; /* a row's text, room for the longest of the topics' */
    size_t row_cap;
    long long columns; /* of every topic's layout */
    long long appended[APPENDED_MAX];
    int n_appended, next_appended;
    sim_log_ulog_stats_t *st;
    sim_log_error_t *err;
    char msg[256];
} decoder_t;

static int fail_at(decoder_t *d, long long offset, const char *what)
{
    return sim_log_fail(d->err, d->name, 0, 0, "offset %lld: %s", offset, what);
}

static int asked_for(const decoder_t *d, const unsigned char *name, size_t len)
{
    if (d->topics == NULL || d->n_topics <= 0) {
        return 1;
    }
    for (int i = 0; i < d->n_topics; ++i) {
        if (d->topics[i] != NULL && strlen(d->topics[i]) == len && memcmp(d->topics[i], name, len) == 0) {
            return 1;
        }
    }
    return 0;
}

static int grow(void **p, int *cap, int n, size_t size)
{
    if (n < *cap) {
        return 0;
    }
    const int c = *cap > 0 ? 2 * *cap : 16;
    void *grown = realloc(*p, (size_t)c * size);
    if (grown == NULL) {
        return -1;
    }
    *p = grown;
    *cap = c;
    return 0;
}

/* The topic's index, its layout built at its first subscription; -1 with
 * the error set. */
static int find_topic(decoder_t *d, const unsigned char *name, size_t len, long long offset)
{
    for (int i = 0; i < d->n_topic; ++i) {
        if (d->topic[i].len == len && memcmp(d->topic[i].name, name, len) == 0) {
            return i;
        }
    }
    if (grow((void **)&d->topic, &d->cap_topic, d->n_topic, sizeof *d->topic) != 0) {
        return fail_at(d, offset, "out of memory");
    }
    topic_t *t = &d->topic[d->n_topic];
    char why[200];
    if (sim_ulog_layout_build(&d->formats, (const char *)name, len, &t->layout, why, sizeof why) != 0) {
        snprintf(d->msg, sizeof d->msg, "topic '%.*s': %s", (int)(len > SHOWN ? SHOWN : len), (const char *)name, why);
        return fail_at(d, offset, d->msg);
    }
    d->columns += t->layout.n_col;
    if (d->columns > COLUMNS_MAX) {
        sim_ulog_layout_free(&t->layout);
        snprintf(d->msg, sizeof d->msg, "the topics read have more than %d columns", COLUMNS_MAX);
        return fail_at(d, offset, d->msg);
    }
    const size_t row_cap = t->layout.row_max + SIM_NUMFMT_MAX; /* a number's text may run past row_max */
    if (row_cap > d->row_cap) {
        char *row = realloc(d->row, row_cap);
        if (row == NULL) {
            sim_ulog_layout_free(&t->layout);
            return fail_at(d, offset, "out of memory");
        }
        d->row = row;
        d->row_cap = row_cap;
    }
    t->name = malloc(len + 1);
    if (t->name == NULL) {
        sim_ulog_layout_free(&t->layout);
        return fail_at(d, offset, "out of memory");
    }
    memcpy(t->name, name, len);
    t->name[len] = '\0';
    t->len = len;
    return d->n_topic++;
}

/* The out of (topic, multi_id), made at its first subscription. */
static int find_out(decoder_t *d, int topic, int multi_id, long long offset)
{
    for (int i = 0; i < d->n_out; ++i) {
        if (d->out[i].topic == topic && d->out[i].multi_id == multi_id) {
            return i;
        }
    }
    if (grow((void **)&d->out, &d->cap_out, d->n_out, sizeof *d->out) != 0) {
        return fail_at(d, offset, "out of memory");
    }
    out_t *o = &d->out[d->n_out];
    memset(o, 0, sizeof *o);
    o->topic = topic;
    o->multi_id = multi_id;
    const topic_t *t = &d->topic[topic];
    const size_t base = strlen(d->out_base);
    if (base + t->len + 16 > PATH_MAX_LEN) {
        snprintf(d->msg, sizeof d->msg, "topic '%.*s': its file's path would exceed %d bytes",
                 (int)(t->len > SHOWN ? SHOWN : t->len), t->name, PATH_MAX_LEN);
        return fail_at(d, offset, d->msg);
    }
    o->path = malloc(base + t->len + 16);
    if (o->path == NULL) {
        return fail_at(d, offset, "out of memory");
    }
    memcpy(o->path, d->out_base, base);
    o->path[base] = '_';
    for (size_t i = 0; i < t->len; ++i) { /* as ulog2csv: a topic's '/' is no folder; nor NUL or control bytes */
        const unsigned char c = (unsigned char)t->name[i];
        o->path[base + 1 + i] = (c == '/' || c < 0x20 || c == 0x7f) ? '_' : (char)c;
    }
    snprintf(o->path + base + 1 + t->len, 16, "_%d.csv", multi_id);
    for (int i = 0; i < d->n_out; ++i) {
        if (strcmp(d->out[i].path, o->path) == 0) {
            free(o->path);
            snprintf(d->msg, sizeof d->msg, "topics '%.*s' and '%.*s' would write one file",
                     (int)(t->len > SHOWN ? SHOWN : t->len), t->name, SHOWN, d->topic[d->out[i].topic].name);
            return fail_at(d, offset, d->msg);
        }
    }
    return d->n_out++;
}

/* 'A': multi_id, msg_id, the topic's name. */
static int add_logged(decoder_t *d, const unsigned char *p, size_t size, long long offset)
{
    if (size < 4) {
        snprintf(d->msg, sizeof d->msg, "'A' message of %zu bytes: its multi_id, msg_id and name take 4 at least",
                 size);
        return fail_at(d, offset, d->msg);
    }
    ++d->st->subscribed;
    const int multi_id = p[0];
    const uint16_t msg_id = le16(p + 1);
    if (!asked_for(d, p + 3, size - 3)) {
        d->sub[msg_id] = SUB_FILTERED;
        return 0;
    }
    const int topic = find_topic(d, p + 3, size - 3, offset);
    const int out = topic >= 0 ? find_out(d, topic, multi_id, offset) : -1;
    if (out < 0) {
        return -1;
    }
    d->sub[msg_id] = out + 1;
    return 0;
}

static char *write_real(char *s, double v, int digits)
{
    if (isnan(v)) {
        memcpy(s, "nan", 3); /* whatever its sign, as ulog2csv */
        return s + 3;
    }
    if (digits <= 15) {
        return s + sim_fmt_g(s, v, digits);
    }
    return s + snprintf(s, SIM_NUMFMT_MAX, "%.*g", digits, v);
}

/* A text cell: the chars up to the first NUL, those that would break the
 * row written '?'. */
static char *write_text(char *s, const unsigned char *p, unsigned count)
{
    for (unsigned i = 0; i < count && p[i] != 0; ++i) {
        *s++ = (p[i] < 0x20 || p[i] >= 0x7f || p[i] == ',') ? '?' : (char)p[i];
    }
    return s;
}

/* The cell of column c of data p. */
static char *write_cell(char *s, const sim_ulog_column_t *c, const unsigned char *p)
{
    p += c->offset;
    switch ((sim_ulog_type_t)c->type) {
    case SIM_ULOG_INT8:
    case SIM_ULOG_BOOL: /* numpy int8, as ulog2csv writes them */
    case SIM_ULOG_CHAR:
        return sim_log_put_i64(s, (int8_t)p[0]);
    case SIM_ULOG_UINT8:
        return sim_log_put_u64(s, p[0]);
    case SIM_ULOG_INT16:
        return sim_log_put_i64(s, (int16_t)le16(p));
    case SIM_ULOG_UINT16:
        return sim_log_put_u64(s, le16(p));
    case SIM_ULOG_INT32:
        return sim_log_put_i64(s, (int32_t)le32(p));
    case SIM_ULOG_UINT32:
        return sim_log_put_u64(s, le32(p));
    case SIM_ULOG_INT64:
        return sim_log_put_i64(s, (int64_t)le64(p));
    case SIM_ULOG_UINT64:
        return sim_log_put_u64(s, le64(p));
    case SIM_ULOG_FLOAT: {
        const uint32_t bits = le32(p);
        float v;
        memcpy(&v, &bits, sizeof v);
        return write_real(s, (double)v, 9); /* 9 digits read back to the float */
    }
    case SIM_ULOG_DOUBLE: {
        const uint64_t bits = le64(p);
        double v;
        memcpy(&v, &bits, sizeof v);
        return write_real(s, v, 17);
    }
    case SIM_ULOG_TEXT:
        return write_text(s, p, c->count);
    }
    return s;
}

/* The row's timestamp in us, narrower fields unwrapped. */
static uint64_t row_time_us(out_t *o, const sim_ulog_column_t *ts, const unsigned char *data)
{
    const unsigned char *p = data + ts->offset;
    uint64_t raw, span;
    switch ((sim_ulog_type_t)ts->type) {
    case SIM_ULOG_UINT32:
        raw = le32(p);
        span = (uint64_t)1 << 32;
        break;
    case SIM_ULOG_UINT16:
        raw = le16(p);
        span = (uint64_t)1 << 16;
        break;
    case SIM_ULOG_UINT8:
        raw = p[0];
        span = (uint64_t)1 << 8;
        break;
    default:
        return le64(p);
    }
    if (o->ts_seen && raw < o->ts_raw) {
        o->ts_high += span;
    }
    o->ts_seen = 1;
    o->ts_raw = raw;
    const uint64_t t = o->ts_high + raw;
    return ts->type == SIM_ULOG_UINT8 ? t * 1000u : t; /* uint8_t timestamps are in ms */
}

static int open_out(decoder_t *d, out_t *o)
{
    o->f = fopen(o->path, "wb");
    if (o->f == NULL) {
        return sim_log_fail(d->err, o->path, 0, 0, "cannot create: %s", strerror(errno));
    }
    o->created = 1;
    setvbuf(o->f, NULL, _IOFBF, OUT_BUFFER);
    ++d->st->files;
    const sim_ulog_layout_t *l = &d->topic[o->topic].layout;
    if (fwrite(l->header, 1, l->header_len, o->f) != l->header_len) {
        return sim_log_fail(d->err, o->path, 0, 0, "cannot write: %s", strerror(errno));
    }
    return 0;
}

/* 'D': msg_id, the topic's data. */
static int data(decoder_t *d, const unsigned char *p, size_t size, long long offset)
{
    if (size < 2) {
        snprintf(d->msg, sizeof d->msg, "'D' message of %zu bytes: its msg_id takes 2", size);
        return fail_at(d, offset, d->msg);
    }
    const int sub = d->sub[le16(p)];
    if (sub == SUB_FILTERED) {
        return 0;
    }
    if (sub == SUB_NONE) {
        ++d->st->data_no_subscription;
        return 0;
    }
    out_t *o = &d->out[sub - 1];
    const sim_ulog_layout_t *l = &d->topic[o->topic].layout;
    const unsigned char *v = p + 2;
    const size_t n = size - 2;
    if (n < l->size_min || n > l->size_max) {
        ++d->st->data_bad_size;
        return 0;
    }
    const uint64_t t_us = row_time_us(o, &l->col[0], v);
    if (o->rows > 0 && t_us <= o->last_us) {
        ++d->st->out_of_order;
        return 0;
    }
    if (o->f == NULL && open_out(d, o) != 0) {
        return -1;
    }
    char *s = sim_log_put_u64(d->row, t_us);
    for (int c = 1; c < l->n_col; ++c) {
        *s++ = ',';
        s = write_cell(s, &l->col[c], v);
    }
    *s++ = '\n';
    const size_t len = (size_t)(s - d->row);
    if (fwrite(d->row, 1, len, o->f) != len) {
        return sim_log_fail(d->err, o->path, 0, 0, "cannot write: %s", strerror(errno));
    }
    o->last_us = t_us;
    ++o->rows;
    ++d->st->rows;
    return 0;
}

/* 'B', the first message: incompatible flags refuse the log; appended
 * data's offsets are kept. */
static int flag_bits(decoder_t *d, const unsigned char *p, size_t size, long long offset)
{
    if (size < FLAG_BITS_MIN) {
        snprintf(d->msg, sizeof d->msg, "'B' message of %zu bytes: its flags and offsets take %u", size, FLAG_BITS_MIN);
        return fail_at(d, offset, d->msg);
    }
    const unsigned char *incompat = p + 8;
    int unknown = (incompat[0] & ~1u) != 0;
    for (int i = 1; i < 8; ++i) {
        unknown |= incompat[i] != 0;
    }
    if (unknown) {
        return fail_at(d, offset, "incompatible flags set that this reader does not know: a newer ULog form");
    }
    if (incompat[0] & 1u) { /* data appended */
        for (int i = 0; i < APPENDED_MAX; ++i) {
            const uint64_t a = le64(p + 16 + 8 * i);
            if (a > 0 && a < (uint64_t)1 << 62) {
                int j = d->n_appended++; /* kept ascending: they are reached in order */
                for (; j > 0 && d->appended[j - 1] > (long long)a; --j) {
                    d->appended[j] = d->appended[j - 1];
                }
                d->appended[j] = (long long)a;
            }
        }
    }
    return 0;
}

static int message(decoder_t *d, unsigned type, const unsigned char *p, size_t size, long long offset)
{
    switch (type) {
    case 'D':
        return data(d, p, size, offset);
    case 'A':
        return add_logged(d, p, size, offset);
    case 'F':
        if (sim_ulog_formats_add(&d->formats, (const char *)p, size, d->msg, sizeof d->msg) != 0) {
            return fail_at(d, offset, d->msg);
        }
        return 0;
    case 'R':
        if (size < 2) {
            return fail_at(d, offset, "'R' message shorter than its msg_id");
        }
        d->sub[le16(p)] = SUB_NONE;
        return 0;
    case 'O':
        if (size < 2) {
            return fail_at(d, offset, "'O' message shorter than its duration");
        }
        ++d->st->dropouts;
        d->st->dropout_ms += le16(p);
        return 0;
    case 'B':
        return offset == HEADER_BYTES ? flag_bits(d, p, size, offset) : 0; /* only the first counts */
    case 'I': /* information, multi-information, parameters, defaults, text, sync: nothing to write */
    case 'M':
    case 'P':
    case 'Q':
    case 'L':
    case 'C':
    case 'S':
        return 0;
    default:
        ++d->st->unknown; /* the spec: skip messages of unknown types */
        return 0;
    }
}

/* The next appended offset after pos, those behind it passed. */
static long long next_appended(decoder_t *d, long long pos)
{
    while (d->next_appended < d->n_appended && d->appended[d->next_appended] <= pos) {
        d->st->appended += d->appended[d->next_appended] == pos;
        ++d->next_appended;
    }
    return d->next_appended < d->n_appended ? d->appended[d->next_appended] : -1;
}

static void report_progress(decoder_t *d, sim_log_ulog_progress_fn progress, void *ctx, long long total,
                            long long *next)
{
    const long long pos = reader_pos(&d->r);
    if (progress != NULL && pos >= *next) {
        progress(ctx, pos, total);
        *next = pos + PROGRESS_EVERY;
    }
}

static int decode_messages(decoder_t *d, sim_log_ulog_progress_fn progress, void *ctx, long long total)
{
    reader_t *r = &d->r;
    long long next_progress = 0;
    for (;;) {
        report_progress(d, progress, ctx, total, &next_progress);
        const long long pos = reader_pos(r);
        const long long appended = next_appended(d, pos);
        if (!reader_fill(r, MSG_HEADER)) {
            if (r->end > r->start) {
                d->st->end = SIM_LOG_ULOG_END_CUT;
                d->st->end_offset = pos;
            }
            return 0;
        }
        const unsigned char *h = r->buf + r->start;
        const size_t size = le16(h);
        const unsigned type = h[2];
        if (appended > pos && pos + MSG_HEADER + (long long)size > appended) {
            /* cut by the appended data: it resumes there */
            const long long cut = appended - pos;
            if (reader_skip(r, cut) < cut) {
                d->st->end = SIM_LOG_ULOG_END_CUT;
                d->st->end_offset = pos;
                return 0;
            }
            d->st->appended_cut_bytes += cut;
            continue;
        }
        if (type == 0 || size == 0) { /* corrupt: what pyulog takes as one too */
            long long skipped;
            r->start += 1;
            if (!reader_find_sync(r, &skipped)) {
                d->st->end = SIM_LOG_ULOG_END_CORRUPT;
                d->st->end_offset = pos;
                return 0;
            }
            ++d->st->resyncs;
            d->st->resync_bytes += skipped + 1;
            continue;
        }
        if (!reader_fill(r, MSG_HEADER + size)) {
            d->st->end = SIM_LOG_ULOG_END_CUT;
            d->st->end_offset = pos;
            return 0;
        }
        if (message(d, type, r->buf + r->start + MSG_HEADER, size, pos) != 0) {
            return -1;
        }
        ++d->st->messages;
        r->start += MSG_HEADER + size;
    }
}

static int read_header(decoder_t *d)
{
    if (!reader_fill(&d->r, HEADER_BYTES)) {
        const size_t n = d->r.end - d->r.start;
        if (n < sizeof MAGIC || memcmp(d->r.buf, MAGIC, sizeof MAGIC) != 0) {
            return fail_at(d, 0, "not a ULog: no 'ULog' magic");
        }
        snprintf(d->msg, sizeof d->msg, "the log ends inside its 16-byte header (%zu bytes)", n);
        return fail_at(d, 0, d->msg);
    }
    if (memcmp(d->r.buf, MAGIC, sizeof MAGIC) != 0) {
        return fail_at(d, 0, "not a ULog: no 'ULog' magic");
    }
    d->st->version = d->r.buf[7];
    d->r.start += HEADER_BYTES;
    return 0;
}

/* Closes every CSV; on a refusal (or a failed close) removes them all. */
static int finish(decoder_t *d, int rc)
{
    for (int i = 0; i < d->n_out; ++i) {
        out_t *o = &d->out[i];
        if (o->f != NULL && fclose(o->f) != 0 && rc == 0) {
            rc = sim_log_fail(d->err, o->path, 0, 0, "cannot write: %s", strerror(errno));
        }
        o->f = NULL;
    }
    for (int i = 0; i < d->n_out; ++i) {
        if (rc != 0 && d->out[i].created) {
            (void)remove(d->out[i].path);
        }
        free(d->out[i].path);
    }
    free(d->row);
    for (int i = 0; i < d->n_topic; ++i) {
        free(d->topic[i].name);
        sim_ulog_layout_free(&d->topic[i].layout);
    }
    free(d->out);
    free(d->topic);
    free(d->sub);
    free(d->r.buf);
    sim_ulog_formats_free(&d->formats);
    if (rc != 0) {
        d->st->files = 0;
        d->st->rows = 0;
    }
    return rc;
}

int sim_log_ulog_to_csv_stream(FILE *in, const char *name, long long total_bytes, const char *out_base,
                               const char *const *topics, int n_topics, sim_log_ulog_progress_fn progress,
                               void *progress_ctx, sim_log_ulog_stats_t *stats, sim_log_error_t *err)
{
    sim_log_ulog_stats_t own;
    decoder_t d;
    memset(&d, 0, sizeof d);
    d.st = stats != NULL ? stats : &own;
    memset(d.st, 0, sizeof *d.st);
    d.name = name;
    d.out_base = out_base;
    d.topics = topics;
    d.n_topics = n_topics;
    d.err = err;
    d.r.f = in;
    d.r.chunk = total_bytes > 0 && total_bytes < (long long)READ_CHUNK ? (size_t)total_bytes : READ_CHUNK;
    d.r.cap = d.r.chunk + MSG_MAX;
    d.r.buf = malloc(d.r.cap);
    d.sub = calloc(65536, sizeof *d.sub);
    int rc;
    if (d.r.buf == NULL || d.sub == NULL) {
        rc = fail_at(&d, 0, "out of memory");
    } else if ((rc = read_header(&d)) == 0) {
        rc = decode_messages(&d, progress, progress_ctx, total_bytes);
    }
    if (rc == 0 && d.r.error) {
        rc = sim_log_fail(err, name, 0, 0, "offset %lld: read error", reader_pos(&d.r));
    }
    d.st->bytes = d.r.base + (long long)d.r.end;
    if (rc == 0 && progress != NULL) {
        progress(progress_ctx, d.st->bytes, total_bytes);
    }
    return finish(&d, rc);
}

int sim_log_ulog_to_csv_stats(const char *in_path, const char *out_base, const char *const *topics, int n_topics,
                              sim_log_ulog_progress_fn progress, void *progress_ctx, sim_log_ulog_stats_t *stats,
                              sim_log_error_t *err)
{
    FILE *f = fopen(in_path, "rb");
    if (f == NULL) {
        return sim_log_fail(err, in_path, 0, 0, "cannot open: %s", strerror(errno));
    }
    long long total = 0;
    if (fseek(f, 0, SEEK_END) == 0) {
        total = ftell(f);
        rewind(f);
    }
    const int rc = sim_log_ulog_to_csv_stream(f, in_path, total > 0 ? total : 0, out_base, topics, n_topics, progress,
                                              progress_ctx, stats, err);
    fclose(f);
    return rc;
}

int sim_log_ulog_to_csv(const char *in_path, const char *out_base, const char *const *topics, int n_topics,
                        sim_log_ulog_progress_fn progress, void *progress_ctx, sim_log_error_t *err)
{
    return sim_log_ulog_to_csv_stats(in_path, out_base, topics, n_topics, progress, progress_ctx, NULL, err);
}

/* Appends a note to buf: "; " between notes. */
static void note(char *buf, size_t len, int *n, const char *text)
{
    const size_t used = strlen(buf);
    if (used < len) {
        snprintf(buf + used, len - used, "%s%s", *n > 0 ? "; " : "", text);
    }
    ++*n;
}

int sim_log_ulog_stats_describe(const sim_log_ulog_stats_t *st, char *buf, size_t len)
{
    char t[200];
    int n = 0;
    if (len == 0) {
        return 0;
    }
    buf[0] = '\0';
    if (st->end == SIM_LOG_ULOG_END_CUT) {
        snprintf(t, sizeof t, "the log ends inside a message at offset %lld: decoded up to it", st->end_offset);
        note(buf, len, &n, t);
    } else if (st->end == SIM_LOG_ULOG_END_CORRUPT) {
        snprintf(t, sizeof t, "a corrupt message header at offset %lld and no sync message after it: decoded up to it",
                 st->end_offset);
        note(buf, len, &n, t);
    }
    if (st->version > 1) { /* the spec: parse a newer version as well, with a warning */
        snprintf(t, sizeof t, "ULog version %d, newer than this reader's 1: read as 1", st->version);
        note(buf, len, &n, t);
    }
    if (st->dropouts > 0) {
        snprintf(t, sizeof t, "%lld dropout%s (%lld ms lost)", st->dropouts, st->dropouts == 1 ? "" : "s",
                 st->dropout_ms);
        note(buf, len, &n, t);
    }
    if (st->resyncs > 0) {
        snprintf(t, sizeof t, "%lld corrupt header%s: %lld bytes passed to the next sync message", st->resyncs,
                 st->resyncs == 1 ? "" : "s", st->resync_bytes);
        note(buf, len, &n, t);
    }
    if (st->data_bad_size + st->data_no_subscription > 0) {
        snprintf(t, sizeof t,
                 "%lld data messages skipped (%lld of a size their format does not fit, %lld of no "
                 "subscription)",
                 st->data_bad_size + st->data_no_subscription, st->data_bad_size, st->data_no_subscription);
        note(buf, len, &n, t);
    }
    if (st->out_of_order > 0) {
        snprintf(t, sizeof t, "%lld row%s whose timestamp did not increase skipped", st->out_of_order,
                 st->out_of_order == 1 ? "" : "s");
        note(buf, len, &n, t);
    }
    if (st->unknown > 0) {
        snprintf(t, sizeof t, "%lld message%s of unknown types skipped", st->unknown, st->unknown == 1 ? "" : "s");
        note(buf, len, &n, t);
    }
    if (st->appended_cut_bytes > 0) {
        snprintf(t, sizeof t, "%lld bytes of a message cut by appended data dropped", st->appended_cut_bytes);
        note(buf, len, &n, t);
    }
    return n;
}
