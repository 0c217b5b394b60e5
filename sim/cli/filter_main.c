/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ladrc_filter: the library's gyro filter stage (gyro_filter.h) run over a
 * flight log's gyro before its filters (or its gyro when it has no other),
 * the filtered series written, and per axis the noise in bands before and
 * after, the attenuation and the delay; the same for the log's own filter
 * chain when it has both gyros (docs/filter-tool.md).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ladrc/gyro_filter.h"
#include "ladrc/margins.h"
#include "cli/cli_number.h"
#include "cli/staged_dir.h"
#include "log/filter_proposal.h"
#include "log/log_convert.h"
#include "log/log_noise.h"
#include "scenario/scenario.h"
#include "scenario/setup.h"

#define PI 3.14159265358979323846
#define RAD2DEG (180.0 / PI)
/* The crossover the proposal keeps the phase cost at when none is given
 * (rad/s): the simulator's chirp flight's tuned crossovers span 21-34. */
#define CROSSOVER_DEFAULT_RAD_S 30.0

static const char *const AXIS[3] = {"roll", "pitch", "yaw"};

typedef struct {
    sim_log_options_t log;
    const char *filter_from, *out;
    double crossover_rad_s;
    int given;        /* a stage option was given */
    int format_given; /* --format: else told from the file, as ladrc_replay tells it */
    ladrc_gyro_filter_config_t cfg;
} options_t;

static void usage(FILE *out)
{
    fputs("usage: ladrc_filter LOG [--format betaflight|px4|generic] [--map FIELD=SOURCE]... [--dt S]\n"
          "                    [--from S] [--to S] [--filter-from SCENARIO.ini | stage options]\n"
          "                    [--crossover RAD_S] [--out FILE.csv]\n"
          "  --filter-from F   the stage of scenario F's [filter] section (e.g. ladrc_replay's airframe.ini)\n"
          "  stage options     --lpf HZ [--lpf-order 1|2], --notch HZ (up to 4) [--notch-q Q],\n"
          "                    --rpm-harmonics N [--rpm-q Q] [--rpm-min HZ] [--rpm-fade HZ] (needs rotor speed)\n"
          "  (neither: the stage proposed from the log's spectrum, as ladrc_replay proposes it)\n"
          "  --crossover W     the loop crossover (rad/s) the proposal keeps the phase cost at (default 30)\n"
          "  --out FILE.csv    the series: t_s, the input and the filtered gyro per axis (rad/s)\n"
          "Prints per axis the rms in 0-20, 20-100, >100 Hz and the vibration band, before and after,\n"
          "the attenuation (dB), the phase at the crossover (deg) and its delay (ms); the same for the log's own chain "
          "when it has both\n"
          "gyros. Exit status 0; 2 for bad usage or a refused log or stage.\n",
          out);
}

/* One stage option at argv[a] with its value; 1 when it was one, 0 when
 * not, -1 on a bad value. */
static int stage_option(options_t *o, const char *arg, const char *val)
{
    static const char *const names[] = {"--lpf",           "--lpf-order", "--notch",   "--notch-q",
                                        "--rpm-harmonics", "--rpm-q",     "--rpm-min", "--rpm-fade"};
    int which = -1;
    for (int k = 0; k < (int)(sizeof names / sizeof names[0]); ++k) {
        which = strcmp(arg, names[k]) == 0 ? k : which;
    }
    if (which < 0) {
        return 0;
    }
    double v;
    if (sim_cli_number("ladrc_filter", arg, val, &v) != 0) {
        return -1;
    }
    ladrc_gyro_filter_config_t *c = &o->cfg;
    o->given = 1;
    switch (which) {
    case 0:
        c->lpf_cutoff_hz = (ladrc_real_t)v;
        c->lpf_order = c->lpf_order == 0 ? 2 : c->lpf_order;
        break;
    case 1:
        if (v != 1.0 && v != 2.0) {
            fprintf(stderr, "ladrc_filter: --lpf-order: expected 1 or 2, got '%s'\n", val);
            return -1;
        }
        c->lpf_order = (uint8_t)v;
        break;
    case 2:
        if (c->n_notches >= LADRC_GYRO_FILTER_MAX_NOTCHES) {
            fprintf(stderr, "ladrc_filter: --notch: at most %u notches\n", LADRC_GYRO_FILTER_MAX_NOTCHES);
            return -1;
        }
        c->notch_hz[c->n_notches++] = (ladrc_real_t)v;
        break;
    case 3:
        c->notch_q = (ladrc_real_t)v;
        break;
    case 4:
        if (v != floor(v) || v < 1.0 || v > LADRC_GYRO_FILTER_MAX_HARMONICS) {
            fprintf(stderr, "ladrc_filter: --rpm-harmonics: expected 1..%u, got '%s'\n",
                    LADRC_GYRO_FILTER_MAX_HARMONICS, val);
            return -1;
        }
        c->rpm_harmonics = (uint8_t)v;
        c->rpm_rotors = 1; /* the rotors the log reports, set once it is open */
        break;
    case 5:
        c->rpm_q = (ladrc_real_t)v;
        break;
    case 6:
        c->rpm_min_hz = (ladrc_real_t)v;
        break;
    default:
        c->rpm_fade_hz = (ladrc_real_t)v;
        break;
    }
    return 1;
}

