/* SPDX-License-Identifier: BSD-3-Clause */
/* Logs as they come (log_convert.h): the form told from the bytes, binary
 * logs decoded into a temporary folder of CSVs. */
#define _POSIX_C_SOURCE 200809L
#include "log_convert.h"

#include "log_ardupilot.h"
#include "log_bbl.h"
#include "log_dataflash.h"
#include "log_file.h"
#include "log_px4.h"
#include "log_ulog.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define HEAD_BYTES 64
#define HEADER_LINE_MAX 4096 /* bytes of a CSV header looked at for gyroADC */

static const char BBL_MAGIC[] = "H Product:Blackbox flight data recorder";
static const unsigned char ULOG_MAGIC[] = {'U', 'L', 'o', 'g', 0x01, 0x12, 0x35};
enum { DATAFLASH_HEAD1 = 0xA3, DATAFLASH_HEAD2 = 0x95, DATAFLASH_FMT = 0x80 };

const char *sim_log_source_name(sim_log_source_t s)
{
    static const char *const names[] = {"CSV", "PX4 ULog", "Betaflight blackbox", "ArduPilot DataFlash", "missing"};
    return (int)s >= 0 && (int)s <= (int)SIM_LOG_SOURCE_MISSING ? names[s] : "?";
}

/* ulog2csv's topic files under the prefix path (the prefix is no file). */
static int has_px4_topic_files(const char *path)
{
    char topic[SIM_LOG_PATH_LEN + 64];
    return sim_log_px4_topic_path(path, "vehicle_angular_velocity", topic, sizeof topic) == 0 &&
           access(topic, R_OK) == 0;
}

sim_log_source_t sim_log_source_of(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return has_px4_topic_files(path) ? SIM_LOG_SOURCE_CSV : SIM_LOG_SOURCE_MISSING;
    }
    unsigned char head[HEAD_BYTES];
    const size_t n = fread(head, 1, sizeof head, f);
    fclose(f);
    if (n >= sizeof ULOG_MAGIC && memcmp(head, ULOG_MAGIC, sizeof ULOG_MAGIC) == 0) {
        return SIM_LOG_SOURCE_ULOG;
    }
    if (n >= sizeof BBL_MAGIC - 1 && memcmp(head, BBL_MAGIC, sizeof BBL_MAGIC - 1) == 0) {
        return SIM_LOG_SOURCE_BBL;
    }
    if (n >= 3 && head[0] == DATAFLASH_HEAD1 && head[1] == DATAFLASH_HEAD2 && head[2] == DATAFLASH_FMT) {
        return SIM_LOG_SOURCE_DATAFLASH;
    }
    return SIM_LOG_SOURCE_CSV;
}

sim_log_format_t sim_log_csv_format_of(const char *path)
{
    /* ulog2csv's topic names are in the file's name, not in its folders' */
    const char *slash = strrchr(path, '/');
    const char *name = slash != NULL ? slash + 1 : path;
    if (strstr(name, "_vehicle_") != NULL || strstr(name, "_sensor_combined_") != NULL || has_px4_topic_files(path)) {
        return SIM_LOG_PX4;
    }
    FILE *f = fopen(path, "r");
    char line[HEADER_LINE_MAX] = "";
    if (f != NULL) {
        while (fgets(line, sizeof line, f) != NULL && (line[0] == '#' || line[0] == '\n')) {
        }
        fclose(f);
    }
    return strstr(line, "gyroADC") != NULL ? SIM_LOG_BETAFLIGHT : SIM_LOG_GENERIC;
}

/* The log's name without folders and extension. */
static void stem_of(const char *path, char *buf, size_t len)
{
    const char *base = strrchr(path, '/');
    snprintf(buf, len, "%s", base != NULL ? base + 1 : path);
    char *dot = strrchr(buf, '.');
    if (dot != NULL && dot != buf) {
        *dot = '\0';
    }
}

static long long file_bytes(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long long)st.st_size : 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A fresh folder under $TMPDIR (or /tmp): 0, or -1 with err set. */
static int make_temp_dir(sim_log_prepared_t *p, sim_log_error_t *err)
{
    const char *tmp = getenv("TMPDIR");
    if (tmp == NULL || tmp[0] == '\0') {
        tmp = "/tmp";
    }
    if (snprintf(p->dir, sizeof p->dir, "%s/ladrc_log.XXXXXX", tmp) >= (int)sizeof p->dir) {
        p->dir[0] = '\0';
        return sim_log_fail(err, p->original, 0, 0, "TMPDIR too long for a temporary folder");
    }
    if (mkdtemp(p->dir) == NULL) {
        const int e = errno;
        p->dir[0] = '\0';
        return sim_log_fail(err, p->original, 0, 0, "cannot make a temporary folder in %s: %s", tmp, strerror(e));
    }
    return 0;
}

