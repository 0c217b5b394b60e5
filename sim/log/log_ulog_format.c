/* SPDX-License-Identifier: BSD-3-Clause */
/* ULog formats and a topic's flattened layout (log_ulog_format.h). */
#include "log_ulog_format.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEPTH_MAX 32      /* nesting: PX4's deepest is 2 */
#define NAME_MAX_LEN 1024 /* a flattened column name */
#define SHOWN 60          /* characters of a name quoted in a message */

static const struct {
    const char *name;
    sim_ulog_type_t type;
    uint32_t size;
    size_t width; /* the longest text of a value: "-9223372036854775808", "-1.17549435e-38" */
} BASIC[] = {
    {"int8_t", SIM_ULOG_INT8, 1, 4},     {"uint8_t", SIM_ULOG_UINT8, 1, 3},    {"int16_t", SIM_ULOG_INT16, 2, 6},
    {"uint16_t", SIM_ULOG_UINT16, 2, 5}, {"int32_t", SIM_ULOG_INT32, 4, 11},   {"uint32_t", SIM_ULOG_UINT32, 4, 10},
    {"int64_t", SIM_ULOG_INT64, 8, 20},  {"uint64_t", SIM_ULOG_UINT64, 8, 20}, {"float", SIM_ULOG_FLOAT, 4, 16},
    {"double", SIM_ULOG_DOUBLE, 8, 24},  {"bool", SIM_ULOG_BOOL, 1, 4},        {"char", SIM_ULOG_CHAR, 1, 4},
};
#define N_BASIC ((int)(sizeof BASIC / sizeof BASIC[0]))

uint32_t sim_ulog_type_size(sim_ulog_type_t t)
{
    return t == SIM_ULOG_TEXT ? 1u : BASIC[t].size;
}

static int fail(char *msg, size_t len, const char *format, const char *p, size_t n)
{
    snprintf(msg, len, format, (int)(n > SHOWN ? SHOWN : n), p);
    return -1;
}

int sim_ulog_formats_add(sim_ulog_formats_t *fs, const char *text, size_t len, char *msg, size_t msg_len)
{
    const char *colon = memchr(text, ':', len);
    if (colon == NULL || colon == text) {
        return fail(msg, msg_len, "format '%.*s': no 'name:' before its fields", text, len);
    }
    const size_t name_len = (size_t)(colon - text);
    int i = 0;
    while (i < fs->n && !(fs->f[i].name_len == name_len && memcmp(fs->f[i].name, text, name_len) == 0)) {
        ++i;
    }
    const size_t held = fs->bytes - (i < fs->n ? strlen(fs->f[i].name) : 0u);
    if (held + len > SIM_ULOG_FORMATS_BYTES_MAX) {
        snprintf(msg, msg_len, "the formats exceed %u bytes", SIM_ULOG_FORMATS_BYTES_MAX);
        return -1;
    }
    char *copy = malloc(len + 1);
    if (copy == NULL) {
        snprintf(msg, msg_len, "out of memory");
        return -1;
    }
    memcpy(copy, text, len);
    copy[len] = '\0';
    if (i == fs->n) {
        if (fs->n == fs->cap) {
            const int cap = fs->cap > 0 ? 2 * fs->cap : 64;
            sim_ulog_format_t *grown = realloc(fs->f, (size_t)cap * sizeof *grown);
            if (grown == NULL) {
                free(copy);
                snprintf(msg, msg_len, "out of memory");
                return -1;
            }
            fs->f = grown;
            fs->cap = cap;
        }
        ++fs->n;
    } else {
        free(fs->f[i].name); /* the later definition wins, as pyulog reads it */
    }
    fs->f[i].name = copy;
    fs->f[i].name_len = name_len;
    fs->bytes = held + len;
    return 0;
}

void sim_ulog_formats_free(sim_ulog_formats_t *fs)
{
    for (int i = 0; i < fs->n; ++i) {
        free(fs->f[i].name);
    }
    free(fs->f);
    memset(fs, 0, sizeof *fs);
}

static const sim_ulog_format_t *find(const sim_ulog_formats_t *fs, const char *name, size_t len)
{
    for (int i = 0; i < fs->n; ++i) {
        if (fs->f[i].name_len == len && memcmp(fs->f[i].name, name, len) == 0) {
            return &fs->f[i];
        }
    }
    return NULL;
}

/* The flattening in progress. */
typedef struct {
    const sim_ulog_formats_t *fs;
    sim_ulog_layout_t *l;
    int cap_col;
    char name[NAME_MAX_LEN]; /* the prefix of the current field */
    size_t name_len;
    uint32_t offset;
    uint32_t end_used; /* end of the last field that is not the top level's padding */
    int in_padding;    /* within a top-level field named _padding*: no columns (ulog2csv shows none) */
    int ts_col;        /* the top-level timestamp's column, -1 */
    size_t header_cap;
    char *msg;
    size_t msg_len;
} walk_t;

