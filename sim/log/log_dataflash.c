/* SPDX-License-Identifier: BSD-3-Clause */
/* ArduPilot DataFlash logs into CSVs (log_dataflash.h). */
#include "log_dataflash.h"

#include "log_ardupilot.h"
#include "log_dataflash_fields.h"
#include "log_file.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define HEAD1 0xA3
#define HEAD2 0x95
#define HEADER_LEN 3
#define FMT_TYPE 128
#define FMT_LEN 89     /* header, Type B, Length B, Name n, Format N, Columns Z */
#define MAX_FIELDS 16  /* the format string is an N: 16 characters */
#define NAME_LEN 4     /* a type's name, an n */
#define COLUMNS_LEN 64 /* the column names, a Z */
#define N_TYPES 256
#define N_INSTANCES 256
#define IN_BUF (1 << 16)
#define OUT_BUF (1 << 14)          /* each CSV's stdio buffer: 512 of them stay under 8 MiB */
#define PROGRESS_EVERY (4LL << 20) /* bytes between progress calls */
#define LINE_MAX (MAX_FIELDS * DF_ARRAY_N * (DF_CELL_MAX + 1) + 2)
#define POW10_TOL 1e-6 /* relative: a multiplier this close to a power of ten is one (MULTs are floats widened) */

typedef struct {
    int defined, frozen, wanted, has_fmtu;
    int length; /* header included */
    char name[NAME_LEN + 1];
    char format[MAX_FIELDS + 1];
    char names[COLUMNS_LEN + 1]; /* the column names, each NUL-terminated */
    char unit_ids[MAX_FIELDS + 1], mult_ids[MAX_FIELDS + 1];
    int n_fields;
    field_t field[MAX_FIELDS];
    int time_field, instance_field; /* -1: none */
} type_t;

typedef struct {
    FILE *f;
    char *path;
    long long last_time;
    int has_rows;
} output_t;

typedef struct {
    FILE *in;
    const char *name;
    const char *out_base;
    const char *const *topics;
    int n_topics;
    sim_log_convert_progress_fn progress;
    void *progress_ctx;
    long long total;
    sim_log_dataflash_stats_t *st;
    sim_log_error_t *err;
    unsigned char *buf;
    size_t buf_len, buf_pos;
    long long buf_offset; /* of buf[0] in the log */
    int in_eof;
    type_t *type;
    double mult_of[256];
    int mult_known[256];
    int fmtu_type, mult_type; /* -1 until defined */
    short *out_index;         /* [type * N_INSTANCES + instance]: -1, or into out */
    output_t *out;
    int n_out;
    char *line;
    int in_skip; /* inside a run of skipped bytes */
} decoder_t;

static int fail(decoder_t *d, long long offset, const char *what)
{
    return sim_log_fail(d->err, d->name, 0, 0, "offset %lld: %s", offset, what);
}

/* ---- input ---- */

/* At least `need` bytes from buf_pos when the log has them: the bytes there. */
static size_t fill(decoder_t *d, size_t need)
{
    size_t have = d->buf_len - d->buf_pos;
    if (have >= need || d->in_eof) {
        return have;
    }
    memmove(d->buf, d->buf + d->buf_pos, have);
    d->buf_offset += (long long)d->buf_pos;
    d->buf_pos = 0;
    d->buf_len = have;
    while (d->buf_len < need && !d->in_eof) {
        const size_t got = fread(d->buf + d->buf_len, 1, IN_BUF - d->buf_len, d->in);
        d->buf_len += got;
        if (got == 0) {
            d->in_eof = 1;
        }
    }
    return d->buf_len;
}

static long long offset_now(const decoder_t *d)
{
    return d->buf_offset + (long long)d->buf_pos;
}

/* ---- FMT, FMTU, MULT ---- */

static int is_name_char(unsigned char ch)
{
    return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_';
}

static int find_field(const type_t *t, const char *name)
{
    for (int i = 0; i < t->n_fields; ++i) {
        if (strcmp(t->names + t->field[i].name_at, name) == 0) {
            return i;
        }
    }
    return -1;
}

/* The column that times the type's rows: SampleUS for GYR and ACC, written
 * in bursts, TimeUS for the others. */
