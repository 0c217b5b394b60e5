/* SPDX-License-Identifier: BSD-3-Clause */
/* The flight-log reader (log.h): opening the files, the tick grid, each
 * tick's sample from the files' brackets. */
#include "log.h"

#include "log_ardupilot.h"
#include "log_px4.h"
#include "log_reader.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A control period within this of a whole number of microseconds is one:
 * the grid is then computed in integers. */
#define WHOLE_US_TOL 1e-9
/* Tick indices stay below this; ticks past 2^54 us lie after any row. */
#define K_MAX 4611686018427387904.0      /* 2^62 */
#define TIME_SPAN_US 18014398509481984.0 /* 2^54 */
#define DT_MIN_S 1e-6

void sim_log_options_default(sim_log_options_t *o)
{
    memset(o, 0, sizeof *o);
    o->format = SIM_LOG_BETAFLIGHT;
}

static const char *const FORMAT_NAMES[SIM_LOG_FORMAT_COUNT] = {"betaflight", "px4", "generic", "ardupilot"};

int sim_log_format_parse(const char *name)
{
    for (int i = 0; name != NULL && i < SIM_LOG_FORMAT_COUNT; ++i) {
        if (strcmp(name, FORMAT_NAMES[i]) == 0) {
            return i;
        }
    }
    return -1;
}

const char *sim_log_format_name(sim_log_format_t f)
{
    return ((int)f >= 0 && (int)f < SIM_LOG_FORMAT_COUNT) ? FORMAT_NAMES[f] : "?";
}

void sim_log_error_format(const sim_log_error_t *err, char *buf, size_t len)
{
    if (err->line > 0) {
        snprintf(buf, len, "%s:%d:%d: %s", err->path, err->line, err->column, err->message);
    } else {
        snprintf(buf, len, "%s: %s", err->path, err->message);
    }
}

static int check_options(const sim_log_options_t *o, const char *path, sim_log_error_t *err)
{
    if ((int)o->format < 0 || (int)o->format >= SIM_LOG_FORMAT_COUNT) {
        return sim_log_fail(err, path, 0, 0, "unknown log form %d", (int)o->format);
    }
    if (!(o->dt_s == 0.0 || (o->dt_s >= DT_MIN_S && isfinite(o->dt_s)))) {
        return sim_log_fail(err, path, 0, 0, "dt_s %g: 0 (the log's median row period) or 1e-6 s and up", o->dt_s);
    }
    if (!(o->t_from_s >= 0.0 && isfinite(o->t_from_s) && isfinite(o->t_to_s))) {
        return sim_log_fail(err, path, 0, 0, "window %g to %g s: from 0 s up, finite", o->t_from_s, o->t_to_s);
    }
    if (o->t_to_s > 0.0 && o->t_to_s <= o->t_from_s) {
        return sim_log_fail(err, path, 0, 0, "empty window: %g to %g s", o->t_from_s, o->t_to_s);
    }
    if (o->n_map < 0 || o->n_map > SIM_LOG_MAX_MAP) {
        return sim_log_fail(err, path, 0, 0, "%d map items (0 to %d)", o->n_map, SIM_LOG_MAX_MAP);
    }
    return 0;
}

static int file_exists(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f != NULL) {
        fclose(f);
    }
    return f != NULL;
}

/* The form's preset and the caller's items. ArduPilot: the commands from
 * RATE, or from PIDR/PIDP/PIDY when the log has those and no RATE. */
static int build_map(sim_log_t *log, const sim_log_options_t *opt, char *msg, size_t len)
{
    if (opt->format != SIM_LOG_ARDUPILOT) {
        return sim_log_map_build(&log->map, opt->format, opt->map, opt->n_map, msg, len);
    }
    char base[SIM_LOG_PATH_LEN], rate[SIM_LOG_PATH_LEN + 16], pidr[SIM_LOG_PATH_LEN + 16];
    sim_log_ardupilot_base(opt->path, base, sizeof base);
    const int with_rate = sim_log_ardupilot_topic_path(base, "RATE", rate, sizeof rate) != 0 || file_exists(rate) ||
                          sim_log_ardupilot_topic_path(base, "PIDR", pidr, sizeof pidr) != 0 || !file_exists(pidr);
    return sim_log_map_build_ardupilot(&log->map, with_rate, opt->map, opt->n_map, msg, len);
}

