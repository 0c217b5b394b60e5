/* SPDX-License-Identifier: BSD-3-Clause */
/* The ULog decoder (log/log_ulog.h) on logs written byte by byte here:
 * every field kind (each basic type, arrays, char text, nested types in an
 * array, padding in the middle and at the end, a 32-bit timestamp that
 * wraps), the CSVs' names and cells, the topics asked for, multi-instance
 * topics, dropouts, unknown messages, data of a wrong size, appended data,
 * a cut at every byte, corrupt headers with and without a sync message
 * after them, the located refusals (leaving no file), and the PX4 form end
 * to end through sim_log_open with the fallbacks of older releases. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "unity.h"
#include "log/log.h"
#include "log/log_px4.h"
#include "log/log_ulog.h"

#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ---- a ULog written by hand ---- */

typedef struct {
    unsigned char *b;
    size_t n, cap;
} bytes_t;

static void put(bytes_t *x, const void *p, size_t n)
{
    if (x->n + n > x->cap) {
        x->cap = (x->n + n) * 2 + 256;
        x->b = realloc(x->b, x->cap);
        TEST_ASSERT_NOT_NULL(x->b);
    }
    memcpy(x->b + x->n, p, n);
    x->n += n;
}

static void put_le(bytes_t *x, uint64_t v, int n)
{
    for (int i = 0; i < n; ++i) {
        const unsigned char c = (unsigned char)(i < 8 ? v >> (8 * i) : 0u);
        put(x, &c, 1);
    }
}

static void put_f32(bytes_t *x, float v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    put_le(x, u, 4);
}

static void put_f64(bytes_t *x, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    put_le(x, u, 8);
}

/* A message: its header, then the payload. Returns its offset. */
static size_t message(bytes_t *x, char type, const bytes_t *payload)
{
    const size_t at = x->n;
    put_le(x, payload->n, 2);
    put(x, &type, 1);
    put(x, payload->b, payload->n);
    return at;
}

static void ulog_header(bytes_t *x)
{
    static const unsigned char magic[8] = {'U', 'L', 'o', 'g', 0x01, 0x12, 0x35, 0x01};
    put(x, magic, sizeof magic);
    put_le(x, 123456789u, 8);
}

static size_t flag_bits(bytes_t *x, unsigned incompat0, unsigned incompat1, uint64_t appended)
{
    bytes_t p = {0};
    put_le(&p, 0, 8); /* compat */
    put_le(&p, incompat0, 1);
    put_le(&p, incompat1, 1);
    put_le(&p, 0, 6);
    put_le(&p, appended, 8);
    put_le(&p, 0, 16);
    const size_t at = message(x, 'B', &p);
    free(p.b);
    return at;
}

static size_t text_message(bytes_t *x, char type, const char *text)
{
    bytes_t p = {0};
    put(&p, text, strlen(text));
    const size_t at = message(x, type, &p);
    free(p.b);
    return at;
}

static size_t add_logged(bytes_t *x, int multi_id, int msg_id, const char *name)
{
    bytes_t p = {0};
    put_le(&p, (uint64_t)multi_id, 1);
    put_le(&p, (uint64_t)msg_id, 2);
    put(&p, name, strlen(name));
    const size_t at = message(x, 'A', &p);
    free(p.b);
    return at;
}

/* 'D' of msg_id with the data d. */
static size_t data(bytes_t *x, int msg_id, const bytes_t *d)
{
    bytes_t p = {0};
    put_le(&p, (uint64_t)msg_id, 2);
    put(&p, d->b, d->n);
    const size_t at = message(x, 'D', &p);
    free(p.b);
    return at;
}

static void dropout(bytes_t *x, unsigned ms)
{
    bytes_t p = {0};
    put_le(&p, ms, 2);
    message(x, 'O', &p);
    free(p.b);
}

static void sync_message(bytes_t *x)
{
    static const unsigned char magic[8] = {0x2F, 0x73, 0x13, 0x20, 0x25, 0x0C, 0xBB, 0x12};
    bytes_t p = {0};
    put(&p, magic, sizeof magic);
    message(x, 'S', &p);
    free(p.b);
}

/* One vehicle_angular_velocity row (the PX4 format below). */
static void gyro_row(bytes_t *x, int msg_id, uint64_t t_us, float a, float b, float c)
{
    bytes_t d = {0};
    put_le(&d, t_us, 8);
    put_le(&d, t_us - 100, 8);
    put_f32(&d, a);
    put_f32(&d, b);
    put_f32(&d, c);
    data(x, msg_id, &d);
    free(d.b);
}

static const char GYRO_FORMAT[] = "vehicle_angular_velocity:uint64_t timestamp;uint64_t timestamp_sample;float[3] xyz;";

/* ---- files ---- */

static char dir[64];
static char base[128];
static char in_path[160];

void setUp(void)
{
    snprintf(dir, sizeof dir, "log_ulog_XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    snprintf(base, sizeof base, "%s/flight", dir);
    snprintf(in_path, sizeof in_path, "%s/flight.ulg", dir);
}

void tearDown(void)
{
    DIR *d = opendir(dir);
    if (d != NULL) {
        const struct dirent *e;
        char p[400];
        while ((e = readdir(d)) != NULL) {
            if (e->d_name[0] != '.') {
                snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
                remove(p);
            }
        }
        closedir(d);
    }
    rmdir(dir);
}

static void write_file(const char *path, const unsigned char *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_TRUE(fwrite(b, 1, n, f) == n);
    fclose(f);
}

/* The files in dir but the log itself. */
static int csv_files(void)
{
    DIR *d = opendir(dir);
    TEST_ASSERT_NOT_NULL(d);
    int n = 0;
    const struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        n += strstr(e->d_name, ".csv") != NULL;
    }
    closedir(d);
    return n;
}