static const char *time_name_of(const type_t *t)
{
    return sim_log_ardupilot_sample_timed(t->name) ? "SampleUS" : "TimeUS";
}

static int is_wanted(const decoder_t *d, const char *name)
{
    if (d->topics == NULL || d->n_topics <= 0) {
        return 1;
    }
    for (int i = 0; i < d->n_topics; ++i) {
        if (d->topics[i] != NULL && strcmp(d->topics[i], name) == 0) {
            return 1;
        }
    }
    return 0;
}

/* The FMT message's definition into *t: 0, or -1 when it cannot be used. */
static int parse_fmt(const unsigned char *m, type_t *t)
{
    memset(t, 0, sizeof *t);
    t->length = m[4];
    int n = 0;
    while (n < NAME_LEN && m[5 + n] != 0) {
        if (!is_name_char(m[5 + n])) {
            return -1;
        }
        t->name[n] = (char)m[5 + n];
        ++n;
    }
    int k = 0, size = HEADER_LEN;
    while (k < MAX_FIELDS && m[9 + k] != 0) {
        const char kind = (char)m[9 + k];
        const int s = df_kind_size(kind);
        if (s == 0) {
            return -1;
        }
        t->format[k] = kind;
        t->field[k].kind = kind;
        t->field[k].size = (unsigned char)s;
        t->field[k].offset = (unsigned char)size;
        size += s;
        ++k;
    }
    t->n_fields = k;
    if (n == 0 || size > t->length) { /* bytes past the fields: framed, not read (Copter 3.x's BAR3) */
        return -1;
    }
    if (k == 0) { /* Copter 3.2's STRT: frames its messages, writes nothing */
        return m[25] == 0 ? 0 : -1;
    }
    /* the names: k of them, comma separated, printable */
    int f = 0, at = 0;
    t->field[0].name_at = 0;
    for (int i = 0; i < COLUMNS_LEN && m[25 + i] != 0; ++i) {
        const unsigned char ch = m[25 + i];
        if (ch == ',') {
            if (at == t->field[f].name_at || f + 1 >= k) {
                return -1;
            }
            t->names[at++] = '\0';
            t->field[++f].name_at = at;
        } else if (ch <= 0x20 || ch > 0x7e || ch == '"') {
            return -1;
        } else {
            t->names[at++] = (char)ch;
        }
    }
    if (f + 1 != k || at == t->field[f].name_at) {
        return -1;
    }
    for (int i = 0; i < k; ++i) { /* each name once: one column is the time */
        if (find_field(t, t->names + t->field[i].name_at) != i) {
            return -1;
        }
    }
    /* the time column, where there is one, a plain integer (us) */
    const int time_at = find_field(t, time_name_of(t));
    return time_at >= 0 && strchr("bBhHiIqQM", t->field[time_at].kind) == NULL ? -1 : 0;
}

static int same_definition(const type_t *a, const type_t *b)
{
    return a->length == b->length && strcmp(a->name, b->name) == 0 && strcmp(a->format, b->format) == 0 &&
           memcmp(a->names, b->names, sizeof a->names) == 0;
}

static void take_fmt(decoder_t *d, const unsigned char *m)
{
    const int id = m[3];
    type_t t;
    if (id == FMT_TYPE) {
        return; /* FMT's own definition is fixed */
    }
    if (parse_fmt(m, &t) != 0) {
        ++d->st->bad_fmts;
        return;
    }
    type_t *old = &d->type[id];
    if (old->defined && same_definition(old, &t)) {
        return;
    }
    if (old->frozen) { /* rows written under the old definition */
        ++d->st->bad_fmts;
        return;
    }
    for (int j = 0; j < N_TYPES; ++j) {
        if (j != id && d->type[j].defined && strcmp(d->type[j].name, t.name) == 0) {
            ++d->st->bad_fmts; /* two types of one name: one file name */
            return;
        }
    }
    t.defined = 1;
    t.wanted = is_wanted(d, t.name);
    *old = t;
    snprintf(d->st->type_name[id], sizeof d->st->type_name[id], "%s", t.name);
    if (strcmp(t.name, "FMTU") == 0) {
        d->fmtu_type = id;
    } else if (strcmp(t.name, "MULT") == 0) {
        d->mult_type = id;
    }
}