static sim_log_t *start(const sim_log_options_t *opt, const char *path, sim_log_error_t *err)
{
    if (check_options(opt, path, err) != 0) {
        return NULL;
    }
    /* a file per topic, at most one per slot */
    const size_t file_slots = sim_log_format_has_topics(opt->format) ? SIM_LOG_N_SLOTS : 1;
    sim_log_t *log = calloc(1, sizeof *log);
    sim_log_item_t *t = log != NULL ? &log->topic_time : NULL;
    if (log == NULL || (log->files = calloc(file_slots, sizeof *log->files)) == NULL) {
        free(log);
        sim_log_fail(err, path, 0, 0, "out of memory");
        return NULL;
    }
    log->format = opt->format;
    snprintf(log->path, sizeof log->path, "%s", path);
    char message[sizeof err->message];
    if (build_map(log, opt, message, sizeof message) != 0) {
        sim_log_fail(err, path, 0, 0, "%s", message);
        sim_log_close(log);
        return NULL;
    }
    t->slot = 0;
    t->n_terms = 1;
    strcpy(t->term[0].column, opt->format == SIM_LOG_ARDUPILOT ? "TimeUS" : "timestamp");
    t->scale = 1e-6;
    log->sample_time = *t;
    strcpy(log->sample_time.term[0].column, "SampleUS");
    return log;
}

/* The quaternion's components are all mapped or none: 0, or -1 at the
 * header of the file with one of them. */
static int check_quat(sim_log_t *log, sim_log_group_t g, sim_log_error_t *err)
{
    const int first = sim_log_group_first(g);
    int with = -1, without = -1;
    for (int i = 0; i < 4; ++i) {
        if (log->slot_file[first + i] >= 0) {
            with = with < 0 ? first + i : with;
        } else {
            without = without < 0 ? first + i : without;
        }
    }
    if (with >= 0 && without >= 0) {
        char a[32], b[32];
        const sim_log_file_t *f = &log->files[log->slot_file[with]];
        sim_log_slot_name(without, a, sizeof a);
        sim_log_slot_name(with, b, sizeof b);
        return sim_log_fail(err, f->path, f->header_line, f->header_end,
                            "no column for %s while %s has one (a quaternion takes all four)", a, b);
    }
    return 0;
}

static int group_present(const sim_log_t *log, sim_log_group_t g)
{
    const int first = sim_log_group_first(g);
    for (int i = 0; i < sim_log_group_count(g); ++i) {
        if (log->slot_file[first + i] >= 0) {
            return 1;
        }
    }
    return 0;
}

/* The fields the files give, as flags, and the motors' count. */
static int find_fields(sim_log_t *log, sim_log_error_t *err)
{
    static const struct {
        sim_log_group_t g;
        unsigned flag;
    } PLAIN[] = {{SIM_LOG_G_GYRO, SIM_LOG_HAS_GYRO},         {SIM_LOG_G_GYRO_RAW, SIM_LOG_HAS_GYRO_RAW},
                 {SIM_LOG_G_REF_RATE, SIM_LOG_HAS_REF_RATE}, {SIM_LOG_G_COMMAND, SIM_LOG_HAS_COMMAND},
                 {SIM_LOG_G_THROTTLE, SIM_LOG_HAS_THROTTLE}, {SIM_LOG_G_MOTOR, SIM_LOG_HAS_MOTOR},
                 {SIM_LOG_G_ROTOR_HZ, SIM_LOG_HAS_ROTOR_HZ}};
    for (int s = 0; s < SIM_LOG_N_SLOTS; ++s) {
        log->slot_file[s] = -1;
    }
    for (int i = 0; i < log->n_files; ++i) {
        const sim_log_file_t *f = &log->files[i];
        for (int j = 0; j < f->n_items; ++j) {
            if (f->present[j]) {
                log->slot_file[f->slot[j]] = i;
                log->slot_index[f->slot[j]] = j;
            }
        }
    }
    if (check_quat(log, SIM_LOG_G_QUAT, err) != 0 || check_quat(log, SIM_LOG_G_REF_QUAT, err) != 0) {
        return -1;
    }
    for (int g = 0; g < SIM_LOG_G_COUNT; ++g) {
        log->group_has[g] = group_present(log, (sim_log_group_t)g);
    }
    log->has = 0;
    for (size_t i = 0; i < sizeof PLAIN / sizeof PLAIN[0]; ++i) {
        log->has |= log->group_has[PLAIN[i].g] ? PLAIN[i].flag : 0u;
    }
    if (log->group_has[SIM_LOG_G_ANGLE] || log->group_has[SIM_LOG_G_QUAT]) {
        log->has |= SIM_LOG_HAS_ANGLE;
    } else if (log->has & SIM_LOG_HAS_GYRO) {
        log->has |= SIM_LOG_HAS_ANGLE_INTEGRATED;
    }
    if (log->group_has[SIM_LOG_G_REF_ANGLE] || log->group_has[SIM_LOG_G_REF_QUAT]) {
        log->has |= SIM_LOG_HAS_REF_ANGLE;
    } else if (log->has & SIM_LOG_HAS_REF_RATE) {
        log->has |= SIM_LOG_HAS_REF_INTEGRATED;
    }
    log->n_motors = 0;
    for (int q = 0; q < SIM_LOG_MAX_MOTORS; ++q) {
        if (log->slot_file[sim_log_group_first(SIM_LOG_G_MOTOR) + q] >= 0 ||
            log->slot_file[sim_log_group_first(SIM_LOG_G_ROTOR_HZ) + q] >= 0) {
            log->n_motors = q + 1;
        }
    }
    return 0;
}