/* The whole text of base_<suffix>; NULL when there is no such file. */
static char *read_csv(const char *suffix)
{
    char p[300];
    snprintf(p, sizeof p, "%s_%s", base, suffix);
    FILE *f = fopen(p, "rb");
    if (f == NULL) {
        return NULL;
    }
    static char text[1 << 16];
    const size_t n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    fclose(f);
    return text;
}

static int decode(const bytes_t *x, const char *const *topics, int n_topics, sim_log_ulog_stats_t *st,
                  sim_log_error_t *err)
{
    write_file(in_path, x->b, x->n);
    return sim_log_ulog_to_csv_stats(in_path, base, topics, n_topics, NULL, NULL, st, err);
}

static void expect_refusal(const bytes_t *x, long long offset, const char *needle)
{
    sim_log_ulog_stats_t st;
    sim_log_error_t err;
    char want[64], shown[600];
    TEST_ASSERT_EQUAL_INT(-1, decode(x, NULL, 0, &st, &err));
    sim_log_error_format(&err, shown, sizeof shown);
    snprintf(want, sizeof want, "offset %lld: ", offset);
    TEST_ASSERT_EQUAL_STRING_MESSAGE(in_path, err.path, shown);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, err.line, shown);
    TEST_ASSERT_TRUE_MESSAGE(strncmp(err.message, want, strlen(want)) == 0, shown);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, needle), shown);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, csv_files(), "a refusal leaves no file");
}

/* ---- every field kind ---- */

/* A topic of every basic type, a nested type in an array, padding in the
 * middle (its bytes skipped) and at the end (not logged), two instances. */
static void kinds_log(bytes_t *x)
{
    ulog_header(x);
    flag_bits(x, 0, 0, 0);
    text_message(x, 'I',
                 "\x0f"
                 "char[3] sys_namePX4");
    text_message(x, 'F',
                 "kinds:uint64_t timestamp;int8_t i8;uint8_t u8;int16_t i16;uint16_t u16;int32_t i32;"
                 "uint32_t u32;int64_t i64;uint64_t u64;float f;double d;bool ok;char c;char[6] name;"
                 "uint8_t[2] _padding0;float[2] v;uint8_t[3] _padding1;");
    text_message(x, 'F', "esc_report:int32_t esc_rpm;float esc_voltage;");
    text_message(x, 'F', "esc_status:uint64_t timestamp;uint8_t esc_count;esc_report[2] esc;");
    text_message(x, 'P',
                 "\x0b"
                 "float PARAMA\x00\x00\x80\x3f");
    add_logged(x, 0, 0, "kinds");
    add_logged(x, 0, 1, "esc_status");
    add_logged(x, 1, 2, "esc_status");
    bytes_t d = {0};
    put_le(&d, 1000, 8);
    put_le(&d, (uint8_t)-128, 1);
    put_le(&d, 255, 1);
    put_le(&d, (uint16_t)-32768, 2);
    put_le(&d, 65535, 2);
    put_le(&d, (uint32_t)INT32_MIN, 4);
    put_le(&d, UINT32_MAX, 4);
    put_le(&d, (uint64_t)INT64_MIN, 8);
    put_le(&d, UINT64_MAX, 8);
    put_f32(&d, 0.1f);
    put_f64(&d, 0.1);
    put_le(&d, 1, 1);
    put_le(&d, 'A', 1);
    put(&d, "a,b\n\0z", 6); /* text to its NUL, the comma and the line end written '?' */
    put_le(&d, 0xEEEE, 2);  /* padding */
    put_f32(&d, -2.5e-7f);
    put_f32(&d, NAN);
    /* the trailing padding is not logged */
    data(x, 0, &d);
    d.n = 0;
    put_le(&d, 2000, 8);
    put_le(&d, 0, 1);
    put_le(&d, 0, 1);
    put_le(&d, 0, 2);
    put_le(&d, 0, 2);
    put_le(&d, 0, 4);
    put_le(&d, 0, 4);
    put_le(&d, 0, 8);
    put_le(&d, 0, 8);
    put_f32(&d, INFINITY);
    put_f64(&d, -1.0 / 3.0);
    put_le(&d, 0, 1);
    put_le(&d, 0, 1);
    put(&d, "abcdef", 6); /* no NUL: all six */
    put_le(&d, 0, 2);
    put_f32(&d, 3.0f);
    put_f32(&d, 16777216.0f);
    put_le(&d, 0, 3); /* the trailing padding, logged this time: accepted */
    data(x, 0, &d);
    for (int id = 1; id <= 2; ++id) {
        d.n = 0;
        put_le(&d, 5000, 8);
        put_le(&d, 2, 1);
        put_le(&d, (uint32_t)(1000 * id), 4);
        put_f32(&d, 12.5f);
        put_le(&d, (uint32_t)-7, 4);
        put_f32(&d, 0.5f);
        data(x, id, &d);
    }
    free(d.b);
}