static int out_of_memory(walk_t *w)
{
    snprintf(w->msg, w->msg_len, "out of memory");
    return -1;
}

static int append_header(walk_t *w, const char *text, size_t n)
{
    sim_ulog_layout_t *l = w->l;
    if (l->header_len + n + 2 > w->header_cap) {
        size_t cap = w->header_cap > 0 ? w->header_cap : 256;
        while (l->header_len + n + 2 > cap) {
            cap *= 2;
        }
        char *grown = realloc(l->header, cap);
        if (grown == NULL) {
            return out_of_memory(w);
        }
        l->header = grown;
        w->header_cap = cap;
    }
    memcpy(l->header + l->header_len, text, n);
    l->header_len += n;
    return 0;
}

/* One column at the current offset, named by the prefix (the timestamp's
 * name is written first, when the header is finished). */
static int add_column(walk_t *w, sim_ulog_type_t type, uint16_t count, int is_timestamp)
{
    const int is_padding = w->in_padding;
    sim_ulog_layout_t *l = w->l;
    const uint32_t size = type == SIM_ULOG_TEXT ? count : BASIC[type].size;
    if (!is_padding) {
        if (l->n_col == w->cap_col) {
            const int cap = w->cap_col > 0 ? 2 * w->cap_col : 32;
            sim_ulog_column_t *grown = realloc(l->col, (size_t)cap * sizeof *grown);
            if (grown == NULL) {
                return out_of_memory(w);
            }
            l->col = grown;
            w->cap_col = cap;
        }
        l->col[l->n_col].offset = w->offset;
        l->col[l->n_col].count = count;
        l->col[l->n_col].type = (uint8_t)type;
        if (is_timestamp) {
            w->ts_col = l->n_col;
        } else if (append_header(w, ",", 1) != 0 || append_header(w, w->name, w->name_len) != 0) {
            return -1;
        }
        l->row_max += 1 + (type == SIM_ULOG_TEXT ? count : BASIC[type].width);
        ++l->n_col;
    }
    w->offset += size;
    if (w->offset > SIM_ULOG_DATA_MAX) {
        snprintf(w->msg, w->msg_len, "larger than a data message's %u bytes", SIM_ULOG_DATA_MAX);
        return -1;
    }
    if (!is_padding) {
        w->end_used = w->offset;
    }
    return 0;
}

/* The prefix extended by text (its length restored by the caller); a
 * comma or a control byte, which would break the header's cells, written
 * '?'. */
static int push_name(walk_t *w, const char *text, size_t n)
{
    if (w->name_len + n >= sizeof w->name) {
        return fail(w->msg, w->msg_len, "a field name longer than 1023 bytes: '%.*s'", w->name, w->name_len);
    }
    for (size_t i = 0; i < n; ++i) {
        const unsigned char c = (unsigned char)text[i];
        w->name[w->name_len + i] = (c < 0x20 || c == 0x7f || c == ',') ? '?' : (char)c;
    }
    w->name_len += n;
    w->name[w->name_len] = '\0';
    return 0;
}

static int push_index(walk_t *w, uint32_t i, int dot)
{
    char idx[16];
    const int n = snprintf(idx, sizeof idx, dot ? "[%u]." : "[%u]", (unsigned)i);
    return push_name(w, idx, (size_t)n);
}

static int walk(walk_t *w, const sim_ulog_format_t *f, int depth);

/* One field "type name" or "type[n] name" of the format. */
static int walk_field(walk_t *w, const char *p, const char *end, int depth)
{
    const char *space = memchr(p, ' ', (size_t)(end - p));
    if (space == NULL || space == p || space + 1 == end) {
        return fail(w->msg, w->msg_len, "field '%.*s': not 'type name'", p, (size_t)(end - p));
    }
    const char *name = space + 1;
    const char *name_end = memchr(name, ' ', (size_t)(end - name));
    name_end = name_end != NULL ? name_end : end;
    const char *bracket = memchr(p, '[', (size_t)(space - p));
    const char *type_end = bracket != NULL ? bracket : space;
    uint32_t count = 0; /* 0: not an array */
    if (bracket != NULL) {
        const char *q = bracket + 1;
        while (q < space && *q >= '0' && *q <= '9' && count <= SIM_ULOG_DATA_MAX) {
            count = count * 10u + (uint32_t)(*q++ - '0');
        }
        if (q + 1 != space || *q != ']' || count == 0 || count > SIM_ULOG_DATA_MAX) {
            return fail(w->msg, w->msg_len, "field '%.*s': bad array length", p, (size_t)(end - p));
        }
    }
    const size_t saved = w->name_len;
    const int top = depth == 0;
    if (top) {
        w->in_padding = (size_t)(name_end - name) >= 8 && memcmp(name, "_padding", 8) == 0;
    }
    const int is_timestamp =
        top && count == 0 && w->ts_col < 0 && name_end - name == 9 && memcmp(name, "timestamp", 9) == 0;
    if (push_name(w, name, (size_t)(name_end - name)) != 0) {
        return -1;
    }
    int b = 0;
    while (b < N_BASIC && !(strlen(BASIC[b].name) == (size_t)(type_end - p) &&
                            memcmp(BASIC[b].name, p, (size_t)(type_end - p)) == 0)) {
        ++b;
    }
    int rc = 0;
    if (b < N_BASIC && BASIC[b].type == SIM_ULOG_CHAR && count > 0) {
        rc = add_column(w, SIM_ULOG_TEXT, (uint16_t)count, 0);
    } else if (b < N_BASIC) {
        for (uint32_t i = 0; rc == 0 && i < (count > 0 ? count : 1u); ++i) {
            const size_t base = w->name_len;
            rc = count > 0 ? push_index(w, i, 0) : 0;
            rc = rc == 0 ? add_column(w, BASIC[b].type, 1, is_timestamp) : rc;
            w->name_len = base;
        }
    } else {
        const sim_ulog_format_t *nested = find(w->fs, p, (size_t)(type_end - p));
        if (nested == NULL) {
            return fail(w->msg, w->msg_len, "no format of the type '%.*s'", p, (size_t)(type_end - p));
        }
        for (uint32_t i = 0; rc == 0 && i < (count > 0 ? count : 1u); ++i) {
            const size_t base = w->name_len;
            rc = count > 0 ? push_index(w, i, 1) : push_name(w, ".", 1);
            rc = rc == 0 ? walk(w, nested, depth + 1) : rc;
            w->name_len = base;
        }
    }
    w->name_len = saved;
    return rc;
}

