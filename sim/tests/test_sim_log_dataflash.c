/* SPDX-License-Identifier: BSD-3-Clause */
/* ArduPilot DataFlash logs (log/log_dataflash.h) built byte by byte here:
 * every field kind's text, FMTU multipliers, IMU instances split into
 * their files, a garbage run skipped and counted, a log cut at every byte
 * of its end, refusals that leave nothing behind, and the ardupilot form
 * end to end through sim_log_open against the values written. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, opendir */
#include "unity.h"
#include "log/log.h"
#include "log/log_ardupilot.h"
#include "log/log_dataflash.h"

#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846
/* A float written with 9 significant digits reads back within 2^-24 of
 * its value relative (float's own rounding); values here are below 4. */
#define FLOAT_TEXT_TOL 4e-7
#define EXACT_TOL 1e-12 /* exact decimals through a multiplication by pi/180 */

#define TEST_ASSERT_EQUAL_LL(want, got) TEST_ASSERT_TRUE((long long)(want) == (long long)(got))
#define ASSERT_NEAR(tol, want, got) assert_near((tol), (want), (got), __LINE__)

static void assert_near(double tol, double want, double got, int line)
{
    static char msg[200];
    snprintf(msg, sizeof msg, "want %.17g, got %.17g (tolerance %.3g)", want, got, tol);
    UNITY_TEST_ASSERT(fabs(got - want) <= tol, line, msg);
}

/* ---- a log, byte by byte ---- */

#define LOG_MAX (1 << 20)
typedef struct {
    unsigned char b[LOG_MAX];
    size_t n;
} log_bytes_t;

static log_bytes_t lb;

static void put(const void *p, size_t n)
{
    TEST_ASSERT_TRUE(lb.n + n <= LOG_MAX);
    memcpy(lb.b + lb.n, p, n);
    lb.n += n;
}

static void put_le(uint64_t v, int size)
{
    for (int i = 0; i < size; ++i) {
        const unsigned char ch = (unsigned char)(i < 8 ? v >> (8 * i) : 0u);
        put(&ch, 1);
    }
}

static void put_f32(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put_le(u, 4);
}

static void put_f64(double d)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    put_le(u, 8);
}

static void put_text(const char *s, size_t size)
{
    unsigned char buf[64] = {0};
    memcpy(buf, s, strlen(s) < size ? strlen(s) : size);
    put(buf, size);
}

static void header(int type)
{
    const unsigned char h[3] = {0xA3, 0x95, (unsigned char)type};
    put(h, 3);
}

enum { T_FMT = 128, T_FMTU = 200, T_MULT = 201, T_IMU = 10, T_ATT = 11, T_RATE = 12, T_RCOU = 13 };
enum { T_KIN1 = 20, T_KIN2 = 21, T_PIDR = 30, T_PIDP = 31, T_PIDY = 32 };

static void fmt(int type, int length, const char *name, const char *format, const char *columns)
{
    header(T_FMT);
    put_le((uint64_t)type, 1);
    put_le((uint64_t)length, 1);
    put_text(name, 4);
    put_text(format, 16);
    put_text(columns, 64);
}

static long long preamble_us; /* FMTU's and MULT's times, increasing as ArduPilot's */

static void fmtu(int type, const char *units, const char *mults)
{
    header(T_FMTU);
    put_le((uint64_t)++preamble_us, 8);
    put_le((uint64_t)type, 1);
    put_text(units, 16);
    put_text(mults, 16);
}

static void mult(char id, double v)
{
    header(T_MULT);
    put_le((uint64_t)++preamble_us, 8);
    put_le((uint64_t)(unsigned char)id, 1);
    put_f64(v);
}

/* The log's preamble: FMT of FMTU and MULT, the multipliers ArduPilot logs
 * (as floats widened to double, as it does). */
static void preamble(void)
{
    lb.n = 0;
    preamble_us = 0;
    fmt(T_FMTU, 44, "FMTU", "QBNN", "TimeUS,FmtType,UnitIds,MultIds");
    fmt(T_MULT, 20, "MULT", "Qbd", "TimeUS,Id,Mult");
    mult('0', 1.0);
    mult('B', (double)0.01f);
    mult('C', (double)0.001f);
    mult('F', (double)1e-6f);
}

static void imu(long long t_us, int instance, float x, float y, float z)
{
    header(T_IMU);
    put_le((uint64_t)t_us, 8);
    put_le((uint64_t)instance, 1);
    put_f32(x);
    put_f32(y);
    put_f32(z);
}