static void test_every_field_kind(void)
{
    bytes_t x = {0};
    kinds_log(&x);
    sim_log_ulog_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, decode(&x, NULL, 0, &st, &err), err.message);
    TEST_ASSERT_EQUAL_INT(3, st.files);
    TEST_ASSERT_TRUE(st.rows == 4 && st.subscribed == 3 && st.end == SIM_LOG_ULOG_END_WHOLE && st.version == 1);
    TEST_ASSERT_EQUAL_STRING(
        "timestamp,i8,u8,i16,u16,i32,u32,i64,u64,f,d,ok,c,name,v[0],v[1]\n"
        "1000,-128,255,-32768,65535,-2147483648,4294967295,-9223372036854775808,18446744073709551615,0.100000001,"
        "0.10000000000000001,1,65,a?b?,-2.49999999e-07,nan\n"
        "2000,0,0,0,0,0,0,0,0,inf,-0.33333333333333331,0,0,abcdef,3,16777216\n",
        read_csv("kinds_0.csv"));
    TEST_ASSERT_EQUAL_STRING("timestamp,esc_count,esc[0].esc_rpm,esc[0].esc_voltage,esc[1].esc_rpm,esc[1].esc_voltage\n"
                             "5000,2,1000,12.5,-7,0.5\n",
                             read_csv("esc_status_0.csv"));
    TEST_ASSERT_EQUAL_STRING("timestamp,esc_count,esc[0].esc_rpm,esc[0].esc_voltage,esc[1].esc_rpm,esc[1].esc_voltage\n"
                             "5000,2,2000,12.5,-7,0.5\n",
                             read_csv("esc_status_1.csv"));
    char notes[200];
    TEST_ASSERT_EQUAL_INT(0, sim_log_ulog_stats_describe(&st, notes, sizeof notes));
    TEST_ASSERT_EQUAL_STRING("", notes);
    free(x.b);
}

static void note_progress(void *ctx, long long done, long long total)
{
    long long *seen = ctx;
    TEST_ASSERT_TRUE(done >= seen[0] && done <= total); /* never back, never past the end */
    seen[0] = done;
    seen[1] = total;
}

/* Only the topics asked for; one subscribed but never logged has no file;
 * a '/' in a topic's name is no folder. */
static void test_the_topics_asked_for(void)
{
    bytes_t x = {0};
    ulog_header(&x);
    text_message(&x, 'F', GYRO_FORMAT);
    text_message(&x, 'F', "a/b:uint64_t timestamp;float v;");
    text_message(&x, 'F', "unlogged:uint64_t timestamp;float v;");
    add_logged(&x, 0, 3, "vehicle_angular_velocity");
    add_logged(&x, 0, 4, "a/b");
    add_logged(&x, 0, 9, "unlogged");
    for (int k = 0; k < 5; ++k) {
        gyro_row(&x, 3, 1000u * (unsigned)(k + 1), (float)k, 0.0f, 0.0f);
        bytes_t d = {0};
        put_le(&d, 1000u * (unsigned)(k + 1), 8);
        put_f32(&d, 1.0f);
        data(&x, 4, &d);
        free(d.b);
    }
    const char *const topics[] = {"a/b", "unlogged"};
    sim_log_ulog_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, decode(&x, topics, 2, &st, &err), err.message);
    TEST_ASSERT_EQUAL_INT(1, csv_files());
    TEST_ASSERT_NOT_NULL(read_csv("a_b_0.csv"));
    TEST_ASSERT_TRUE(st.rows == 5 && st.files == 1 && st.data_no_subscription == 0);
    long long seen[2] = {-1, -1}; /* the last progress: done, total */
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_ulog_to_csv(in_path, base, NULL, 0, note_progress, seen, &err),
                                  err.message);
    TEST_ASSERT_TRUE(seen[0] == (long long)x.n && seen[1] == (long long)x.n); /* the whole log, its size known */
    TEST_ASSERT_EQUAL_INT(2, csv_files());
    TEST_ASSERT_EQUAL_STRING("timestamp,timestamp_sample,xyz[0],xyz[1],xyz[2]\n"
                             "1000,900,0,0,0\n2000,1900,1,0,0\n3000,2900,2,0,0\n4000,3900,3,0,0\n5000,4900,4,0,0\n",
                             read_csv("vehicle_angular_velocity_0.csv"));
    free(x.b);
}

/* Counted, not refused: dropouts, unknown messages, data of a wrong size
 * or of no subscription, rows whose time does not increase, a removed
 * subscription; a 32-bit timestamp unwrapped. */
static void test_what_is_counted(void)
{
    bytes_t x = {0};
    ulog_header(&x);
    text_message(&x, 'F', GYRO_FORMAT);
    text_message(&x, 'F', "narrow:uint32_t timestamp;int16_t v;");
    add_logged(&x, 0, 0, "vehicle_angular_velocity");
    add_logged(&x, 0, 1, "narrow");
    gyro_row(&x, 0, 1000, 1.0f, 2.0f, 3.0f);
    dropout(&x, 40);
    text_message(&x, 'Z', "a message of a type to come");
    text_message(&x, 'L',
                 "\x06"
                 "12345678logged text");
    sync_message(&x);
    dropout(&x, 15);
    bytes_t d = {0};
    put_le(&d, 2000, 8);
    put_le(&d, 0, 8);
    put_f32(&d, 1.0f); /* two floats short of its format */
    data(&x, 0, &d);
    data(&x, 7, &d);                         /* no subscription */
    gyro_row(&x, 0, 1000, 9.0f, 9.0f, 9.0f); /* not after the last row */
    gyro_row(&x, 0, 3000, 4.0f, 5.0f, 6.0f);
    const uint32_t narrow[] = {4294967000u, 4294967295u, 200u, 300u}; /* wraps after the second */
    for (int k = 0; k < 4; ++k) {
        d.n = 0;
        put_le(&d, narrow[k], 4);
        put_le(&d, (uint16_t)(-k), 2);
        data(&x, 1, &d);
    }
    bytes_t r = {0};
    put_le(&r, 0, 2);
    message(&x, 'R', &r); /* vehicle_angular_velocity no longer logged */
    gyro_row(&x, 0, 4000, 7.0f, 8.0f, 9.0f);
    sim_log_ulog_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, decode(&x, NULL, 0, &st, &err), err.message);
    TEST_ASSERT_TRUE(st.dropouts == 2 && st.dropout_ms == 55 && st.unknown == 1);
    TEST_ASSERT_TRUE(st.data_bad_size == 1 && st.data_no_subscription == 2 && st.out_of_order == 1);
    TEST_ASSERT_EQUAL_STRING("timestamp,timestamp_sample,xyz[0],xyz[1],xyz[2]\n1000,900,1,2,3\n3000,2900,4,5,6\n",
                             read_csv("vehicle_angular_velocity_0.csv"));
    TEST_ASSERT_EQUAL_STRING("timestamp,v\n4294967000,0\n4294967295,-1\n4294967496,-2\n4294967596,-3\n",
                             read_csv("narrow_0.csv"));
    char notes[600];
    TEST_ASSERT_EQUAL_INT(4, sim_log_ulog_stats_describe(&st, notes, sizeof notes));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(notes, "2 dropouts (55 ms lost)"), notes);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(notes, "3 data messages skipped"), notes);
    free(d.b);
    free(r.b);
    free(x.b);
}