static int walk(walk_t *w, const sim_ulog_format_t *f, int depth)
{
    if (depth >= DEPTH_MAX) {
        return fail(w->msg, w->msg_len, "format '%.*s' nested deeper than 32 (circular?)", f->name, f->name_len);
    }
    const char *p = f->name + f->name_len + 1;
    const char *end = p + strlen(p);
    int fields = 0;
    while (p < end) {
        const char *semi = memchr(p, ';', (size_t)(end - p));
        const char *f_end = semi != NULL ? semi : end;
        if (f_end > p) {
            ++fields;
            if (walk_field(w, p, f_end, depth) != 0) {
                return -1;
            }
        }
        p = f_end + 1;
    }
    if (fields == 0) {
        return fail(w->msg, w->msg_len, "format '%.*s' has no fields", f->name, f->name_len);
    }
    return 0;
}

/* The timestamp's column first, its name first in the header. */
static int timestamp_first(walk_t *w)
{
    sim_ulog_layout_t *l = w->l;
    const sim_ulog_type_t t = w->ts_col >= 0 ? (sim_ulog_type_t)l->col[w->ts_col].type : SIM_ULOG_FLOAT;
    if (t != SIM_ULOG_UINT64 && t != SIM_ULOG_UINT32 && t != SIM_ULOG_UINT16 && t != SIM_ULOG_UINT8) {
        snprintf(w->msg, w->msg_len, "no field 'timestamp' of an unsigned integer type");
        return -1;
    }
    const sim_ulog_column_t ts = l->col[w->ts_col];
    memmove(&l->col[1], &l->col[0], (size_t)w->ts_col * sizeof ts);
    l->col[0] = ts;
    l->row_max += BASIC[SIM_ULOG_UINT64].width; /* unwrapped, in us */
    static const char NAME[] = "timestamp";
    if (append_header(w, "\n", 1) != 0 || append_header(w, NAME, sizeof NAME - 1) != 0) {
        return -1; /* the second: room for the name before the others */
    }
    l->header_len -= sizeof NAME - 1;
    memmove(l->header + sizeof NAME - 1, l->header, l->header_len);
    memcpy(l->header, NAME, sizeof NAME - 1);
    l->header_len += sizeof NAME - 1;
    l->header[l->header_len] = '\0';
    return 0;
}

int sim_ulog_layout_build(const sim_ulog_formats_t *fs, const char *name, size_t name_len, sim_ulog_layout_t *l,
                          char *msg, size_t msg_len)
{
    memset(l, 0, sizeof *l);
    walk_t w;
    memset(&w, 0, sizeof w);
    w.fs = fs;
    w.l = l;
    w.ts_col = -1;
    w.msg = msg;
    w.msg_len = msg_len;
    const sim_ulog_format_t *f = find(fs, name, name_len);
    int rc;
    if (f == NULL) {
        rc = fail(msg, msg_len, "no format '%.*s'", name, name_len);
    } else if ((rc = walk(&w, f, 0)) == 0) {
        rc = timestamp_first(&w);
    }
    if (rc != 0) {
        sim_ulog_layout_free(l);
        return -1;
    }
    l->size_min = w.end_used;
    l->size_max = w.offset;
    l->row_max += 1;
    return 0;
}

void sim_ulog_layout_free(sim_ulog_layout_t *l)
{
    free(l->col);
    free(l->header);
    memset(l, 0, sizeof *l);
}