/* Decodes the binary log into p->dir; o->path and o->format name the CSVs. */
static int decode(sim_log_options_t *o, sim_log_prepared_t *p, sim_log_convert_progress_fn progress, void *ctx,
                  sim_log_error_t *err)
{
    char stem[SIM_LOG_PATH_LEN], base[SIM_LOG_PATH_LEN];
    stem_of(p->original, stem, sizeof stem);
    if (snprintf(base, sizeof base, "%s/%s", p->dir, stem) >= (int)sizeof base) {
        return sim_log_fail(err, p->original, 0, 0, "path too long");
    }
    switch (p->source) {
    case SIM_LOG_SOURCE_ULOG: { /* the topics the px4 form reads, as ulog2csv's files under base */
        sim_log_px4_topics_t topics;
        char why[sizeof err->message];
        if (sim_log_px4_topics(o->map, o->n_map, &topics, why, sizeof why) != 0) {
            return sim_log_fail(err, p->original, 0, 0, "%s", why);
        }
        sim_log_ulog_stats_t st;
        if (sim_log_ulog_to_csv_stats(p->original, base, topics.list, topics.n, progress, ctx, &st, err) != 0) {
            return -1;
        }
        char notes[sizeof err->message * 2];
        if (sim_log_ulog_stats_describe(&st, notes, sizeof notes) > 0) { /* a cut, dropouts, skips: said */
            fprintf(stderr, "%s: %s\n", p->original, notes);
        }
        o->format = SIM_LOG_PX4;
        snprintf(o->path, sizeof o->path, "%s", base);
        return 0;
    }
    case SIM_LOG_SOURCE_BBL: { /* the longest of its logs, as blackbox_decode's CSV */
        sim_log_bbl_stats_t st;
        char notes[sizeof err->message * 2];
        if (sim_log_bbl_to_csv_stats(p->original, base, 0, progress, ctx, &st, err) != 0) {
            return -1;
        }
        if (sim_log_bbl_stats_describe(&st, notes, sizeof notes) > 0) { /* several logs, corruption, a cut: said */
            fprintf(stderr, "%s: %s\n", p->original, notes);
        }
        o->format = SIM_LOG_BETAFLIGHT;
        return snprintf(o->path, sizeof o->path, "%s.csv", base) < (int)sizeof o->path
                   ? 0
                   : sim_log_fail(err, p->original, 0, 0, "path too long");
    }
    case SIM_LOG_SOURCE_DATAFLASH: {
        char names[SIM_LOG_ARDUPILOT_TOPICS_MAX][SIM_LOG_ARDUPILOT_TYPE_LEN];
        const char *topics[SIM_LOG_ARDUPILOT_TOPICS_MAX];
        const int n = sim_log_ardupilot_topics(o->map, o->n_map, names, topics);
        if (sim_log_dataflash_to_csv(p->original, base, topics, n, progress, ctx, err) != 0) {
            return -1;
        }
        snprintf(o->path, sizeof o->path, "%s", base);
        o->format = SIM_LOG_ARDUPILOT;
        return 0;
    }
    default:
        return sim_log_fail(err, p->original, 0, 0, "not a binary log");
    }
}

int sim_log_prepare(sim_log_options_t *o, int format_given, sim_log_prepared_t *p, sim_log_convert_progress_fn progress,
                    void *progress_ctx, sim_log_error_t *err)
{
    memset(p, 0, sizeof *p);
    snprintf(p->original, sizeof p->original, "%s", o->path);
    struct stat st;
    if (stat(o->path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
        /* a pipe cannot be read again, and even its first bytes (the form's
         * magic) are gone once looked at */
        return sim_log_fail(err, o->path, 0, 0,
                            "not a regular file (a pipe or a device): a log is read more than once; save it "
                            "to a file first");
    }
    p->source = sim_log_source_of(o->path);
    p->bytes = file_bytes(o->path);
    if (p->source == SIM_LOG_SOURCE_MISSING) {
        return sim_log_fail(err, o->path, 0, 0, "no such log (nor ulog2csv topic files under that prefix)");
    }
    if (p->source == SIM_LOG_SOURCE_CSV) {
        if (!format_given) {
            o->format = sim_log_csv_format_of(o->path);
        }
        return 0;
    }
    const double start_s = now_s();
    if (make_temp_dir(p, err) != 0) {
        return -1;
    }
    if (decode(o, p, progress, progress_ctx, err) != 0) {
        sim_log_prepared_remove(p);
        return -1;
    }
    p->decode_s = now_s() - start_s;
    return 0;
}

void sim_log_prepared_explain(const sim_log_prepared_t *p, char *msg, size_t len)
{
    const size_t dir_len = strlen(p->dir);
    char *at = dir_len > 0 ? strstr(msg, p->dir) : NULL;
    if (at == NULL || at[dir_len] != '/') {
        return;
    }
    char out[2048];
    snprintf(out, sizeof out, "%.*s%s, decoded as %s", (int)(at - msg), msg, p->original, at + dir_len + 1);
    snprintf(msg, len, "%s", out);
}

void sim_log_prepared_remove(sim_log_prepared_t *p)
{
    if (p->dir[0] == '\0') {
        return;
    }
    DIR *d = opendir(p->dir);
    if (d != NULL) {
        const struct dirent *e;
        char path[SIM_LOG_PATH_LEN + 300];
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0 &&
                snprintf(path, sizeof path, "%s/%s", p->dir, e->d_name) < (int)sizeof path) {
                (void)remove(path);
            }
        }
        closedir(d);
    }
    (void)rmdir(p->dir);
    p->dir[0] = '\0';
}