/* ---- cuts, appended data, corruption ---- */

/* A log of n gyro rows; the offsets where each row's message ends. */
static void rows_log(bytes_t *x, int n, size_t *row_end)
{
    ulog_header(x);
    flag_bits(x, 0, 0, 0);
    text_message(x, 'F', GYRO_FORMAT);
    add_logged(x, 0, 0, "vehicle_angular_velocity");
    for (int k = 0; k < n; ++k) {
        gyro_row(x, 0, 1000u * (unsigned)(k + 1), (float)k, 0.5f, -0.5f);
        row_end[k] = x->n;
    }
}

static int count_lines(const char *text)
{
    int n = 0;
    for (const char *p = text; *p != '\0'; ++p) {
        n += *p == '\n';
    }
    return n;
}

/* Cut at every byte: refused inside the header, else decoded up to the
 * last whole message, the cut told when it falls inside one. */
static void test_a_cut_at_every_byte(void)
{
    enum { ROWS = 6 };
    bytes_t x = {0};
    size_t row_end[ROWS];
    rows_log(&x, ROWS, row_end);
    const size_t first_row = row_end[0] - (row_end[1] - row_end[0]);
    for (size_t cut = 0; cut <= x.n; ++cut) {
        sim_log_ulog_stats_t st;
        sim_log_error_t err;
        write_file(in_path, x.b, cut);
        const int rc = sim_log_ulog_to_csv_stats(in_path, base, NULL, 0, NULL, NULL, &st, &err);
        char what[80];
        snprintf(what, sizeof what, "cut at %zu of %zu", cut, x.n);
        if (cut < 16) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(-1, rc, what);
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, "offset 0: "), what);
            continue;
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, err.message);
        int whole = 0;
        while (whole < ROWS && row_end[whole] <= cut) {
            ++whole;
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(whole, (int)st.rows, what);
        const char *csv = read_csv("vehicle_angular_velocity_0.csv");
        TEST_ASSERT_EQUAL_INT_MESSAGE(whole > 0, csv != NULL, what);
        if (csv != NULL) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(whole + 1, count_lines(csv), what);
            char p[300];
            snprintf(p, sizeof p, "%s_vehicle_angular_velocity_0.csv", base);
            remove(p);
        }
        const int at_boundary = cut == x.n || (cut >= first_row && (cut - first_row) % (row_end[1] - row_end[0]) == 0);
        if (cut >= first_row) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(at_boundary ? SIM_LOG_ULOG_END_WHOLE : SIM_LOG_ULOG_END_CUT, st.end, what);
        }
        if (st.end == SIM_LOG_ULOG_END_CUT) {
            const size_t last_whole = whole > 0 ? row_end[whole - 1] : 0;
            TEST_ASSERT_TRUE_MESSAGE(last_whole == 0 || st.end_offset == (long long)last_whole, what);
        }
    }
    free(x.b);
}

/* Appended data: the message it cuts is dropped, the rows after it read. */
static void test_appended_data(void)
{
    bytes_t x = {0};
    ulog_header(&x);
    const size_t flags = flag_bits(&x, 1, 0, 0);
    text_message(&x, 'F', GYRO_FORMAT);
    add_logged(&x, 0, 0, "vehicle_angular_velocity");
    for (int k = 1; k <= 3; ++k) {
        gyro_row(&x, 0, 1000u * (unsigned)k, (float)k, 0.0f, 0.0f);
    }
    const size_t before = x.n;
    gyro_row(&x, 0, 3500, 99.0f, 99.0f, 99.0f);
    x.n = before + 10; /* the log stopped inside this row */
    const uint64_t appended = x.n;
    for (int i = 0; i < 8; ++i) {
        x.b[flags + 3 + 16 + (size_t)i] = (unsigned char)(appended >> (8 * i));
    }
    gyro_row(&x, 0, 4000, 4.0f, 0.0f, 0.0f);
    gyro_row(&x, 0, 5000, 5.0f, 0.0f, 0.0f);
    sim_log_ulog_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, decode(&x, NULL, 0, &st, &err), err.message);
    TEST_ASSERT_TRUE(st.rows == 5 && st.appended == 1 && st.appended_cut_bytes == 10);
    TEST_ASSERT_EQUAL_INT(SIM_LOG_ULOG_END_WHOLE, st.end);
    TEST_ASSERT_EQUAL_STRING("timestamp,timestamp_sample,xyz[0],xyz[1],xyz[2]\n1000,900,1,0,0\n2000,1900,2,0,0\n"
                             "3000,2900,3,0,0\n4000,3900,4,0,0\n5000,4900,5,0,0\n",
                             read_csv("vehicle_angular_velocity_0.csv"));
    free(x.b);
}