/* Every file to the first tick, the latest first time of them all. */
static int find_start(sim_log_t *log, sim_log_error_t *err)
{
    int latest = 0;
    for (int i = 1; i < log->n_files; ++i) {
        if (log->files[i].t0 > log->files[latest].t0) {
            latest = i;
        }
    }
    log->t_first_us = log->files[latest].t0;
    for (int i = 0; i < log->n_files; ++i) {
        sim_log_file_t *f = &log->files[i];
        const int rc = sim_log_file_reach(f, log->t_first_us, err);
        if (rc < 0) {
            snprintf(err->path, sizeof err->path, "%s", f->path);
            return -1;
        }
        if (rc == 0) {
            return sim_log_fail(err, f->path, 0, 0, "no overlap in time: it ends at %.9g s, before %s starts at %.9g s",
                                f->t0 * 1e-6, log->files[latest].path, log->t_first_us * 1e-6);
        }
    }
    return 0;
}

static long long clamp_k(double k)
{
    return k < 0.0 ? 0 : (k > K_MAX ? (long long)K_MAX : (long long)k);
}

/* The control period and the window's ticks. */
static void set_grid(sim_log_t *log, const sim_log_options_t *opt)
{
    log->dt_us = opt->dt_s > 0.0 ? opt->dt_s * 1e6 : log->files[0].median_us;
    const double dt_round = floor(log->dt_us + 0.5);
    const double t_round = floor(log->t_first_us + 0.5);
    log->whole = fabs(log->dt_us - dt_round) <= WHOLE_US_TOL && dt_round >= 1.0 && dt_round <= TIME_SPAN_US &&
                 log->t_first_us == t_round;
    if (log->whole) {
        log->dt_us = dt_round;
        log->dt_whole = (long long)dt_round;
        log->t_first_whole = (long long)t_round;
    }
    const double span_k = TIME_SPAN_US / log->dt_us + 1.0; /* ticks past every row */
    const double from_k = ceil(opt->t_from_s * 1e6 / log->dt_us - WHOLE_US_TOL);
    log->k = clamp_k(from_k < span_k ? from_k : span_k);
    log->k_end = opt->t_to_s > 0.0 ? clamp_k(floor(opt->t_to_s * 1e6 / log->dt_us + WHOLE_US_TOL)) : (long long)K_MAX;
    log->t_from_s = opt->t_from_s;
}

/* After the files are open: fields, start, grid. */
static sim_log_t *finish_open(sim_log_t *log, const sim_log_options_t *opt, sim_log_error_t *err)
{
    if (log->n_files == 0) {
        sim_log_fail(err, log->path, 0, 0, "no topic file has a mapped column");
    } else if (find_fields(log, err) == 0 && find_start(log, err) == 0) {
        if (!(opt->dt_s > 0.0) && !(log->files[0].median_us >= DT_MIN_S * 1e6)) {
            /* a period the controllers cannot run at, from the log's own times */
            /* located at the header, which names the time column's unit */
            sim_log_fail(err, log->files[0].path, log->files[0].header_line, 1,
                         "rows %g s apart (the median): below 1e-6 s; the time column in another unit? "
                         "(its unit is told by its header; --dt sets the period)",
                         log->files[0].median_us * 1e-6);
        } else {
            set_grid(log, opt);
            return log;
        }
    }
    sim_log_close(log);
    return NULL;
}

static int open_file(sim_log_t *log, FILE *stream, int own, const char *path, const char *topic, sim_log_error_t *err)
{
    const sim_log_item_t *time = &log->map.item[0];
    if (topic != NULL) {
        const int sampled = log->format == SIM_LOG_ARDUPILOT && sim_log_ardupilot_sample_timed(topic);
        time = sampled ? &log->sample_time : &log->topic_time;
    }
    sim_log_file_t *f = &log->files[log->n_files];
    if (sim_log_file_open(f, stream, own, path, time, &log->map, topic, err) != 0) {
        snprintf(err->path, sizeof err->path, "%s", path);
        return -1;
    }
    int used = topic == NULL; /* a single CSV is read even with its time alone */
    for (int j = 0; j < f->n_items; ++j) {
        used |= f->present[j];
    }
    if (used) {
        ++log->n_files;
    } else {
        sim_log_file_close(f); /* all of its columns optional and absent */
    }
    return 0;
}