static void define_imu_att_rate_rcou(int with_rate)
{
    fmt(T_IMU, 24, "IMU", "QBfff", "TimeUS,I,GyrX,GyrY,GyrZ");
    fmtu(T_IMU, "s#EEE", "F-000");
    fmt(T_ATT, 23, "ATT", "Qcccccc", "TimeUS,DesRoll,Roll,DesPitch,Pitch,DesYaw,Yaw");
    fmtu(T_ATT, "sdddddd", "FBBBBBB");
    if (with_rate) {
        fmt(T_RATE, 39, "RATE", "Qfffffff", "TimeUS,RDes,ROut,PDes,POut,YDes,YOut,AOut");
        fmtu(T_RATE, "sk-k-k--", "F?-?-?--");
    }
    fmt(T_RCOU, 19, "RCOU", "QHHHH", "TimeUS,C1,C2,C3,C4");
}

/* ---- files ---- */

static char dir[64];
static char base[128];

void setUp(void)
{
    snprintf(dir, sizeof dir, "log_df_XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    snprintf(base, sizeof base, "%s/flight", dir);
}

static int count_files(void)
{
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d != NULL && (e = readdir(d)) != NULL;) {
        n += e->d_name[0] != '.';
    }
    if (d != NULL) {
        closedir(d);
    }
    return n;
}

void tearDown(void)
{
    DIR *d = opendir(dir);
    char path[512];
    for (struct dirent *e; d != NULL && (e = readdir(d)) != NULL;) {
        if (e->d_name[0] != '.') {
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            remove(path);
        }
    }
    if (d != NULL) {
        closedir(d);
    }
    rmdir(dir);
}

/* The log's bytes [0, n) decoded: the decoder's return. */
static int decode_n(size_t n, const char *const *topics, int n_topics, sim_log_dataflash_stats_t *st,
                    sim_log_error_t *err)
{
    char path[256];
    snprintf(path, sizeof path, "%s.bin", base);
    FILE *f = fopen(path, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_TRUE(fwrite(lb.b, 1, n, f) == n);
    fclose(f);
    f = fopen(path, "rb");
    const int rc = sim_log_dataflash_to_csv_stream(f, path, base, topics, n_topics, NULL, NULL, st, err);
    fclose(f);
    remove(path);
    return rc;
}

static int decode_all(sim_log_dataflash_stats_t *st)
{
    sim_log_error_t err;
    const int rc = decode_n(lb.n, NULL, 0, st, &err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, err.message);
    return rc;
}

/* Line `line` (1-based) of BASE_<name>.csv, without its end; "" past the end. */
static void read_line(const char *name, int line, char *out, size_t len)
{
    char path[256];
    snprintf(path, sizeof path, "%s_%s.csv", base, name);
    FILE *f = fopen(path, "r");
    TEST_ASSERT_NOT_NULL_MESSAGE(f, path);
    out[0] = '\0';
    for (int i = 0; i < line && fgets(out, (int)len, f) != NULL; ++i) {
    }
    if (feof(f)) {
        out[0] = '\0';
    }
    fclose(f);
    out[strcspn(out, "\n")] = '\0';
}

static int count_lines(const char *name)
{
    char path[256], buf[4096];
    snprintf(path, sizeof path, "%s_%s.csv", base, name);
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        return -1;
    }
    int n = 0;
    while (fgets(buf, sizeof buf, f) != NULL) {
        ++n;
    }
    fclose(f);
    return n;
}

/* ---- tests ---- */