/* The text of a text field into out (NUL-terminated, at most len - 1). */
static void field_text(const type_t *t, int i, const unsigned char *m, char *out, size_t len)
{
    size_t n = 0;
    if (i >= 0 && df_is_text_kind(t->field[i].kind)) {
        const unsigned char *s = m + t->field[i].offset;
        while (n + 1 < len && n < t->field[i].size && s[n] != 0) {
            out[n] = (char)s[n];
            ++n;
        }
    }
    out[n] = '\0';
}

static void take_fmtu(decoder_t *d, const unsigned char *m)
{
    const type_t *u = &d->type[d->fmtu_type];
    const int type_at = find_field(u, "FmtType");
    if (type_at < 0 || !df_is_integer_kind(u->field[type_at].kind)) {
        return;
    }
    const uint64_t id = df_get_le(m + u->field[type_at].offset, u->field[type_at].size);
    if (id >= N_TYPES || !d->type[id].defined || d->type[id].frozen) {
        return;
    }
    type_t *t = &d->type[id];
    field_text(u, find_field(u, "UnitIds"), m, t->unit_ids, sizeof t->unit_ids);
    field_text(u, find_field(u, "MultIds"), m, t->mult_ids, sizeof t->mult_ids);
    t->has_fmtu = 1;
}

static void take_mult(decoder_t *d, const unsigned char *m)
{
    const type_t *u = &d->type[d->mult_type];
    const int id_at = find_field(u, "Id"), mult_at = find_field(u, "Mult");
    if (id_at < 0 || mult_at < 0 || u->field[mult_at].kind != 'd' || u->field[id_at].size != 1) {
        return;
    }
    const unsigned id = m[u->field[id_at].offset];
    const double v = df_get_double(m + u->field[mult_at].offset);
    if (isfinite(v) && v != 0.0) {
        d->mult_of[id] = v;
        d->mult_known[id] = 1;
    }
}

/* A name that says its unit (TimeUS, SampleUS, GMS): written as logged. */
static int names_time_unit(const char *name)
{
    const size_t n = strlen(name);
    return n >= 2 && (strcmp(name + n - 2, "US") == 0 || strcmp(name + n - 2, "MS") == 0);
}

/* Each field's conversion, the time and instance fields: at the type's first row. */
static void freeze(decoder_t *d, type_t *t)
{
    const char *time_name = time_name_of(t);
    t->frozen = 1;
    t->time_field = -1;
    t->instance_field = -1;
    for (int i = 0; i < t->n_fields; ++i) {
        field_t *f = &t->field[i];
        const char *name = t->names + f->name_at;
        f->exp10 = strchr("cCeE", f->kind) != NULL ? -2 : (f->kind == 'L' ? -7 : 0);
        f->mult = 1.0;
        if (strcmp(name, time_name) == 0) { /* a plain integer (parse_fmt) */
            t->time_field = i;
        }
        if (t->has_fmtu && i < (int)strlen(t->unit_ids) && t->unit_ids[i] == '#') {
            t->instance_field = i;
        }
        /* c C e E L carry their scale; the FMTU multiplier restates it */
        const int own_scale = f->exp10 != 0 || f->kind == 'a' || df_is_text_kind(f->kind);
        if (!t->has_fmtu || own_scale || names_time_unit(name) || i >= (int)strlen(t->mult_ids)) {
            continue;
        }
        const unsigned char id = (unsigned char)t->mult_ids[i];
        if (id == '-' || id == '?' || !d->mult_known[id]) {
            continue;
        }
        const double m = d->mult_of[id];
        const double k = floor(log10(fabs(m)) + 0.5);
        const int pow10 = m > 0.0 && fabs(m - pow(10.0, k)) <= POW10_TOL * m && fabs(k) <= 12.0;
        if (pow10 && df_is_integer_kind(f->kind)) {
            f->exp10 = (int)k;
        } else {
            f->mult = pow10 ? pow(10.0, k) : m;
        }
    }
    if (!t->has_fmtu) {
        const int a = find_field(t, "I"), b = find_field(t, "Instance");
        t->instance_field = a >= 0 ? a : b;
    }
    if (t->instance_field >= 0 && (!df_is_integer_kind(t->field[t->instance_field].kind) ||
                                   t->field[t->instance_field].exp10 != 0 || t->field[t->instance_field].mult != 1.0)) {
        t->instance_field = -1;
    }
}