static int parse_args(int argc, char **argv, options_t *o)
{
    memset(o, 0, sizeof *o);
    sim_log_options_default(&o->log);
    o->crossover_rad_s = CROSSOVER_DEFAULT_RAD_S;
    ladrc_gyro_filter_config_default(&o->cfg, LADRC_R(0.001), 3); /* dt: the log's, set once it is open */
    const char *path = NULL;
    int format_given = 0;
    for (int a = 1; a < argc; ++a) {
        const char *arg = argv[a], *val = a + 1 < argc ? argv[a + 1] : NULL;
        double v;
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            usage(stdout);
            exit(0);
        }
        if (arg[0] == '-' && val == NULL) {
            fprintf(stderr, "ladrc_filter: %s needs a value\n", arg);
            return -1;
        }
        const int st = arg[0] == '-' ? stage_option(o, arg, val) : 0;
        if (st < 0) {
            return -1;
        } else if (st > 0) {
            ++a;
        } else if (strcmp(arg, "--format") == 0) {
            const int f = sim_log_format_parse(val);
            if (f < 0) {
                fprintf(stderr, "ladrc_filter: --format: expected betaflight, px4 or generic, got '%s'\n", val);
                return -1;
            }
            o->log.format = (sim_log_format_t)f;
            format_given = 1;
            ++a;
        } else if (strcmp(arg, "--map") == 0) {
            if (o->log.n_map >= SIM_LOG_MAX_MAP) {
                fprintf(stderr, "ladrc_filter: --map: at most %d items\n", SIM_LOG_MAX_MAP);
                return -1;
            }
            o->log.map[o->log.n_map++] = argv[++a];
        } else if (strcmp(arg, "--dt") == 0 || strcmp(arg, "--from") == 0 || strcmp(arg, "--to") == 0 ||
                   strcmp(arg, "--crossover") == 0) {
            if (sim_cli_number("ladrc_filter", arg, argv[++a], &v) != 0) {
                return -1;
            }
            *(arg[2] == 'd'   ? &o->log.dt_s
              : arg[2] == 'f' ? &o->log.t_from_s
              : arg[2] == 't' ? &o->log.t_to_s
                              : &o->crossover_rad_s) = v;
        } else if (strcmp(arg, "--filter-from") == 0) {
            o->filter_from = argv[++a];
        } else if (strcmp(arg, "--out") == 0) {
            o->out = argv[++a];
        } else if (arg[0] == '-' || path != NULL) {
            fprintf(stderr, "ladrc_filter: unknown or extra argument '%s'\n", arg);
            return -1;
        } else {
            path = arg;
        }
    }
    if (path == NULL) {
        usage(stderr);
        return -1;
    }
    if (o->filter_from != NULL && o->given) {
        fprintf(stderr, "ladrc_filter: --filter-from conflicts with the stage options: give one of them\n");
        return -1;
    }
    if (!(o->crossover_rad_s > 0.0)) {
        fprintf(stderr, "ladrc_filter: --crossover: expected a frequency > 0 rad/s\n");
        return -1;
    }
    if (snprintf(o->log.path, sizeof o->log.path, "%s", path) >= (int)sizeof o->log.path) {
        fprintf(stderr, "ladrc_filter: %s: path too long\n", path);
        return -1;
    }
    o->format_given = format_given;
    return 0;
}