/* A corrupt header (type and size 0): decoding resumes after the next sync
 * message, or ends there when none follows. */
static void test_a_corrupt_header(void)
{
    for (int with_sync = 0; with_sync <= 1; ++with_sync) {
        bytes_t x = {0};
        ulog_header(&x);
        text_message(&x, 'F', GYRO_FORMAT);
        add_logged(&x, 0, 0, "vehicle_angular_velocity");
        gyro_row(&x, 0, 1000, 1.0f, 0.0f, 0.0f);
        gyro_row(&x, 0, 2000, 2.0f, 0.0f, 0.0f);
        const size_t corrupt = x.n;
        static const unsigned char garbage[12] = {0, 0, 0, 7, 7, 7, 7, 7, 7, 7, 7, 7};
        put(&x, garbage, sizeof garbage);
        if (with_sync) {
            sync_message(&x);
        }
        gyro_row(&x, 0, 3000, 3.0f, 0.0f, 0.0f);
        sim_log_ulog_stats_t st;
        sim_log_error_t err;
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, decode(&x, NULL, 0, &st, &err), err.message);
        char notes[400];
        sim_log_ulog_stats_describe(&st, notes, sizeof notes);
        if (with_sync) {
            TEST_ASSERT_TRUE(st.rows == 3 && st.resyncs == 1 && st.end == SIM_LOG_ULOG_END_WHOLE);
            TEST_ASSERT_EQUAL_INT(sizeof garbage + 11, (int)st.resync_bytes); /* + the sync message */
        } else {
            TEST_ASSERT_TRUE(st.rows == 2 && st.end == SIM_LOG_ULOG_END_CORRUPT);
            TEST_ASSERT_EQUAL_INT((int)corrupt, (int)st.end_offset);
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(notes, "no sync message after it"), notes);
        }
        free(x.b);
        tearDown();
        setUp();
    }
}

/* ---- refusals, located at the message's offset ---- */

/* A log whose definitions end with `format` and subscribe to `topic`,
 * one row logged before: the offset of the 'A'. */
static size_t bad_topic_log(bytes_t *x, const char *format, const char *topic)
{
    ulog_header(x);
    text_message(x, 'F', GYRO_FORMAT);
    text_message(x, 'F', format);
    add_logged(x, 0, 0, "vehicle_angular_velocity");
    gyro_row(x, 0, 1000, 1.0f, 0.0f, 0.0f); /* a file made before the refusal */
    return add_logged(x, 0, 1, topic);
}

static void test_refusals(void)
{
    static const struct {
        const char *format, *topic, *needle;
    } BAD[] = {
        {"t:uint64_t timestamp;float v;", "ghost", "topic 'ghost': no format 'ghost'"},
        {"t:uint64_t timestamp;missing_t m;", "t", "topic 't': no format of the type 'missing_t'"},
        {"t:uint64_t timestamp;t inner;", "t", "nested deeper than 32"},
        {"t:float v;", "t", "no field 'timestamp' of an unsigned integer type"},
        {"t:float timestamp;", "t", "no field 'timestamp' of an unsigned integer type"},
        {"t:uint64_t timestamp;float[0] v;", "t", "field 'float[0] v': bad array length"},
        {"t:uint64_t timestamp;float[3 v;", "t", "bad array length"},
        {"t:uint64_t timestamp;floatv;", "t", "field 'floatv': not 'type name'"},
        {"t:uint64_t timestamp;double[9000] v;", "t", "larger than a data message's 65533 bytes"},
        {"t:", "t", "format 't' has no fields"},
    };
    for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; ++i) {
        bytes_t x = {0};
        const size_t at = bad_topic_log(&x, BAD[i].format, BAD[i].topic);
        expect_refusal(&x, (long long)at, BAD[i].needle);
        /* a topic not asked for is never looked at */
        const char *const gyro[] = {"vehicle_angular_velocity"};
        sim_log_ulog_stats_t st;
        sim_log_error_t err;
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, decode(&x, gyro, 1, &st, &err), err.message);
        TEST_ASSERT_EQUAL_INT(1, (int)st.rows);
        free(x.b);
        tearDown();
        setUp();
    }
}

static void test_refused_messages(void)
{
    bytes_t x = {0};
    static const unsigned char not_ulog[20] = "ULog but not quite";
    put(&x, not_ulog, sizeof not_ulog);
    expect_refusal(&x, 0, "not a ULog");
    x.n = 0;
    ulog_header(&x);
    const size_t flags = flag_bits(&x, 0, 4, 0);
    expect_refusal(&x, (long long)flags, "incompatible flags");
    x.n = 0;
    ulog_header(&x);
    flag_bits(&x, 2, 0, 0);
    expect_refusal(&x, (long long)flags, "incompatible flags");
    x.n = 0;
    ulog_header(&x);
    const size_t colon = text_message(&x, 'F', "no colon here");
    expect_refusal(&x, (long long)colon, "no 'name:' before its fields");
    /* messages too short for their own fields, after a row was written */
    static const struct {
        char type;
        size_t size;
        const char *needle;
    } SHORT[] = {{'A', 3, "'A' message of 3 bytes"},
                 {'D', 1, "'D' message of 1 bytes: its msg_id takes 2"},
                 {'R', 1, "'R' message shorter than its msg_id"},
                 {'O', 1, "'O' message shorter than its duration"}};
    for (size_t i = 0; i < sizeof SHORT / sizeof SHORT[0]; ++i) {
        x.n = 0;
        ulog_header(&x);
        text_message(&x, 'F', GYRO_FORMAT);
        add_logged(&x, 0, 0, "vehicle_angular_velocity");
        gyro_row(&x, 0, 1000, 1.0f, 0.0f, 0.0f);
        bytes_t p = {0};
        put_le(&p, 0, SHORT[i].size);
        const size_t at = message(&x, SHORT[i].type, &p);
        free(p.b);
        gyro_row(&x, 0, 2000, 2.0f, 0.0f, 0.0f);
        expect_refusal(&x, (long long)at, SHORT[i].needle);
    }
    free(x.b);
}