/* A required item of the topic: its slot, or -1. */
static int needs_topic(const sim_log_map_t *m, const char *topic)
{
    for (int s = 1; s < SIM_LOG_N_SLOTS; ++s) {
        if (!m->mapped[s] || strcmp(m->item[s].topic, topic) != 0) {
            continue;
        }
        for (int k = 0; k < m->item[s].n_terms; ++k) {
            if (!m->item[s].term[k].optional) {
                return s;
            }
        }
    }
    return -1;
}

static int topic_path(const sim_log_options_t *opt, const char *base, const char *topic, char *out, size_t len)
{
    return opt->format == SIM_LOG_ARDUPILOT ? sim_log_ardupilot_topic_path(base, topic, out, len)
                                            : sim_log_px4_topic_path(base, topic, out, len);
}

static sim_log_t *open_topics(sim_log_t *log, const sim_log_options_t *opt, sim_log_error_t *err)
{
    const char *topics[SIM_LOG_PX4_TOPICS_MAX];
    /* the base from any topic's file, then each field from the topic logged */
    int n = sim_log_px4_map_topics(&log->map, 1, topics);
    char base[SIM_LOG_PATH_LEN], path[SIM_LOG_PATH_LEN], field[32];
    int rc = 0;
    if (opt->format == SIM_LOG_ARDUPILOT) {
        sim_log_ardupilot_base(opt->path, base, sizeof base);
    } else {
        sim_log_px4_base(opt->path, topics, n, base, sizeof base);
        sim_log_px4_choose(&log->map, base);
        n = sim_log_px4_map_topics(&log->map, 0, topics);
    }
    for (int i = 0; rc == 0 && i < n; ++i) {
        if (topic_path(opt, base, topics[i], path, sizeof path) != 0) {
            rc = sim_log_fail(err, base, 0, 0, "the path of topic %s is longer than %d bytes", topics[i],
                              SIM_LOG_PATH_LEN - 1);
            break;
        }
        FILE *stream = fopen(path, "rb");
        const int open_errno = errno;
        const int slot = stream == NULL ? needs_topic(&log->map, topics[i]) : -1;
        if (stream != NULL) {
            rc = open_file(log, stream, 1, path, topics[i], err);
        } else if (slot >= 0 && opt->format == SIM_LOG_ARDUPILOT) {
            sim_log_slot_name(slot, field, sizeof field);
            rc = sim_log_fail(err, path, 0, 0, "cannot open: %s (no %s messages, needed for %s: logged with %s)",
                              strerror(open_errno), topics[i], field, sim_log_ardupilot_enabled_by(topics[i]));
        } else if (slot >= 0 && log->map.has_fallback[slot]) {
            sim_log_slot_name(slot, field, sizeof field);
            rc = sim_log_fail(err, path, 0, 0,
                              "cannot open: %s (topic %s, needed for %s; nor is there a file of %s, "
                              "which older PX4 releases log)",
                              strerror(open_errno), topics[i], field, log->map.fallback[slot].topic);
        } else if (slot >= 0) {
            sim_log_slot_name(slot, field, sizeof field);
            rc = sim_log_fail(err, path, 0, 0, "cannot open: %s (topic %s, needed for %s)", strerror(open_errno),
                              topics[i], field);
        } /* else its items are optional: absent */
    }
    if (rc == 0) {
        return finish_open(log, opt, err);
    }
    sim_log_close(log);
    return NULL;
}

sim_log_t *sim_log_open(const sim_log_options_t *opt, sim_log_error_t *err)
{
    sim_log_t *log = start(opt, opt->path, err);
    if (log == NULL) {
        return NULL;
    }
    if (sim_log_format_has_topics(opt->format)) {
        return open_topics(log, opt, err);
    }
    FILE *stream = fopen(opt->path, "rb");
    if (stream == NULL) {
        sim_log_fail(err, opt->path, 0, 0, "cannot open: %s", strerror(errno));
    } else if (open_file(log, stream, 1, opt->path, NULL, err) == 0) {
        return finish_open(log, opt, err);
    }
    sim_log_close(log);
    return NULL;
}

sim_log_t *sim_log_open_stream(FILE *stream, const char *name, const sim_log_options_t *opt, sim_log_error_t *err)
{
    if (sim_log_format_has_topics(opt->format)) {
        sim_log_fail(err, name, 0, 0, "the %s form is read from its topic files, not a stream",
                     sim_log_format_name(opt->format));
        return NULL;
    }
    sim_log_t *log = start(opt, name, err);
    if (log == NULL) {
        return NULL;
    }
    if (open_file(log, stream, 0, name, NULL, err) == 0) {
        return finish_open(log, opt, err);
    }
    sim_log_close(log);
    return NULL;
}

void sim_log_close(sim_log_t *log)
{
    if (log == NULL) {
        return;
    }
    for (int i = 0; i < log->n_files; ++i) {
        sim_log_file_close(&log->files[i]);
    }
    free(log->files);
    free(log);
}