/* The stage from the scenario file's [filter]; 0, or -1 after saying why. */
static int stage_from_scenario(const char *path, double dt_s, ladrc_gyro_filter_config_t *cfg)
{
    static sim_scenario_t sc;
    sim_parse_error_t perr;
    if (sim_scenario_load(&sc, path, &perr) != 0) {
        if (perr.line > 0) {
            fprintf(stderr, "%s:%d:%d: %s\n", perr.path, perr.line, perr.column, perr.message);
        } else {
            fprintf(stderr, "%s: %s\n", perr.path, perr.message);
        }
        return -1;
    }
    if (!sim_setup_filters_gyro(&sc)) {
        fprintf(stderr, "%s: no gyro filter stage: its [filter] section has no stage on\n", path);
        return -1;
    }
    if (fabs(sc.control_dt_s - dt_s) > 1e-9 * dt_s) {
        fprintf(stderr, "%s: its control_dt_s %.9g s is not the log's period %.9g s: give --dt %.9g\n", path,
                sc.control_dt_s, dt_s, sc.control_dt_s);
        return -1;
    }
    sim_setup_gyro_filter(&sc, cfg);
    cfg->channels = 3;
    return 0;
}

/* One row: the rms (deg/s) in the bands and the vibration band of `out`;
 * with `in`, the attenuation from it (dB, vibration band and above 20 Hz)
 * and the phase cost at the crossover (deg, a lag positive) with the delay
 * it is (ms). */
static void print_row(const char *label, const sim_spectrum_t *in, const sim_spectrum_t *out, double lo_hz,
                      double hi_hz, double phase_deg, double wc_rad_s)
{
    printf("  %-16s", label);
    static const double edges[] = {0.0, 20.0, 100.0, INFINITY};
    for (int b = 0; b < 3; ++b) {
        printf(" %8.4f", RAD2DEG * sim_spectrum_band_rms(out, edges[b], edges[b + 1]));
    }
    printf(" %8.4f", RAD2DEG * sim_spectrum_band_rms(out, lo_hz, hi_hz));
    if (in == NULL) {
        printf("\n");
        return;
    }
    printf(" %7.1f %7.1f %7.1f %8.2f\n", sim_filter_measured_attenuation_db(in, out, lo_hz, hi_hz),
           sim_filter_measured_attenuation_db(in, out, LADRC_MARGINS_NOISE_CORNER_HZ, INFINITY), phase_deg,
           1e3 * sim_phase_delay_s(phase_deg, wc_rad_s));
}