/* ---- output ---- */

static int write_header(decoder_t *d, const type_t *t, FILE *f)
{
    char *p = d->line;
    for (int i = 0; i < t->n_fields; ++i) {
        const char *name = t->names + t->field[i].name_at;
        if (t->field[i].kind == 'a') {
            for (int k = 0; k < DF_ARRAY_N; ++k) {
                p += sprintf(p, "%s%s[%d]", (i > 0 || k > 0) ? "," : "", name, k);
            }
        } else {
            p += sprintf(p, "%s%s", i > 0 ? "," : "", name);
        }
    }
    *p++ = '\n';
    return fwrite(d->line, 1, (size_t)(p - d->line), f) == (size_t)(p - d->line) ? 0 : -1;
}

/* The output of (type, instance), opened at its first row: its index, or -1 with err set. */
static int output_of(decoder_t *d, int id, int instance, long long offset)
{
    const int at = id * N_INSTANCES + instance;
    if (d->out_index[at] >= 0) {
        return d->out_index[at];
    }
    const type_t *t = &d->type[id];
    if (d->n_out == SIM_LOG_DATAFLASH_MAX_FILES) {
        char what[160];
        snprintf(what, sizeof what, "%s instance %d would be CSV number %d, more than %d", t->name, instance,
                 d->n_out + 1, SIM_LOG_DATAFLASH_MAX_FILES);
        return fail(d, offset, what);
    }
    const size_t len = strlen(d->out_base) + NAME_LEN + 16;
    output_t *o = &d->out[d->n_out];
    memset(o, 0, sizeof *o);
    if ((o->path = malloc(len)) == NULL) {
        return fail(d, offset, "out of memory");
    }
    snprintf(o->path, len, "%s_%s_%d.csv", d->out_base, t->name, instance);
    if ((o->f = fopen(o->path, "wb")) == NULL) {
        sim_log_fail(d->err, o->path, 0, 0, "cannot write: %s", strerror(errno));
        free(o->path);
        o->path = NULL;
        return -1;
    }
    setvbuf(o->f, NULL, _IOFBF, OUT_BUF);
    d->out_index[at] = (short)d->n_out;
    ++d->n_out;
    if (write_header(d, t, o->f) != 0) {
        sim_log_fail(d->err, o->path, 0, 0, "cannot write: %s", strerror(errno));
        return -1;
    }
    return d->n_out - 1;
}

static int write_row(decoder_t *d, int id, const unsigned char *m, long long offset)
{
    type_t *t = &d->type[id];
    if (!t->frozen) {
        freeze(d, t);
    }
    int instance = 0;
    if (t->instance_field >= 0) {
        uint64_t mag;
        int neg;
        const field_t *f = &t->field[t->instance_field];
        df_get_integer(m + f->offset, f->kind, f->size, &mag, &neg);
        if (neg || mag >= N_INSTANCES) {
            ++d->st->rows_bad_instance;
            return 0;
        }
        instance = (int)mag;
    }
    const int k = output_of(d, id, instance, offset);
    if (k < 0) {
        return -1;
    }
    output_t *o = &d->out[k];
    if (t->time_field >= 0) {
        const field_t *f = &t->field[t->time_field];
        uint64_t mag;
        int neg;
        df_get_integer(m + f->offset, f->kind, f->size, &mag, &neg);
        const long long time = neg ? -(long long)(mag > (uint64_t)LLONG_MAX ? (uint64_t)LLONG_MAX : mag)
                                   : (long long)(mag > (uint64_t)LLONG_MAX ? (uint64_t)LLONG_MAX : mag);
        if (o->has_rows && time <= o->last_time) {
            ++d->st->rows_backwards;
            return 0;
        }
        o->last_time = time;
    }
    o->has_rows = 1;
    char *p = d->line;
    for (int i = 0; i < t->n_fields; ++i) {
        if (i > 0) {
            *p++ = ',';
        }
        p += df_put_field(p, &t->field[i], m);
    }
    *p++ = '\n';
    if (fwrite(d->line, 1, (size_t)(p - d->line), o->f) != (size_t)(p - d->line)) {
        sim_log_fail(d->err, o->path, 0, 0, "cannot write: %s", strerror(errno));
        return -1;
    }
    ++d->st->rows;
    return 0;
}