static void test_every_field_kind_as_text(void)
{
    preamble();
    fmt(T_KIN1, 3 + 8 + 1 + 1 + 2 + 2 + 4 + 4 + 4 + 8 + 4 + 16 + 64 + 2 + 2, "KIN1", "QbBhHiIfdnNZcC",
        "TimeUS,vb,vB,vh,vH,vi,vI,vf,vd,vn,vN,vZ,vc,vC");
    /* vh carries a multiplier of 1e-2, vf one of 1e-3; c C restate theirs */
    fmtu(T_KIN1, "s-------------", "F--B---C----BB");
    fmt(T_KIN2, 3 + 8 + 4 + 4 + 4 + 1 + 8 + 8 + 2 + 64, "KIN2", "QeELMqQga", "TimeUS,ve,vE,vL,vM,vq,vQ,vg,va");
    header(T_KIN1);
    put_le(1000, 8);
    put_le((uint64_t)(int8_t)-5, 1);
    put_le(250, 1);
    put_le((uint64_t)(uint16_t)(int16_t)-1234, 2);
    put_le(65535, 2);
    put_le((uint64_t)(uint32_t)(int32_t)-2000000000, 4);
    put_le(4000000000u, 4);
    put_f32(1500.0f);
    put_f64(0.1);
    put_text("ABCD", 4);
    put_text("hello, world", 16);
    put_text("x\"y\nz", 64);
    put_le((uint64_t)(uint16_t)(int16_t)-12345, 2);
    put_le(65535, 2);
    header(T_KIN2);
    put_le(2000, 8);
    put_le((uint64_t)(uint32_t)(int32_t)-5, 4);
    put_le(123456789u, 4);
    put_le((uint64_t)(uint32_t)(int32_t)-353632608, 4);
    put_le(5, 1);
    put_le((uint64_t)(int64_t)-9000000000000000000LL, 8);
    put_le(18446744073709551615ULL, 8);
    put_le(0xC100, 2); /* half float -2.5 */
    for (int i = 0; i < 32; ++i) {
        put_le((uint64_t)(uint16_t)(int16_t)(i * 1000 - 16000), 2);
    }
    sim_log_dataflash_stats_t st;
    decode_all(&st);
    char line[4096];
    read_line("KIN1_0", 1, line, sizeof line);
    TEST_ASSERT_EQUAL_STRING("TimeUS,vb,vB,vh,vH,vi,vI,vf,vd,vn,vN,vZ,vc,vC", line);
    read_line("KIN1_0", 2, line, sizeof line);
    TEST_ASSERT_EQUAL_STRING("1000,-5,250,-12.34,65535,-2000000000,4000000000,1.5,0.10000000000000001,ABCD,hello_ "
                             "world,x_y_z,-123.45,655.35",
                             line);
    read_line("KIN2_0", 1, line, sizeof line);
    TEST_ASSERT_EQUAL_STRING("TimeUS,ve,vE,vL,vM,vq,vQ,vg,va[0", strtok(line, "]"));
    read_line("KIN2_0", 2, line, sizeof line);
    char want[4096];
    int w = snprintf(want, sizeof want,
                     "2000,-0.05,1234567.89,-35.3632608,5,-9000000000000000000,18446744073709551615,-2.5");
    for (int i = 0; i < 32; ++i) {
        w += snprintf(want + w, sizeof want - (size_t)w, ",%d", i * 1000 - 16000);
    }
    TEST_ASSERT_EQUAL_STRING(want, line);
    TEST_ASSERT_EQUAL_STRING("KIN2", st.type_name[T_KIN2]);
    TEST_ASSERT_EQUAL_LL(1, st.type_count[T_KIN2]);
    TEST_ASSERT_EQUAL_INT(0, st.bad_fmts);
    TEST_ASSERT_EQUAL_LL(0, st.skipped_bytes);
}

/* Floats over their whole range, and the edges of the formatter's cases
 * (decades, 1e-14 and 1e30, subnormals, signed zero), read back bit for bit. */
#define N_FLOATS 4000

static void test_floats_read_back_to_the_float_logged(void)
{
    static float v[N_FLOATS];
    static const float EDGES[] = {0.0f,       -0.0f,        1.0f,     9.99999999e8f, 1e9f,      999999.94f, 1e-4f,
                                  9.9999e-5f, 1e-14f,       9.9e-15f, 1e30f,         9.99e29f,  1e-45f,     3.4e38f,
                                  0.1f,       123456789.0f, -2.5e-7f, 16777216.0f,   0.000123f, 5e-5f};
    const int n_edges = (int)(sizeof EDGES / sizeof EDGES[0]);
    uint32_t state = 12345u;
    for (int i = 0; i < N_FLOATS; ++i) {
        if (i < n_edges) {
            v[i] = EDGES[i];
            continue;
        }
        do { /* a finite float of random bits */
            state = state * 1664525u + 1013904223u;
            memcpy(&v[i], &state, 4);
        } while (!isfinite(v[i]));
    }
    preamble();
    fmt(50, 15, "FLT", "Qf", "TimeUS,V");
    for (int i = 0; i < N_FLOATS; ++i) {
        header(50);
        put_le((uint64_t)(i + 1), 8);
        put_f32(v[i]);
    }
    sim_log_dataflash_stats_t st;
    decode_all(&st);
    char path[256], line[256];
    snprintf(path, sizeof path, "%s_FLT_0.csv", base);
    FILE *f = fopen(path, "r");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_NOT_NULL(fgets(line, sizeof line, f));
    for (int i = 0; i < N_FLOATS; ++i) {
        TEST_ASSERT_NOT_NULL(fgets(line, sizeof line, f));
        const float back = strtof(strchr(line, ',') + 1, NULL);
        char msg[300];
        snprintf(msg, sizeof msg, "%.9g written as %s", (double)v[i], line);
        TEST_ASSERT_TRUE_MESSAGE(memcmp(&back, &v[i], 4) == 0, msg);
    }
    fclose(f);
}