/* ---- the PX4 form end to end ---- */

#define PX4_ROWS 400
#define PX4_T0_US 2000000u

static float gyro_value(int axis, int k)
{
    return (float)sin(0.01 * k + axis);
}

static float control_value(int axis, int k)
{
    return 0.2f * (float)cos(0.02 * k + axis);
}

/* A PX4 log at 1 kHz: the gyro, the attitude (a turn about x), the torque
 * as vehicle_torque_setpoint (twice actuator_controls_0's) and/or
 * actuator_controls_0, and actuator_outputs. */
static void px4_log(bytes_t *x, int with_torque, int with_controls)
{
    ulog_header(x);
    flag_bits(x, 0, 0, 0);
    text_message(x, 'F', GYRO_FORMAT);
    text_message(x, 'F', "vehicle_attitude:uint64_t timestamp;uint64_t timestamp_sample;float[4] q;");
    text_message(x, 'F',
                 "vehicle_torque_setpoint:uint64_t timestamp;uint64_t timestamp_sample;float[3] xyz;"
                 "uint8_t[4] _padding0;");
    text_message(x, 'F', "actuator_controls_0:uint64_t timestamp;uint64_t timestamp_sample;float[8] control;");
    text_message(x, 'F',
                 "actuator_outputs:uint64_t timestamp;uint32_t noutputs;float[16] output;uint8_t[4] _padding0;");
    add_logged(x, 0, 0, "vehicle_angular_velocity");
    add_logged(x, 0, 1, "vehicle_attitude");
    add_logged(x, 0, 2, "vehicle_torque_setpoint");
    add_logged(x, 0, 3, "actuator_controls_0");
    add_logged(x, 0, 4, "actuator_outputs");
    bytes_t d = {0};
    for (int k = 0; k < PX4_ROWS; ++k) {
        const uint64_t t = PX4_T0_US + 1000u * (unsigned)k;
        gyro_row(x, 0, t, gyro_value(0, k), gyro_value(1, k), gyro_value(2, k));
        d.n = 0;
        put_le(&d, t, 8);
        put_le(&d, t, 8);
        put_f32(&d, (float)cos(0.001 * k));
        put_f32(&d, (float)sin(0.001 * k));
        put_f32(&d, 0.0f);
        put_f32(&d, 0.0f);
        data(x, 1, &d);
        if (with_torque) {
            d.n = 0;
            put_le(&d, t, 8);
            put_le(&d, t, 8);
            for (int i = 0; i < 3; ++i) {
                put_f32(&d, 2.0f * control_value(i, k));
            }
            data(x, 2, &d);
        }
        if (with_controls) {
            d.n = 0;
            put_le(&d, t, 8);
            put_le(&d, t, 8);
            for (int i = 0; i < 8; ++i) {
                put_f32(&d, control_value(i, k));
            }
            data(x, 3, &d);
        }
        d.n = 0;
        put_le(&d, t, 8);
        put_le(&d, 4, 4);
        for (int q = 0; q < 16; ++q) {
            put_f32(&d, q < 4 ? 1500.0f + (float)(q * 10 + k) : 900.0f);
        }
        data(x, 4, &d);
    }
    free(d.b);
}

/* A float written to 9 digits and read back as a double: within half a
 * float's ulp, 2^-24 of its size (6e-8), taken as 1e-7. */
static void assert_float_text(float want, double got)
{
    char msg[120];
    snprintf(msg, sizeof msg, "want %.9g, got %.17g", (double)want, got);
    TEST_ASSERT_TRUE_MESSAGE(fabs(got - (double)want) <= 1e-7 * fabs((double)want) + 1e-30, msg);
}

static sim_log_t *open_px4(const char *path, sim_log_error_t *err)
{
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = SIM_LOG_PX4;
    snprintf(o.path, sizeof o.path, "%s", path);
    return sim_log_open(&o, err);
}

static void decode_px4(const bytes_t *x)
{
    sim_log_px4_topics_t topics;
    char msg[200];
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_px4_topics(NULL, 0, &topics, msg, sizeof msg), msg);
    sim_log_ulog_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, decode(x, topics.list, topics.n, &st, &err), err.message);
}

static void check_px4_ticks(int torque_scale)
{
    sim_log_error_t err;
    sim_log_t *log = open_px4(in_path, &err); /* the .ulg's name: its files' base */
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    TEST_ASSERT_EQUAL_UINT(SIM_LOG_HAS_GYRO | SIM_LOG_HAS_ANGLE | SIM_LOG_HAS_COMMAND | SIM_LOG_HAS_MOTOR,
                           sim_log_has(log));
    sim_log_sample_t s;
    int k = 0;
    while (sim_log_next(log, &s, &err) == 1) {
        for (int i = 0; i < 3; ++i) {
            assert_float_text(gyro_value(i, k), s.gyro_rad_s[i]);
            assert_float_text((float)torque_scale * control_value(i, k), s.command[i]);
        }
        TEST_ASSERT_EQUAL_INT(SIM_LOG_MAX_MOTORS, s.n_motors); /* actuator_outputs: all 8 mapped */
        assert_float_text(1500.0f + (float)k, s.motor[0]);
        assert_float_text(900.0f, s.motor[7]);
        /* the angle from the quaternion (cos 0.001k, sin 0.001k): 0.002k, to its floats' rounding */
        TEST_ASSERT_TRUE(fabs(s.angle_rad[0] - 0.002 * k) <= 1e-6);
        ++k;
    }
    TEST_ASSERT_EQUAL_INT(PX4_ROWS, k);
    sim_log_close(log);
}