/* ---- the messages ---- */

static int take_message(decoder_t *d, int id, const unsigned char *m, long long offset)
{
    ++d->st->messages;
    ++d->st->type_count[id];
    if (id == FMT_TYPE) {
        take_fmt(d, m);
    } else if (id == d->fmtu_type) {
        take_fmtu(d, m);
    } else if (id == d->mult_type) {
        take_mult(d, m);
    }
    return d->type[id].wanted && d->type[id].n_fields > 0 ? write_row(d, id, m, offset) : 0;
}

static void skip_byte(decoder_t *d, long long offset)
{
    if (!d->in_skip) {
        ++d->st->skip_runs;
        if (d->st->first_skip_offset < 0) {
            d->st->first_skip_offset = offset;
        }
        d->in_skip = 1;
    }
    ++d->st->skipped_bytes;
    ++d->buf_pos;
}

static int decode(decoder_t *d)
{
    long long next_progress = PROGRESS_EVERY;
    for (;;) {
        const long long offset = offset_now(d);
        if (d->progress != NULL && offset >= next_progress) {
            d->progress(d->progress_ctx, offset, d->total);
            next_progress = offset + PROGRESS_EVERY;
        }
        size_t have = fill(d, HEADER_LEN);
        if (have == 0) {
            break;
        }
        const unsigned char *p = d->buf + d->buf_pos;
        if (have < HEADER_LEN) {
            if (p[0] == HEAD1 && (have == 1 || p[1] == HEAD2)) {
                d->st->truncated = 1; /* a header cut short */
                d->st->truncated_offset = offset;
                break;
            }
            skip_byte(d, offset);
            continue;
        }
        const int id = p[2];
        if (p[0] != HEAD1 || p[1] != HEAD2 || !d->type[id].defined) {
            skip_byte(d, offset);
            continue;
        }
        const size_t len = (size_t)d->type[id].length;
        have = fill(d, len);
        p = d->buf + d->buf_pos;
        if (have < len) {
            d->st->truncated = 1;
            d->st->truncated_offset = offset;
            break;
        }
        d->in_skip = 0;
        if (take_message(d, id, p, offset) != 0) {
            return -1;
        }
        d->buf_pos += len;
    }
    if (ferror(d->in)) {
        return fail(d, offset_now(d), "read error");
    }
    d->st->bytes = offset_now(d) + (long long)(d->buf_len - d->buf_pos);
    if (d->progress != NULL) {
        d->progress(d->progress_ctx, d->st->bytes, d->total);
    }
    int fmts = 0;
    for (int i = 0; i < N_TYPES; ++i) {
        fmts += i != FMT_TYPE && d->type[i].defined;
    }
    if (fmts == 0) {
        return fail(d, 0, "not an ArduPilot DataFlash log: no FMT message (0xA3 0x95 0x80) defines a message type");
    }
    return 0;
}

/* Every CSV closed; on failure (rc != 0) removed. */
static int finish(decoder_t *d, int rc)
{
    for (int i = 0; i < d->n_out; ++i) {
        output_t *o = &d->out[i];
        if (o->f != NULL) {
            const int bad = ferror(o->f);
            if (fclose(o->f) != 0 || bad) {
                if (rc == 0) {
                    rc = sim_log_fail(d->err, o->path, 0, 0, "cannot write: %s", strerror(errno));
                }
            }
        }
    }
    for (int i = 0; i < d->n_out; ++i) {
        if (rc != 0) {
            remove(d->out[i].path);
        }
        free(d->out[i].path);
    }
    d->st->files = rc == 0 ? d->n_out : 0;
    return rc;
}

static void define_fmt(type_t *t)
{
    static const char NAMES[] = "Type,Length,Name,Format,Columns";
    unsigned char m[FMT_LEN];
    memset(m, 0, sizeof m);
    m[3] = FMT_TYPE;
    m[4] = FMT_LEN;
    memcpy(m + 5, "FMT", 3);
    memcpy(m + 9, "BBnNZ", 5);
    memcpy(m + 25, NAMES, sizeof NAMES - 1);
    parse_fmt(m, t);
    t->defined = 1;
}