#define N_IMU 200

static void write_imu_pairs(void)
{
    for (int k = 0; k < N_IMU; ++k) {
        imu(1000 + 1000LL * k, 0, 0.001f * (float)k, -0.5f, 1.0f);
        imu(1000 + 1000LL * k, 1, -0.001f * (float)k, 0.5f, 2.0f);
    }
}

static void test_imu_instances_go_to_their_files(void)
{
    preamble();
    define_imu_att_rate_rcou(1);
    write_imu_pairs();
    sim_log_dataflash_stats_t st;
    decode_all(&st);
    TEST_ASSERT_EQUAL_INT(N_IMU + 1, count_lines("IMU_0"));
    TEST_ASSERT_EQUAL_INT(N_IMU + 1, count_lines("IMU_1"));
    TEST_ASSERT_EQUAL_INT(-1, count_lines("IMU_2"));
    char line[256];
    read_line("IMU_1", 3, line, sizeof line);
    TEST_ASSERT_EQUAL_STRING("2000,1,-0.00100000005,0.5,2", line);
    TEST_ASSERT_EQUAL_LL(2 * N_IMU, st.type_count[T_IMU]);
}

static void test_only_the_topics_asked(void)
{
    preamble();
    define_imu_att_rate_rcou(1);
    write_imu_pairs();
    const char *const topics[] = {"ATT", "IMU"};
    sim_log_dataflash_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT(0, decode_n(lb.n, topics, 2, &st, &err));
    TEST_ASSERT_EQUAL_INT(2, count_files()); /* IMU_0 and IMU_1: ATT has no rows, FMT is not asked */
    TEST_ASSERT_EQUAL_INT(2, st.files);
}

static void test_a_garbage_run_is_skipped_and_counted(void)
{
    preamble();
    define_imu_att_rate_rcou(1);
    imu(1000, 0, 1.0f, 2.0f, 3.0f);
    const size_t at = lb.n;
    /* a lone header byte, a header of an undefined type, noise */
    const unsigned char junk[] = {0xA3, 0x00, 0xA3, 0x95, 0x07, 0x11, 0x95, 0xA3, 0xA3, 0x22};
    put(junk, sizeof junk);
    imu(2000, 0, 4.0f, 5.0f, 6.0f);
    sim_log_dataflash_stats_t st;
    decode_all(&st);
    TEST_ASSERT_EQUAL_LL((long long)sizeof junk, st.skipped_bytes);
    TEST_ASSERT_EQUAL_LL(1, st.skip_runs);
    TEST_ASSERT_EQUAL_LL((long long)at, st.first_skip_offset);
    char line[256];
    read_line("IMU_0", 3, line, sizeof line);
    TEST_ASSERT_EQUAL_STRING("2000,0,4,5,6", line);
}

/* Cut at every byte of the last three messages: decoded up to the cut. */
static void test_a_log_cut_anywhere_decodes_up_to_the_cut(void)
{
    preamble();
    define_imu_att_rate_rcou(1);
    for (int k = 0; k < 10; ++k) {
        imu(1000 + 1000LL * k, 0, 1.0f, 2.0f, 3.0f);
    }
    const size_t imu_len = 24, full = lb.n;
    for (size_t cut = full - 3 * imu_len; cut <= full; ++cut) {
        sim_log_dataflash_stats_t st;
        sim_log_error_t err;
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, decode_n(cut, NULL, 0, &st, &err), err.message);
        const size_t into = (cut - (full - 10 * imu_len)) % imu_len;
        const int whole = (int)((cut - (full - 10 * imu_len)) / imu_len);
        TEST_ASSERT_EQUAL_INT(into != 0, st.truncated);
        if (into != 0) {
            TEST_ASSERT_EQUAL_LL((long long)(cut - into), st.truncated_offset);
        }
        TEST_ASSERT_EQUAL_INT(whole + 1, count_lines("IMU_0"));
        TEST_ASSERT_EQUAL_LL(0, st.skipped_bytes);
    }
}