/* Everything after the log is prepared: 0, or 2 after saying why. */
static int run(const options_t *o, sim_log_noise_t *n, char *err, size_t err_len)
{
    if (sim_log_noise_measure(&o->log, o->crossover_rad_s, n, err, err_len) != 0) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    for (int i = 0; i < 3; ++i) {
        char outliers[512];
        if (sim_log_outliers_describe(&n->outliers, i, outliers, sizeof outliers) > 0) {
            printf("%s%s (repaired before the spectra)\n", sim_log_outliers_many(&n->outliers, i) ? "warning: " : "",
                   outliers);
        }
    }
    const int raw = (n->has & SIM_LOG_HAS_GYRO_RAW) != 0;
    const sim_spectrum_t *input = raw ? n->gyro_raw : n->gyro;
    const double rotor_hz = sim_log_noise_rotor_hz(n);
    static sim_filter_proposal_t p;
    if (sim_filter_propose(input, n->dt_s, rotor_hz, n->rotors, o->crossover_rad_s, &p, err, err_len) != 0) {
        fprintf(stderr, "%s: %s\n", o->log.path, err);
        return 2;
    }
    ladrc_gyro_filter_config_t cfg = p.cfg;
    const char *source = "proposed from the log's spectrum";
    if (o->filter_from != NULL) {
        if (stage_from_scenario(o->filter_from, n->dt_s, &cfg) != 0) {
            return 2;
        }
        source = o->filter_from;
    } else if (o->given) {
        cfg = o->cfg;
        cfg.dt_s = (ladrc_real_t)n->dt_s;
        source = "given";
    }
    if (cfg.rpm_rotors > 0) {
        if (!(n->has & SIM_LOG_HAS_ROTOR_HZ) || n->rotors == 0) {
            fprintf(stderr,
                    "%s: RPM notches need the rotors' speed: the log has none (map rotor_hz[i], e.g. "
                    "Betaflight's eRPM[i] or PX4's esc_status)\n",
                    o->log.path);
            return 2;
        }
        cfg.rpm_rotors = (uint8_t)n->rotors; /* as many as the log reports */
    }
    static ladrc_gyro_filter_t f;
    const ladrc_status_t st = ladrc_gyro_filter_init(&f, &cfg);
    if (st != LADRC_OK) {
        fprintf(stderr, "ladrc_filter: the stage (%s) is refused: %s\n", source, ladrc_status_str(st));
        return 2;
    }
    /* the second pass: the stage over the input */
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(&o->log, &lerr);
    if (log == NULL) {
        sim_log_error_format(&lerr, err, err_len);
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    /* the input as the noise pass took it: its outliers repaired */
    sim_log_despike_t *despike = sim_log_despike_new(n->has);
    if (despike == NULL) {
        fprintf(stderr, "ladrc_filter: out of memory\n");
        sim_log_close(log);
        return 2;
    }
    FILE *csv = NULL;
    static sim_staged_file_t series; /* --out, put in place once whole */
    if (o->out != NULL) {
        const char *const inputs[] = {o->log.path, o->filter_from};
        if (sim_staged_file_open(&series, o->out, inputs, 2, err, err_len) != 0) {
            fprintf(stderr, "ladrc_filter: --out: %s\n", err);
            sim_log_despike_free(despike);
            sim_log_close(log);
            return 2;
        }
        csv = series.f;
        fprintf(csv, "t_s,in_roll_rad_s,in_pitch_rad_s,in_yaw_rad_s,out_roll_rad_s,out_pitch_rad_s,out_yaw_rad_s\n");
    }
    static sim_spectrum_t out_spectrum[3];
    static sim_phase_probe_t probe[3];
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_init(&out_spectrum[i], 1.0 / n->dt_s);
        sim_phase_probe_init(&probe[i], o->crossover_rad_s, n->dt_s);
    }
    sim_log_sample_t s;
    int rc, first = 1;
    long long faults = 0;
    while ((rc = sim_log_next_repaired(log, despike, &s, &lerr)) == 1) {
        ladrc_real_t in[3], out[3];
        for (int i = 0; i < 3; ++i) {
            in[i] = (ladrc_real_t)(raw ? s.gyro_raw_rad_s[i] : s.gyro_rad_s[i]);
        }
        if (first) {
            ladrc_gyro_filter_reset(&f, in); /* at rest on the first sample: no start-up transient */
            first = 0;
        }
        if (cfg.rpm_rotors > 0) {
            ladrc_real_t hz[LADRC_GYRO_FILTER_MAX_ROTORS];
            for (int m = 0; m < (int)LADRC_GYRO_FILTER_MAX_ROTORS; ++m) {
                hz[m] = (ladrc_real_t)(m < s.n_motors ? s.rotor_hz[m] : 0.0);
            }
            faults += ladrc_gyro_filter_set_rotor_hz(&f, hz) != LADRC_FAULT_NONE;
        }
        faults += ladrc_gyro_filter_step(&f, in, out) != LADRC_FAULT_NONE;
        for (int i = 0; i < 3; ++i) {
            sim_spectrum_push(&out_spectrum[i], (double)out[i]);
            sim_phase_probe_push(&probe[i], (double)in[i], (double)out[i]);
        }
        if (csv != NULL) {
            fprintf(csv, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", s.t_s, (double)in[0], (double)in[1], (double)in[2],
                    (double)out[0], (double)out[1], (double)out[2]);
        }
    }
    if (rc < 0) {
        sim_log_error_format(&lerr, err, err_len);
        fprintf(stderr, "%s\n", err);
    }
    sim_log_despike_free(despike);
    sim_log_close(log);
    if (csv != NULL && rc < 0) {
        sim_staged_file_abort(&series);
        return 2;
    }
    if (csv != NULL && sim_staged_file_commit(&series, err, err_len) != 0) {
        fprintf(stderr, "ladrc_filter: --out: %s\n", err);
        return 2;
    }
    if (rc < 0) {
        return 2;
    }

    printf("%s: %lld ticks at %.4g s, the gyro %s its filters%s\n", o->log.path, n->ticks, n->dt_s,
           raw ? "before" : "(no gyro before", raw ? "" : ")");
    printf("stage (%s): low-pass ", source);
    if (cfg.lpf_order > 0) {
        printf("order %u at %.1f Hz", (unsigned)cfg.lpf_order, (double)cfg.lpf_cutoff_hz);
    } else {
        printf("none");
    }
    printf(", %u notch(es)", (unsigned)cfg.n_notches);
    for (int k = 0; k < cfg.n_notches; ++k) {
        printf("%s%.1f", k == 0 ? " at " : " ", (double)cfg.notch_hz[k]);
    }
    if (cfg.n_notches > 0) {
        printf(" Hz Q %.3g", (double)cfg.notch_q);
    }
    if (cfg.rpm_rotors > 0) {
        printf(", RPM notches: %u harmonics Q %.3g (rotors' mean %.1f Hz)", (unsigned)cfg.rpm_harmonics,
               (double)cfg.rpm_q, rotor_hz);
    }
    printf("\nvibration band %.1f-%.1f Hz (%s); delay and phase at %.3g rad/s; rms in deg/s\n", p.band_lo_hz,
           p.band_hi_hz, p.n_lines > 0 ? "the lines' span" : "no lines: the floor band", o->crossover_rad_s);
    if (faults > 0) {
        printf("warning: the stage raised a fault on %lld ticks (a sample or rotor speed not finite)\n", faults);
    }
    printf("  %-16s %8s %8s %8s %8s %7s %7s %7s %8s\n", "", "0-20Hz", "20-100Hz", ">100Hz", "vib", "att dB", ">20 dB",
           "deg", "delay ms");
    for (int i = 0; i < 3; ++i) {
        printf("%s\n", AXIS[i]);
        print_row("input", NULL, &input[i], p.band_lo_hz, p.band_hi_hz, NAN, o->crossover_rad_s);
        print_row("this stage", &input[i], &out_spectrum[i], p.band_lo_hz, p.band_hi_hz,
                  -sim_phase_probe_rad(&probe[i]) * RAD2DEG, o->crossover_rad_s);
        if (raw) {
            print_row("the log's chain", &n->gyro_raw[i], &n->gyro[i], p.band_lo_hz, p.band_hi_hz,
                      sim_log_noise_chain_phase_deg(n, i), o->crossover_rad_s);
        }
    }
    printf("this stage's response at %.3g rad/s: %.1f deg%s (measured above from the streams)\n", o->crossover_rad_s,
           sim_filter_phase_cost_deg(&cfg, rotor_hz, o->crossover_rad_s),
           cfg.rpm_rotors > 0 ? ", RPM notches at the rotors' mean speed" : "");
    return 0;
}

int main(int argc, char **argv)
{
    static options_t o;
    if (parse_args(argc, argv, &o) != 0) {
        return 2;
    }
    static sim_log_noise_t n;
    char err[1024];
    static sim_log_prepared_t prepared; /* a binary log decoded into a temporary folder */
    const char *const inputs[] = {o.log.path, o.filter_from};
    if (o.out != NULL && sim_staged_check_file(o.out, inputs, 2, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_filter: --out: %s\n", err);
        return 2;
    }
    sim_log_error_t lerr;
    if (sim_log_prepare(&o.log, o.format_given, &prepared, NULL, NULL, &lerr) != 0) {
        sim_log_error_format(&lerr, err, sizeof err);
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    const int rc = run(&o, &n, err, sizeof err);
    sim_log_prepared_remove(&prepared);
    return rc;
}
