/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ladrc_views: the field's views (step response, frequency response, noise
 * against throttle: log/response.h) of one or more flight logs side by side,
 * each under its source name, and a log's setpoints as a recorded series a
 * scenario flies (docs/flight-logs.md, "The field's views").
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli_number.h"
#include "cli/staged_dir.h"
#include "log/log_reference.h"
#include "log/log_views.h"

#define MAX_LOGS 16

static void usage(FILE *out)
{
    fputs("usage: ladrc_views --out DIR [--format F] [--map FIELD=SOURCE]... [--dt S] NAME=LOG...\n"
          "       ladrc_views --reference FILE [--seconds S] [--format F] [--map FIELD=SOURCE]... [--dt S] LOG\n"
          "  NAME=LOG          a log and its name in the CSVs (LOG: the log flown; a controller's name)\n"
          "  --format F        betaflight, px4 or generic: the form of the logs that follow (default betaflight)\n"
          "  --map F=SOURCE    a column for a field of the logs that follow (docs/flight-logs.md)\n"
          "  --dt S            the period to resample the logs that follow to (default: each log's row period)\n"
          "  --out DIR         writes step_response.csv, freq_response.csv, noise_throttle.csv and\n"
          "                    response_summary.csv there (tools/response_plot.py DIR draws them)\n"
          "  --reference FILE  writes the log's setpoints (reference angles, rad) as a recorded series\n"
          "                    for a scenario's [reference] series; --seconds S: its first S seconds\n"
          "Exit status 0; 2 for bad usage or a refused log (nothing written).\n",
          out);
}

int main(int argc, char **argv)
{
    static sim_views_input_t in[MAX_LOGS];
    int n = 0;
    sim_log_options_t cur;
    sim_log_options_default(&cur);
    const char *out = NULL, *reference = NULL;
    double seconds = 0.0;
    for (int a = 1; a < argc; ++a) {
        const char *arg = argv[a], *val = a + 1 < argc ? argv[a + 1] : NULL;
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            usage(stdout);
            return 0;
        }
        if (arg[0] == '-' && val == NULL) {
            fprintf(stderr, "ladrc_views: %s needs a value\n", arg);
            return 2;
        }
        if (strcmp(arg, "--format") == 0) {
            const int f = sim_log_format_parse(val);
            if (f < 0) {
                fprintf(stderr, "ladrc_views: --format: expected betaflight, px4 or generic, got '%s'\n", val);
                return 2;
            }
            cur.format = (sim_log_format_t)f;
            cur.n_map = 0; /* a form's mapping does not carry over to another form */
            ++a;
        } else if (strcmp(arg, "--map") == 0) {
            if (cur.n_map >= SIM_LOG_MAX_MAP) {
                fprintf(stderr, "ladrc_views: --map: at most %d items\n", SIM_LOG_MAX_MAP);
                return 2;
            }
            cur.map[cur.n_map++] = argv[++a];
        } else if (strcmp(arg, "--dt") == 0 || strcmp(arg, "--seconds") == 0) {
            if (sim_cli_number("ladrc_views", arg, val, arg[2] == 'd' ? &cur.dt_s : &seconds) != 0) {
                return 2;
            }
            ++a;
        } else if (strcmp(arg, "--out") == 0) {
            out = argv[++a];
        } else if (strcmp(arg, "--reference") == 0) {
            reference = argv[++a];
        } else if (arg[0] == '-') {
            fprintf(stderr, "ladrc_views: unknown option '%s'\n", arg);
            return 2;
        } else {
            const char *eq = strchr(arg, '=');
            if (n >= MAX_LOGS) {
                fprintf(stderr, "ladrc_views: at most %d logs\n", MAX_LOGS);
                return 2;
            }
            if (reference == NULL && (eq == NULL || eq == arg)) {
                fprintf(stderr, "ladrc_views: '%s': expected NAME=LOG\n", arg);
                return 2;
            }
            in[n].log = cur;
            const char *path = reference == NULL ? eq + 1 : arg;
            if (snprintf(in[n].log.path, sizeof in[n].log.path, "%s", path) >= (int)sizeof in[n].log.path) {
                fprintf(stderr, "ladrc_views: %s: path too long\n", path);
                return 2;
            }
            if (reference == NULL) {
                char *name = malloc((size_t)(eq - arg) + 1);
                if (name == NULL) {
                    return 2;
                }
                memcpy(name, arg, (size_t)(eq - arg));
                name[eq - arg] = '\0';
                in[n].source = name;
            }
            ++n;
        }
    }
    char err[1024];
    if (reference != NULL) {
        if (n != 1 || out != NULL) {
            fprintf(stderr, "ladrc_views: --reference takes one LOG and no --out\n");
            return 2;
        }
        double written_s;
        const char *const input = in[0].log.path;
        if (sim_staged_check_file(reference, &input, 1, err, sizeof err) != 0) {
            fprintf(stderr, "ladrc_views: --reference: %s: give another path\n", err);
            return 2;
        }
        if (sim_log_reference_write(&in[0].log, seconds, reference, &written_s, err, sizeof err) != 0) {
            fprintf(stderr, "%s\n", err);
            return 2;
        }
        printf("%s: %.3f s of setpoints from %s\n", reference, written_s, in[0].log.path);
        return 0;
    }
    if (out == NULL || n == 0) {
        usage(stderr);
        return 2;
    }
    const char *views[SIM_VIEWS_FILES], *inputs[MAX_LOGS];
    char path[SIM_STAGED_PATH_LEN];
    for (int k = 0; k < SIM_VIEWS_FILES; ++k) {
        views[k] = sim_log_views_file(k);
    }
    for (int i = 0; i < n; ++i) {
        inputs[i] = in[i].log.path;
    }
    static sim_staged_dir_t stage; /* the four files put in place together, or none */
    if (sim_staged_check_inputs(out, views, SIM_VIEWS_FILES, inputs, n, err, sizeof err) != 0 ||
        sim_staged_open(&stage, out, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_views: --out: %s\n", err);
        return 2;
    }
    for (int k = 0; k < SIM_VIEWS_FILES; ++k) {
        (void)sim_staged_path(&stage, views[k], path, sizeof path); /* registered: an abort removes it */
    }
    int rc = sim_log_views_write(in, n, stage.stage, stdout, err, sizeof err);
    for (int i = 0; i < n; ++i) {
        free((void *)in[i].source);
    }
    if (rc != 0) {
        sim_staged_abort(&stage);
    } else {
        rc = sim_staged_commit(&stage, views, SIM_VIEWS_FILES, err, sizeof err);
    }
    if (rc != 0) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    printf("outputs in %s (tools/response_plot.py %s draws them)\n", out, out);
    return 0;
}