static void test_refusals_leave_nothing(void)
{
    sim_log_dataflash_stats_t st;
    sim_log_error_t err;
    lb.n = 0;
    put("not a log at all, just text\n", 28);
    TEST_ASSERT_EQUAL_INT(-1, decode_n(lb.n, NULL, 0, &st, &err));
    TEST_ASSERT_NOT_NULL(strstr(err.message, "offset 0: not an ArduPilot DataFlash log"));
    TEST_ASSERT_EQUAL_INT(0, err.line);
    /* only the FMT of FMT's own type: nothing defined */
    lb.n = 0;
    fmt(T_FMT, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
    TEST_ASSERT_EQUAL_INT(-1, decode_n(lb.n, NULL, 0, &st, &err));
    TEST_ASSERT_EQUAL_INT(0, count_files());
    FILE *none = fopen("no_such_dir_df/x.bin", "rb");
    TEST_ASSERT_NULL(none);
    TEST_ASSERT_EQUAL_INT(-1, sim_log_dataflash_to_csv("no_such_dir_df/x.bin", base, NULL, 0, NULL, NULL, &err));
    TEST_ASSERT_NOT_NULL(strstr(err.message, "cannot open"));
}

static void test_bad_fmts_are_not_used(void)
{
    preamble();
    fmt(40, 30, "BADL", "Qf", "TimeUS,V");   /* fields 15 bytes, length 30: bytes past them allowed */
    fmt(41, 10, "BADS", "Qf", "TimeUS,V");   /* fields 15 bytes, length 10 */
    fmt(42, 15, "BA/D", "Qf", "TimeUS,V");   /* a name that is no file name */
    fmt(43, 15, "BADC", "Qf", "TimeUS,V,W"); /* three names for two fields */
    fmt(44, 15, "BADK", "Qx", "TimeUS,V");   /* no such kind */
    fmt(45, 15, "MULT", "Qf", "TimeUS,V");   /* a name of another type */
    fmt(46, 23, "BADT", "Nf", "TimeUS,V");   /* a time that is text */
    fmt(47, 9, "BADE", "cf", "TimeUS,V");    /* a time in hundredths */
    fmt(48, 15, "BADN", "Qf", "V,V");        /* a name twice */
    fmt(49, 3, "STRT", "", "");              /* no fields: framed, nothing written */
    header(49);
    header(40);
    put_le(5, 8);
    put_f32(2.0f);
    put_le(0, 30 - 15); /* BADL's bytes past its fields: framed, not read */
    header(41);
    put_le(5, 8);
    sim_log_dataflash_stats_t st;
    decode_all(&st);
    TEST_ASSERT_EQUAL_INT(8, st.bad_fmts);
    TEST_ASSERT_EQUAL_LL(1, st.type_count[49]);
    TEST_ASSERT_EQUAL_INT(-1, count_lines("STRT_0"));
    TEST_ASSERT_EQUAL_LL(3 + 8, st.skipped_bytes); /* the message of undefined type 41 */
    char line[256];
    read_line("BADL_0", 2, line, sizeof line);
    TEST_ASSERT_EQUAL_STRING("5,2", line);
}

static void test_time_not_increasing_is_dropped(void)
{
    preamble();
    define_imu_att_rate_rcou(1);
    imu(3000, 0, 1.0f, 1.0f, 1.0f);
    imu(3000, 0, 2.0f, 2.0f, 2.0f); /* the same time */
    imu(2000, 0, 3.0f, 3.0f, 3.0f); /* back */
    imu(4000, 0, 4.0f, 4.0f, 4.0f);
    const char *const topics[] = {"IMU"}; /* the preamble's rows share a time */
    sim_log_dataflash_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT(0, decode_n(lb.n, topics, 1, &st, &err));
    TEST_ASSERT_EQUAL_LL(2, st.rows_backwards);
    TEST_ASSERT_EQUAL_INT(3, count_lines("IMU_0"));
}

/* ---- the ardupilot form end to end ---- */

#define T_END_US 2000000LL
static double gyro_of(double s)
{
    return 0.5 * sin(2.0 * PI * 3.0 * s);
}
static double roll_cdeg_of(long long t_us)
{
    return (double)(t_us / 1000 % 3000) - 1500.0; /* centidegrees, integral */
}
static double rout_of(double s)
{
    return 0.2 * cos(2.0 * PI * 2.0 * s);
}

static void write_flight(int with_rate, int with_pid)
{
    preamble();
    define_imu_att_rate_rcou(with_rate);
    if (with_pid) {
        static const int types[3] = {T_PIDR, T_PIDP, T_PIDY};
        static const char *const names[3] = {"PIDR", "PIDP", "PIDY"};
        for (int a = 0; a < 3; ++a) {
            fmt(types[a], 31, names[a], "Qfffff", "TimeUS,Des,P,I,D,FF");
        }
    }
    for (long long t = 1000; t <= T_END_US; t += 1000) {
        const double s = (double)t * 1e-6;
        imu(t, 0, (float)gyro_of(s), (float)-gyro_of(s), 0.25f);
        imu(t, 1, 9.0f, 9.0f, 9.0f); /* the second IMU: not read */
        if (t % 4000 == 0) {
            header(T_ATT);
            put_le((uint64_t)t, 8);
            const int16_t roll = (int16_t)roll_cdeg_of(t);
            const int16_t v[6] = {(int16_t)(roll + 100), roll, 0, -250, 9000, 8990};
            for (int i = 0; i < 6; ++i) {
                put_le((uint64_t)(uint16_t)v[i], 2);
            }
        }
        if (with_rate) {
            header(T_RATE);
            put_le((uint64_t)t, 8);
            const float r[7] = {10.0f, (float)rout_of(s), -20.0f, -0.1f, 30.0f, 0.05f, 0.4f};
            for (int i = 0; i < 7; ++i) {
                put_f32(r[i]);
            }
        }
        if (with_pid) {
            for (int a = 0; a < 3; ++a) {
                header(a == 0 ? T_PIDR : (a == 1 ? T_PIDP : T_PIDY));
                put_le((uint64_t)t, 8);
                const float p[5] = {1.0f, 0.125f * (float)(a + 1), 0.25f, -0.0625f, 0.5f};
                for (int i = 0; i < 5; ++i) {
                    put_f32(p[i]);
                }
            }
        }
        if (t % 2000 == 0) {
            header(T_RCOU);
            put_le((uint64_t)t, 8);
            for (int q = 0; q < 4; ++q) {
                put_le((uint64_t)(1100 + 100 * q), 2);
            }
        }
    }
}

static sim_log_options_t ardupilot_options(void)
{
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = SIM_LOG_ARDUPILOT;
    snprintf(o.path, sizeof o.path, "%s.bin", base);
    o.dt_s = 0.001;
    return o;
}

static void test_the_ardupilot_form_reads_what_was_written(void)
{
    write_flight(1, 0);
    sim_log_dataflash_stats_t st;
    decode_all(&st);
    const sim_log_options_t o = ardupilot_options();
    sim_log_error_t err;
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    const unsigned has = sim_log_has(log);
    TEST_ASSERT_TRUE(has & SIM_LOG_HAS_GYRO);
    TEST_ASSERT_TRUE(has & SIM_LOG_HAS_ANGLE);
    TEST_ASSERT_TRUE(has & SIM_LOG_HAS_REF_ANGLE);
    TEST_ASSERT_TRUE(has & SIM_LOG_HAS_REF_RATE);
    TEST_ASSERT_TRUE(has & SIM_LOG_HAS_COMMAND);
    TEST_ASSERT_TRUE(has & SIM_LOG_HAS_THROTTLE);
    TEST_ASSERT_TRUE(has & SIM_LOG_HAS_MOTOR);
    TEST_ASSERT_FALSE(has & SIM_LOG_HAS_GYRO_RAW);
    sim_log_sample_t s;
    long long ticks = 0;
    while (sim_log_next(log, &s, &err) == 1) {
        const long long t_us = 4000 + 1000 * ticks; /* from the latest first row: ATT's, at 4 ms */
        const double t = (double)t_us * 1e-6;
        ASSERT_NEAR(1e-9, (double)ticks * 1e-3, s.t_s);
        ASSERT_NEAR(FLOAT_TEXT_TOL, gyro_of(t), s.gyro_rad_s[0]);
        ASSERT_NEAR(FLOAT_TEXT_TOL, -gyro_of(t), s.gyro_rad_s[1]);
        ASSERT_NEAR(FLOAT_TEXT_TOL, 0.25, s.gyro_rad_s[2]);
        ASSERT_NEAR(FLOAT_TEXT_TOL, rout_of(t), s.command[0]);
        ASSERT_NEAR(FLOAT_TEXT_TOL, -0.1, s.command[1]);
        ASSERT_NEAR(FLOAT_TEXT_TOL, 0.05, s.command[2]);
        ASSERT_NEAR(FLOAT_TEXT_TOL, 0.4, s.throttle);
        ASSERT_NEAR(FLOAT_TEXT_TOL, 10.0 * PI / 180.0, s.ref_rate_rad_s[0]);
        ASSERT_NEAR(FLOAT_TEXT_TOL, 30.0 * PI / 180.0, s.ref_rate_rad_s[2]);
        if (t_us % 4000 == 0) { /* on an ATT row: its values, exactly */
            ASSERT_NEAR(EXACT_TOL, roll_cdeg_of(t_us) * 0.01 * PI / 180.0, s.angle_rad[0]);
            ASSERT_NEAR(EXACT_TOL, (roll_cdeg_of(t_us) + 100.0) * 0.01 * PI / 180.0, s.ref_angle_rad[0]);
            ASSERT_NEAR(EXACT_TOL, -2.5 * PI / 180.0, s.angle_rad[1]);
            ASSERT_NEAR(EXACT_TOL, 89.9 * PI / 180.0, s.angle_rad[2]);
        }
        if (t_us % 2000 == 0) {
            ASSERT_NEAR(0.0, 1300.0, s.motor[2]);
        }
        ++ticks;
    }
    TEST_ASSERT_EQUAL_LL((T_END_US - 4000) / 1000 + 1, ticks);
    sim_log_close(log);
}

/* GYR written in bursts of four, every 4 ms, all at the burst's TimeUS:
 * read at each sample's SampleUS. */
static void test_raw_gyro_bursts_read_at_their_sample_time(void)
{
    write_flight(1, 0);
    enum { T_GYR = 60 };
    fmt(T_GYR, 32, "GYR", "QBQfff", "TimeUS,I,SampleUS,GyrX,GyrY,GyrZ");
    fmtu(T_GYR, "s#sEEE", "F-F000");
    for (long long t = 4000; t <= T_END_US; t += 4000) {
        for (long long j = 3; j >= 0; --j) {
            const long long sample = t - 1000 * j;
            header(T_GYR);
            put_le((uint64_t)t, 8);
            put_le(0, 1);
            put_le((uint64_t)sample, 8);
            put_f32((float)(0.001 * (double)(sample / 1000)));
            put_f32(0.0f);
            put_f32(-1.0f);
        }
    }
    sim_log_dataflash_stats_t st;
    decode_all(&st);
    TEST_ASSERT_EQUAL_LL(0, st.rows_backwards); /* TimeUS repeats, SampleUS does not */
    const sim_log_options_t o = ardupilot_options();
    sim_log_error_t err;
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    TEST_ASSERT_TRUE(sim_log_has(log) & SIM_LOG_HAS_GYRO_RAW);
    sim_log_sample_t s;
    for (long long k = 0; sim_log_next(log, &s, &err) == 1; ++k) {
        const long long t_us = 4000 + 1000 * k;
        ASSERT_NEAR(FLOAT_TEXT_TOL, 0.001 * (double)(t_us / 1000), s.gyro_raw_rad_s[0]);
        ASSERT_NEAR(0.0, -1.0, s.gyro_raw_rad_s[2]);
    }
    sim_log_close(log);
}

static void test_older_logs_command_from_the_pids(void)
{
    write_flight(0, 1);
    sim_log_dataflash_stats_t st;
    decode_all(&st);
    const sim_log_options_t o = ardupilot_options();
    sim_log_error_t err;
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    sim_log_sample_t s;
    TEST_ASSERT_EQUAL_INT(1, sim_log_next(log, &s, &err));
    for (int a = 0; a < 3; ++a) { /* P + I + D + FF, each exact in binary */
        ASSERT_NEAR(0.0, 0.125 * (a + 1) + 0.25 - 0.0625 + 0.5, s.command[a]);
    }
    TEST_ASSERT_FALSE(sim_log_has(log) & SIM_LOG_HAS_THROTTLE); /* CTUN not logged */
    sim_log_close(log);
}

static void test_a_log_without_the_command_is_refused_naming_its_bit(void)
{
    write_flight(0, 0);
    sim_log_dataflash_stats_t st;
    decode_all(&st);
    const sim_log_options_t o = ardupilot_options();
    sim_log_error_t err;
    TEST_ASSERT_NULL(sim_log_open(&o, &err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, "no RATE messages, needed for command[0]"), err.message);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, "LOG_BITMASK bit 0 ATTITUDE_FAST"), err.message);
    TEST_ASSERT_NOT_NULL(strstr(err.path, "flight_RATE_0.csv"));
}