/* Before v1.13: actuator_controls_0 and actuator_outputs, told from the
 * topics the log has. */
static void test_px4_before_v1_13(void)
{
    bytes_t x = {0};
    px4_log(&x, 0, 1);
    decode_px4(&x);
    check_px4_ticks(1);
    free(x.b);
}

/* Both: vehicle_torque_setpoint, the newer, is read. */
static void test_px4_torque_setpoint_first(void)
{
    bytes_t x = {0};
    px4_log(&x, 1, 1);
    decode_px4(&x);
    check_px4_ticks(2);
    free(x.b);
}

/* Neither: refused naming the field and both topics. */
static void test_px4_without_a_command(void)
{
    bytes_t x = {0};
    px4_log(&x, 0, 0);
    decode_px4(&x);
    sim_log_error_t err;
    TEST_ASSERT_NULL(open_px4(in_path, &err));
    char shown[600];
    sim_log_error_format(&err, shown, sizeof shown);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, "topic vehicle_torque_setpoint, needed for command[0]; nor is "
                                                     "there a file of actuator_controls_0"),
                                 shown);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.path, "_vehicle_torque_setpoint_0.csv"), shown);
    free(x.b);
}

/* The formats of PX4 v1.15 (as its logger writes them; nested esc_report,
 * padding in the middle and at the ends), every topic of the preset at
 * 1 kHz: the setpoints, the throttle, the motors and the rotor speeds. */
static void v1_15_log(bytes_t *x)
{
    ulog_header(x);
    flag_bits(x, 0, 0, 0);
    text_message(x, 'F', GYRO_FORMAT);
    text_message(x, 'F',
                 "vehicle_attitude:uint64_t timestamp;uint64_t timestamp_sample;float[4] q;"
                 "float[4] delta_q_reset;uint8_t quat_reset_counter;uint8_t[7] _padding0;");
    text_message(x, 'F',
                 "vehicle_torque_setpoint:uint64_t timestamp;uint64_t timestamp_sample;float[3] xyz;"
                 "uint8_t[4] _padding0;");
    text_message(x, 'F',
                 "vehicle_rates_setpoint:uint64_t timestamp;float roll;float pitch;float yaw;"
                 "float[3] thrust_body;bool reset_integral;uint8_t[7] _padding0;");
    text_message(x, 'F',
                 "vehicle_attitude_setpoint:uint64_t timestamp;float roll_body;float pitch_body;"
                 "float yaw_body;float yaw_sp_move_rate;float[4] q_d;float[3] thrust_body;bool reset_integral;"
                 "bool fw_control_yaw_wheel;uint8_t[2] _padding0;");
    text_message(x, 'F',
                 "actuator_motors:uint64_t timestamp;uint64_t timestamp_sample;float[12] control;"
                 "uint16_t reversible_flags;uint8_t[6] _padding0;");
    text_message(x, 'F',
                 "esc_report:uint64_t timestamp;uint32_t esc_errorcount;int32_t esc_rpm;float esc_voltage;"
                 "float esc_current;float esc_temperature;uint16_t failures;uint8_t esc_address;"
                 "uint8_t esc_cmdcount;uint8_t esc_state;uint8_t actuator_function;int8_t esc_power;"
                 "uint8_t[5] _padding0;");
    text_message(x, 'F',
                 "esc_status:uint64_t timestamp;uint16_t counter;uint8_t esc_count;"
                 "uint8_t esc_connectiontype;uint8_t esc_online_flags;uint8_t esc_armed_flags;"
                 "uint8_t[2] _padding0;esc_report[8] esc;");
    static const char *const NAMES[] = {"vehicle_angular_velocity", "vehicle_attitude", "vehicle_torque_setpoint",
                                        "vehicle_rates_setpoint",   "actuator_motors",  "esc_status",
                                        "vehicle_attitude_setpoint"};
    for (int i = 0; i < 7; ++i) {
        add_logged(x, 0, i, NAMES[i]);
    }
    bytes_t d = {0};
    for (int k = 0; k < PX4_ROWS; ++k) {
        const uint64_t t = PX4_T0_US + 1000u * (unsigned)k;
        gyro_row(x, 0, t, gyro_value(0, k), gyro_value(1, k), gyro_value(2, k));
        d.n = 0;
        put_le(&d, t, 8);
        put_le(&d, t, 8);
        put_f32(&d, 1.0f);
        put_le(&d, 0, 12);
        put_le(&d, 0, 17); /* delta_q_reset, the counter; the trailing padding not logged */
        data(x, 1, &d);
        d.n = 0;
        put_le(&d, t, 8);
        put_le(&d, t, 8);
        for (int i = 0; i < 3; ++i) {
            put_f32(&d, control_value(i, k));
        }
        data(x, 2, &d);
        d.n = 0;
        put_le(&d, t, 8);
        for (int i = 0; i < 3; ++i) {
            put_f32(&d, 3.0f * control_value(i, k)); /* roll, pitch, yaw rates */
        }
        put_le(&d, 0, 13); /* thrust_body, reset_integral */
        data(x, 3, &d);
        d.n = 0;
        put_le(&d, t, 8);
        put_le(&d, t, 8);
        for (int q = 0; q < 12; ++q) {
            put_f32(&d, q < 4 ? 0.5f + 0.01f * (float)q : NAN); /* four motors: nan for the others */
        }
        put_le(&d, 0, 2);
        data(x, 4, &d);
        d.n = 0;
        put_le(&d, t, 8);
        put_le(&d, (uint64_t)k, 2);
        put_le(&d, 4, 1);
        put_le(&d, 0, 5);
        for (int q = 0; q < 8; ++q) {
            put_le(&d, t, 8);
            put_le(&d, 0, 4);
            put_le(&d, (uint32_t)(6000 + 600 * q + k), 4); /* rpm */
            put_f32(&d, 16.0f);
            put_le(&d, 0, 20);
        }
        data(x, 5, &d);
        d.n = 0;
        put_le(&d, t, 8);
        put_le(&d, 0, 16);
        put_f32(&d, (float)cos(0.001 * k)); /* q_d: a turn about y */
        put_f32(&d, 0.0f);
        put_f32(&d, (float)sin(0.001 * k));
        put_f32(&d, 0.0f);
        put_f32(&d, 0.0f);
        put_f32(&d, 0.0f);
        put_f32(&d, -0.25f - 0.001f * (float)k); /* thrust along -z */
        put_le(&d, 0, 2);
        data(x, 6, &d);
    }
    free(d.b);
}