static int run(FILE *in, const char *name, long long total, const char *out_base, const char *const *topics,
               int n_topics, sim_log_convert_progress_fn progress, void *progress_ctx, sim_log_dataflash_stats_t *st,
               sim_log_error_t *err)
{
    decoder_t d;
    memset(&d, 0, sizeof d);
    memset(st, 0, sizeof *st);
    st->first_skip_offset = -1;
    st->truncated_offset = -1;
    d.in = in;
    d.name = name;
    d.out_base = out_base;
    d.topics = topics;
    d.n_topics = n_topics;
    d.progress = progress;
    d.progress_ctx = progress_ctx;
    d.total = total;
    d.st = st;
    d.err = err;
    d.fmtu_type = -1;
    d.mult_type = -1;
    d.buf = malloc(IN_BUF);
    d.type = calloc(N_TYPES, sizeof *d.type);
    d.out_index = malloc(sizeof *d.out_index * N_TYPES * N_INSTANCES);
    d.out = calloc(SIM_LOG_DATAFLASH_MAX_FILES, sizeof *d.out);
    d.line = malloc(LINE_MAX);
    int rc;
    if (d.buf == NULL || d.type == NULL || d.out_index == NULL || d.out == NULL || d.line == NULL) {
        rc = fail(&d, 0, "out of memory");
    } else {
        for (int i = 0; i < N_TYPES * N_INSTANCES; ++i) {
            d.out_index[i] = -1;
        }
        define_fmt(&d.type[FMT_TYPE]);
        d.type[FMT_TYPE].wanted = is_wanted(&d, "FMT");
        snprintf(st->type_name[FMT_TYPE], sizeof st->type_name[FMT_TYPE], "FMT");
        rc = decode(&d);
    }
    rc = finish(&d, rc);
    free(d.buf);
    free(d.type);
    free(d.out_index);
    free(d.out);
    free(d.line);
    return rc;
}

int sim_log_dataflash_to_csv_stream(FILE *in, const char *name, const char *out_base, const char *const *topics,
                                    int n_topics, sim_log_convert_progress_fn progress, void *progress_ctx,
                                    sim_log_dataflash_stats_t *st, sim_log_error_t *err)
{
    sim_log_dataflash_stats_t own;
    return run(in, name, 0, out_base, topics, n_topics, progress, progress_ctx, st != NULL ? st : &own, err);
}

int sim_log_dataflash_to_csv(const char *in_path, const char *out_base, const char *const *topics, int n_topics,
                             sim_log_convert_progress_fn progress, void *progress_ctx, sim_log_error_t *err)
{
    FILE *in = fopen(in_path, "rb");
    if (in == NULL) {
        return sim_log_fail(err, in_path, 0, 0, "cannot open: %s", strerror(errno));
    }
    long long total = 0;
    if (fseek(in, 0, SEEK_END) == 0) {
        const long end = ftell(in);
        total = end > 0 ? (long long)end : 0;
    }
    rewind(in);
    sim_log_dataflash_stats_t *st = malloc(sizeof *st);
    if (st == NULL) {
        fclose(in);
        return sim_log_fail(err, in_path, 0, 0, "out of memory");
    }
    int rc = run(in, in_path, total, out_base, topics, n_topics, progress, progress_ctx, st, err);
    fclose(in);
    if (rc == 0 && st->skipped_bytes > 0) {
        fprintf(stderr, "%s: offset %lld: %lld bytes skipped in %lld runs (not a message of a defined type)\n", in_path,
                st->first_skip_offset, st->skipped_bytes, st->skip_runs);
    }
    if (rc == 0 && st->truncated) {
        fprintf(stderr, "%s: offset %lld: the log ends inside a message: decoded up to there\n", in_path,
                st->truncated_offset);
    }
    if (rc == 0 && st->rows_backwards > 0) {
        fprintf(stderr, "%s: %lld rows dropped whose TimeUS was not after their previous row's\n", in_path,
                st->rows_backwards);
    }
    free(st);
    return rc;
}