static void test_the_base_and_the_types_to_decode(void)
{
    TEST_ASSERT_EQUAL_INT(SIM_LOG_ARDUPILOT, sim_log_format_parse("ardupilot"));
    TEST_ASSERT_EQUAL_STRING("ardupilot", sim_log_format_name(SIM_LOG_ARDUPILOT));
    TEST_ASSERT_TRUE(sim_log_format_has_topics(SIM_LOG_ARDUPILOT) && sim_log_format_has_topics(SIM_LOG_PX4));
    TEST_ASSERT_FALSE(sim_log_format_has_topics(SIM_LOG_BETAFLIGHT) || sim_log_format_has_topics(SIM_LOG_GENERIC));
    char b[128];
    sim_log_ardupilot_base("d/LOG_IMU_0.csv", b, sizeof b);
    TEST_ASSERT_EQUAL_STRING("d/LOG", b);
    sim_log_ardupilot_base("d/LOG_ESC_12.csv", b, sizeof b);
    TEST_ASSERT_EQUAL_STRING("d/LOG", b);
    sim_log_ardupilot_base("d/00000012.BIN", b, sizeof b);
    TEST_ASSERT_EQUAL_STRING("d/00000012", b);
    sim_log_ardupilot_base("d/LOG", b, sizeof b);
    TEST_ASSERT_EQUAL_STRING("d/LOG", b);
    sim_log_ardupilot_base("_IMU_0.csv", b, sizeof b); /* no BASE before it: the path */
    TEST_ASSERT_EQUAL_STRING("_IMU_0.csv", b);
    TEST_ASSERT_EQUAL_INT(0, sim_log_ardupilot_topic_path("d/LOG", "ESC[3]", b, sizeof b));
    TEST_ASSERT_EQUAL_STRING("d/LOG_ESC_3.csv", b);
    TEST_ASSERT_EQUAL_INT(-1, sim_log_ardupilot_topic_path("d/LOG", "ESC[3", b, sizeof b));
    TEST_ASSERT_EQUAL_INT(-1, sim_log_ardupilot_topic_path("d/LOG", "ESC[256]", b, sizeof b));
    /* the preset's types, both command variants, and those of the caller's items */
    const char *const map[] = {"gyro_raw[0]=VIBE.VibeX", "bad item"};
    char names[SIM_LOG_ARDUPILOT_TOPICS_MAX][SIM_LOG_ARDUPILOT_TYPE_LEN];
    const char *topics[SIM_LOG_ARDUPILOT_TOPICS_MAX];
    int n = sim_log_ardupilot_topics(map, 1, names, topics);
    static const char *const WANT[] = {"IMU",  "GYR",  "ATT",  "RATE", "PIDR", "PIDP",
                                       "PIDY", "CTUN", "RCOU", "ESC",  "VIBE"};
    const int n_want = (int)(sizeof WANT / sizeof WANT[0]);
    TEST_ASSERT_EQUAL_INT(n_want, n);
    for (int i = 0; i < n_want; ++i) {
        int found = 0;
        for (int k = 0; k < n; ++k) {
            found |= strcmp(topics[k], WANT[i]) == 0;
        }
        TEST_ASSERT_TRUE_MESSAGE(found, WANT[i]);
    }
    n = sim_log_ardupilot_topics(map, 2, names, topics); /* a bad item: the preset's types */
    TEST_ASSERT_EQUAL_INT(n_want - 1, n);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_field_kind_as_text);
    RUN_TEST(test_floats_read_back_to_the_float_logged);
    RUN_TEST(test_imu_instances_go_to_their_files);
    RUN_TEST(test_only_the_topics_asked);
    RUN_TEST(test_a_garbage_run_is_skipped_and_counted);
    RUN_TEST(test_a_log_cut_anywhere_decodes_up_to_the_cut);
    RUN_TEST(test_refusals_leave_nothing);
    RUN_TEST(test_bad_fmts_are_not_used);
    RUN_TEST(test_time_not_increasing_is_dropped);
    RUN_TEST(test_the_ardupilot_form_reads_what_was_written);
    RUN_TEST(test_raw_gyro_bursts_read_at_their_sample_time);
    RUN_TEST(test_older_logs_command_from_the_pids);
    RUN_TEST(test_a_log_without_the_command_is_refused_naming_its_bit);
    RUN_TEST(test_the_base_and_the_types_to_decode);
    return UNITY_END();
}
