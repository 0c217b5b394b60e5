/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Scenario files (scenario.h): the entry points of the parser. The text is
 * copied once and cut up in place by the reader (reader.c), which files each
 * value by the key table (schema.c) through the lexer (lexer.c); checks that
 * involve other keys (kind, duration_s, ideal rotors, the run's limits) run
 * once the whole file is read, the earliest of their errors kept; last, the
 * library initialises what the run would fly (checks.c), so that a value it
 * refuses is an error at its key.
 */
#include "scenario.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "parser.h"

/* name = the file name without directories and its last extension */
static void set_name(sim_scenario_t *sc, const char *path)
{
    const char *base = path;
    for (const char *s = path; *s != '\0'; ++s) {
        if (*s == '/' || *s == '\\') {
            base = s + 1;
        }
    }
    size_t len = strlen(base);
    const char *dot = strrchr(base, '.');
    if (dot != NULL && dot != base) {
        len = (size_t)(dot - base);
    }
    if (len == 0) {
        base = "scenario";
        len = strlen(base);
    }
    if (len >= SIM_NAME_LEN) {
        len = SIM_NAME_LEN - 1;
    }
    memcpy(sc->name, base, len);
    sc->name[len] = '\0';
}

static void copy_path(char *dst, const char *path)
{
    snprintf(dst, SIM_PATH_LEN, "%s", path);
}

static void position_of(const char *data, size_t at, int *line, int *column)
{
    size_t line_start = 0;
    *line = 1;
    for (size_t i = 0; i < at; ++i) {
        if (data[i] == '\n') {
            ++*line;
            line_start = i + 1;
        }
    }
    *column = (int)(at - line_start) + 1;
}

int sim_scenario_parse_buffer(sim_scenario_t *sc, const char *data, size_t len, const char *path,
                              sim_parse_error_t *err)
{
    return sim_scenario_parse_buffer_with(sc, data, len, path, NULL, 0, err);
}

int sim_scenario_parse_buffer_with(sim_scenario_t *sc, const char *data, size_t len, const char *path,
                                   const char *const *sets, int n_sets, sim_parse_error_t *err)
{
    sim_parse_error_t ignored;
    if (err == NULL) {
        err = &ignored;
    }
    if (path == NULL) {
        path = "";
    }
    memset(err, 0, sizeof *err);
    copy_path(err->path, path);
    if (sc == NULL || data == NULL) {
        snprintf(err->message, sizeof err->message, "no scenario or no text");
        return -1;
    }
    const char *nul = memchr(data, '\0', len);
    if (nul != NULL) {
        position_of(data, (size_t)(nul - data), &err->line, &err->column);
        snprintf(err->message, sizeof err->message, "unexpected NUL byte");
        return -1;
    }
    schema_set_defaults(sc);
    copy_path(sc->path, path);
    set_name(sc, path);

    parser_t *p = calloc(1, sizeof *p);
    char *copy = malloc(len + 1);
    if (p == NULL || copy == NULL) {
        free(p);
        free(copy);
        snprintf(err->message, sizeof err->message, "out of memory");
        return -1;
    }
    memcpy(copy, data, len);
    copy[len] = '\0';
    p->sc = sc;
    p->place.err = err;
    p->section = -1;

    int rc = reader_lines(p, copy);
    if (rc == 0 && n_sets > 0) {
        rc = reader_settings(p, sets, n_sets);
    }
    if (rc == 0) {
        checks_run(p);
        rc = p->checked ? -1 : 0;
    }
    if (rc == 0) {
        checks_finish(p);
    }
    err->first_set_line = p->first_set_line;
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        sc->controller_error[id].first_set_line = p->first_set_line;
    }
    free(copy);
    free(p);
    return rc;
}

int sim_scenario_parse(sim_scenario_t *sc, const char *text, const char *path, sim_parse_error_t *err)
{
    return sim_scenario_parse_buffer(sc, text, text != NULL ? strlen(text) : 0u, path, err);
}

int sim_scenario_set_controllers(sim_scenario_t *sc, const sim_controller_id_t *ids, int n, sim_parse_error_t *err)
{
    sim_parse_error_t ignored;
    if (err == NULL) {
        err = &ignored;
    }
    memset(err, 0, sizeof *err);
    if (sc == NULL || ids == NULL || n < 1 || n > SIM_MAX_CONTROLLERS) {
        snprintf(err->message, sizeof err->message, "expected 1 to %d controllers", SIM_MAX_CONTROLLERS);
        return -1;
    }
    copy_path(err->path, sc->path);
    for (int i = 0; i < n; ++i) {
        if ((int)ids[i] < 0 || ids[i] >= SIM_CTRL_COUNT) {
            snprintf(err->message, sizeof err->message, "unknown controller %d", (int)ids[i]);
            return -1;
        }
        for (int k = 0; k < i; ++k) {
            if (ids[k] == ids[i]) {
                snprintf(err->message, sizeof err->message, "controller '%s' listed twice",
                         sim_controller_name(ids[i]));
                return -1;
            }
        }
        if (sc->kind == SIM_KIND_ATTITUDE && sc->controller_error[ids[i]].line != 0) {
            *err = sc->controller_error[ids[i]];
            return -1;
        }
    }
    for (int i = 0; i < n; ++i) {
        sc->controllers[i] = ids[i];
    }
    sc->n_controllers = n;
    return 0;
}

int sim_scenario_load(sim_scenario_t *sc, const char *path, sim_parse_error_t *err)
{
    return sim_scenario_load_with(sc, path, NULL, 0, err);
}

int sim_scenario_load_with(sim_scenario_t *sc, const char *path, const char *const *sets, int n_sets,
                           sim_parse_error_t *err)
{
    sim_parse_error_t ignored;
    if (err == NULL) {
        err = &ignored;
    }
    memset(err, 0, sizeof *err);
    copy_path(err->path, path != NULL ? path : "");
    char *text = NULL;
    size_t len = 0;
    const int read = path != NULL ? ini_read_file(path, &text, &len) : -1;
    if (read != 0) {
        if (read == -1) {
            snprintf(err->message, sizeof err->message, "cannot open: %s", path != NULL ? strerror(errno) : "no path");
        } else {
            snprintf(err->message, sizeof err->message, "%s",
                     read == -2   ? "out of memory"
                     : read == -4 ? "larger than 16 MiB: not a scenario file"
                                  : "read error");
        }
        return -1;
    }
    const int rc = sim_scenario_parse_buffer_with(sc, text, len, path, sets, n_sets, err);
    free(text);
    return rc;
}