/* The preset's column names on PX4 v1.15's formats: the setpoints, the
 * throttle, the motors and esc[i].esc_rpm through the nested array. */
static void test_px4_v1_15_formats(void)
{
    bytes_t x = {0};
    v1_15_log(&x);
    decode_px4(&x);
    sim_log_error_t err;
    sim_log_t *log = open_px4(in_path, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    TEST_ASSERT_EQUAL_UINT(SIM_LOG_HAS_GYRO | SIM_LOG_HAS_ANGLE | SIM_LOG_HAS_COMMAND | SIM_LOG_HAS_REF_ANGLE |
                               SIM_LOG_HAS_REF_RATE | SIM_LOG_HAS_THROTTLE | SIM_LOG_HAS_MOTOR | SIM_LOG_HAS_ROTOR_HZ,
                           sim_log_has(log));
    sim_log_sample_t s;
    int k = 0;
    while (sim_log_next(log, &s, &err) == 1) {
        for (int i = 0; i < 3; ++i) {
            assert_float_text(control_value(i, k), s.command[i]);
            assert_float_text(3.0f * control_value(i, k), s.ref_rate_rad_s[i]);
        }
        assert_float_text(0.25f + 0.001f * (float)k, s.throttle);
        TEST_ASSERT_TRUE(fabs(s.ref_angle_rad[1] - 0.002 * k) <= 1e-6); /* to the floats' rounding */
        TEST_ASSERT_EQUAL_INT(SIM_LOG_MAX_MOTORS, s.n_motors);          /* the rotor speeds of all eight */
        for (int q = 0; q < SIM_LOG_MAX_MOTORS; ++q) {
            /* the preset's 1/60 is written 0.0166666667: 2e-9 relative */
            TEST_ASSERT_TRUE(fabs(s.rotor_hz[q] - (6000.0 + 600.0 * q + k) / 60.0) <= 3e-9 * s.rotor_hz[q]);
            TEST_ASSERT_TRUE(q < 4 ? fabs(s.motor[q] - (0.5 + 0.01 * q)) <= 1e-7 : isnan(s.motor[q]));
        }
        ++k;
    }
    TEST_ASSERT_EQUAL_INT(PX4_ROWS, k);
    sim_log_close(log);
    free(x.b);
}

/* The topics a decoder is asked for: the preset's, their fallbacks, the
 * caller's; a caller's item drops the fallback of its field. */
static void test_px4_topics(void)
{
    sim_log_px4_topics_t t;
    char msg[200];
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_px4_topics(NULL, 0, &t, msg, sizeof msg), msg);
    static const char *const WANT[] = {
        "vehicle_angular_velocity", "sensor_combined",         "vehicle_attitude", "vehicle_attitude_setpoint",
        "vehicle_rates_setpoint",   "vehicle_torque_setpoint", "actuator_motors",  "esc_status",
        "actuator_controls_0",      "actuator_outputs"};
    TEST_ASSERT_EQUAL_INT(10, t.n);
    for (int i = 0; i < 10; ++i) {
        TEST_ASSERT_EQUAL_STRING(WANT[i], t.list[i]);
    }
    const char *const items[] = {"command[0]=my_topic.u", "command[1]=my_topic.v", "command[2]=my_topic.w"};
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_px4_topics(items, 3, &t, msg, sizeof msg), msg);
    int mine = 0, controls = 0, torque = 0;
    for (int i = 0; i < t.n; ++i) {
        mine += strcmp(t.list[i], "my_topic") == 0;
        controls += strcmp(t.list[i], "actuator_controls_0") == 0;
        torque += strcmp(t.list[i], "vehicle_torque_setpoint") == 0;
    }
    TEST_ASSERT_TRUE(mine == 1 && controls == 0 && torque == 0);
    const char *const bad[] = {"command[0]=no_topic"};
    TEST_ASSERT_EQUAL_INT(-1, sim_log_px4_topics(bad, 1, &t, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "command[0]=no_topic"), msg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_field_kind);
    RUN_TEST(test_the_topics_asked_for);
    RUN_TEST(test_what_is_counted);
    RUN_TEST(test_a_cut_at_every_byte);
    RUN_TEST(test_appended_data);
    RUN_TEST(test_a_corrupt_header);
    RUN_TEST(test_refusals);
    RUN_TEST(test_refused_messages);
    RUN_TEST(test_px4_before_v1_13);
    RUN_TEST(test_px4_torque_setpoint_first);
    RUN_TEST(test_px4_without_a_command);
    RUN_TEST(test_px4_v1_15_formats);
    RUN_TEST(test_px4_topics);
    return UNITY_END();
}
