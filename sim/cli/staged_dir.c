/* SPDX-License-Identifier: BSD-3-Clause */
/* An output folder written all at once (staged_dir.h). */
#define _POSIX_C_SOURCE 200809L
#include "staged_dir.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* stage/name into buf (len > 0), with what a signal handler may call. */
static int join(const char *stage, const char *name, char *buf, size_t len)
{
    const size_t a = strlen(stage), b = strlen(name);
    if (a + 1 + b >= len) {
        return -1;
    }
    memcpy(buf, stage, a);
    buf[a] = '/';
    memcpy(buf + a + 1, name, b + 1);
    return 0;
}

int sim_staged_check_input(const char *dir, const char *const *names, int n, const char *input, char *err,
                           size_t err_len)
{
    struct stat in, out;
    if (input == NULL || stat(input, &in) != 0) {
        return 0;
    }
    for (int k = 0; k < n; ++k) {
        char path[SIM_STAGED_PATH_LEN];
        if (join(dir, names[k], path, sizeof path) == 0 && stat(path, &out) == 0 && out.st_dev == in.st_dev &&
            out.st_ino == in.st_ino) {
            snprintf(err, err_len, "%s: the input is the output %s of this run, which would replace it", input, path);
            return -1;
        }
    }
    return 0;
}

int sim_staged_check_inputs(const char *dir, const char *const *names, int n, const char *const *inputs, int n_inputs,
                            char *err, size_t err_len)
{
    for (int k = 0; k < n_inputs; ++k) {
        if (inputs[k] != NULL && inputs[k][0] != '\0' &&
            sim_staged_check_input(dir, names, n, inputs[k], err, err_len) != 0) {
            return -1;
        }
    }
    return 0;
}

int sim_staged_check_file(const char *path, const char *const *inputs, int n_inputs, char *err, size_t err_len)
{
    const char *slash = strrchr(path, '/');
    const char *name = slash != NULL ? slash + 1 : path;
    if (name[0] == '\0' || strlen(path) >= SIM_STAGED_PATH_LEN) {
        snprintf(err, err_len, "'%s': not a usable file name", path);
        return -1;
    }
    char dir[SIM_STAGED_PATH_LEN];
    const int dir_len = slash == NULL || slash == path ? 1 : (int)(slash - path); /* ".", "/" or the folder */
    snprintf(dir, sizeof dir, "%.*s", dir_len, slash == NULL ? "." : path);
    return sim_staged_check_inputs(dir, &name, 1, inputs, n_inputs, err, err_len);
}

int sim_staged_file_open(sim_staged_file_t *s, const char *path, const char *const *inputs, int n_inputs, char *err,
                         size_t err_len)
{
    memset(s, 0, sizeof *s);
    if (sim_staged_check_file(path, inputs, n_inputs, err, err_len) != 0) {
        return -1;
    }
    snprintf(s->final, sizeof s->final, "%s", path);
    snprintf(s->tmp, sizeof s->tmp, "%s.partial-%ld", path, (long)getpid());
    s->f = fopen(s->tmp, "w");
    if (s->f == NULL) {
        snprintf(err, err_len, "%s: cannot write: %s", path, strerror(errno));
        return -1;
    }
    return 0;
}

int sim_staged_file_commit(sim_staged_file_t *s, char *err, size_t err_len)
{
    const int failed = s->f == NULL || (ferror(s->f) | fclose(s->f)) != 0;
    s->f = NULL;
    if (failed || rename(s->tmp, s->final) != 0) {
        snprintf(err, err_len, "%s: %s: %s", s->final, failed ? "write failed" : "cannot rename into place",
                 strerror(errno));
        unlink(s->tmp);
        return -1;
    }
    return 0;
}

void sim_staged_file_abort(sim_staged_file_t *s)
{
    if (s->f != NULL) {
        fclose(s->f);
        s->f = NULL;
        unlink(s->tmp);
    }
}

/* The folder `path` without trailing slashes (the root kept). */
static int trimmed(const char *path, char *buf, size_t len)
{
    if (snprintf(buf, len, "%s", path) >= (int)len || buf[0] == '\0') {
        return -1;
    }
    for (size_t n = strlen(buf); n > 1 && buf[n - 1] == '/'; --n) {
        buf[n - 1] = '\0';
    }
    return 0;
}

/* mkdir -p of the folders above `final` that are missing, each recorded. */
static int make_parents(sim_staged_dir_t *s)
{
    char buf[SIM_STAGED_PATH_LEN];
    snprintf(buf, sizeof buf, "%s", s->final);
    char *last = strrchr(buf, '/');
    if (last == NULL || last == buf) {
        return 0;
    }
    *last = '\0';
    for (char *p = buf + 1;; ++p) {
        const char c = *p;
        if (c == '/' || c == '\0') {
            *p = '\0';
            struct stat st;
            if (stat(buf, &st) != 0) {
                if (s->n_parents >= SIM_STAGED_MAX_PARENTS) {
                    return -1;
                }
                if (mkdir(buf, 0777) == 0) {
                    snprintf(s->parents[s->n_parents++], sizeof s->parents[0], "%s", buf);
                } else if (errno != EEXIST || stat(buf, &st) != 0 || !S_ISDIR(st.st_mode)) {
                    return -1; /* EEXIST: another run made it since the stat; it is not ours to remove */
                }
            } else if (!S_ISDIR(st.st_mode)) {
                errno = ENOTDIR;
                return -1;
            }
            *p = c;
        }
        if (c == '\0') {
            return 0;
        }
    }
}

int sim_staged_open(sim_staged_dir_t *s, const char *final, char *err, size_t err_len)
{
    memset(s, 0, sizeof *s);
    if (trimmed(final, s->final, sizeof s->final) != 0) {
        snprintf(err, err_len, "'%s': not a usable folder name", final);
        return -1;
    }
    struct stat st;
    if (stat(s->final, &st) == 0) {
        if (!S_ISDIR(st.st_mode)) {
            snprintf(err, err_len, "%s: not a folder", s->final);
            return -1;
        }
        s->existed = 1;
        if (snprintf(s->stage, sizeof s->stage, "%s/.partial-XXXXXX", s->final) >= (int)sizeof s->stage) {
            snprintf(err, err_len, "%s: path too long", s->final);
            return -1;
        }
    } else {
        const char *base = strrchr(s->final, '/');
        const int parent_len = base != NULL ? (int)(base - s->final) : 0;
        if (snprintf(s->stage, sizeof s->stage, "%.*s%s.%s.partial-XXXXXX", parent_len, s->final,
                     base != NULL ? "/" : "", base != NULL ? base + 1 : s->final) >= (int)sizeof s->stage) {
            snprintf(err, err_len, "%s: path too long", s->final);
            return -1;
        }
        s->open = 1; /* the parents made are removed on failure */
        if (make_parents(s) != 0) {
            snprintf(err, err_len, "cannot create '%s': %s", s->final, strerror(errno));
            sim_staged_abort(s);
            return -1;
        }
    }
    if (mkdtemp(s->stage) == NULL) {
        snprintf(err, err_len, "cannot create a folder beside '%s': %s", s->final, strerror(errno));
        s->stage[0] = '\0';
        sim_staged_abort(s);
        return -1;
    }
    s->open = 1;
    const mode_t mask = umask(0); /* mkdtemp's folder is private: the output folder as mkdir makes one */
    umask(mask);
    chmod(s->stage, 0777 & ~mask);
    return 0;
}

const char *sim_staged_path(sim_staged_dir_t *s, const char *name, char *buf, size_t len)
{
    int k = 0;
    while (k < s->n_files && strcmp(s->names[k], name) != 0) {
        ++k;
    }
    if (k == s->n_files) {
        if (k >= SIM_STAGED_MAX_FILES || strlen(name) >= sizeof s->names[0] ||
            strlen(s->stage) + 1 + strlen(name) >= SIM_STAGED_PATH_LEN) {
            return NULL;
        }
        snprintf(s->names[k], sizeof s->names[k], "%s", name);
        s->n_files = k + 1; /* the abort sees it from here on */
    }
    return join(s->stage, name, buf, len) == 0 ? buf : NULL;
}

const char *sim_staged_shown(const sim_staged_dir_t *s, const char *path, char *buf, size_t len)
{
    const size_t n = strlen(s->stage);
    if (n > 0 && strncmp(path, s->stage, n) == 0 && (path[n] == '/' || path[n] == '\0')) {
        snprintf(buf, len, "%s%s", s->final, path + n);
        return buf;
    }
    return path;
}

int sim_staged_commit(sim_staged_dir_t *s, const char *const *owned, int n_owned, char *err, size_t err_len)
{
    char path[SIM_STAGED_PATH_LEN + 80];
    if (!s->existed) {
        if (rename(s->stage, s->final) != 0) {
            snprintf(err, err_len, "cannot rename the outputs into '%s': %s", s->final, strerror(errno));
            sim_staged_abort(s);
            return -1;
        }
        s->open = 0;
        return 0;
    }
    int moved[SIM_STAGED_MAX_FILES] = {0};
    for (int k = 0; k < s->n_files; ++k) {
        char staged[SIM_STAGED_PATH_LEN];
        snprintf(path, sizeof path, "%s/%s", s->final, s->names[k]);
        moved[k] = join(s->stage, s->names[k], staged, sizeof staged) == 0 &&
                   access(staged, F_OK) == 0; /* a name registered but not written: none */
        if (moved[k] && rename(staged, path) != 0) {
            snprintf(err, err_len, "cannot rename '%s' into place: %s", path, strerror(errno));
            sim_staged_abort(s);
            return -1;
        }
    }
    for (int k = 0; k < n_owned; ++k) { /* the earlier run's outputs this run did not write */
        int written = 0;
        for (int j = 0; j < s->n_files; ++j) {
            written |= moved[j] && strcmp(s->names[j], owned[k]) == 0;
        }
        snprintf(path, sizeof path, "%s/%s", s->final, owned[k]);
        if (!written && unlink(path) != 0 && errno != ENOENT) {
            snprintf(err, err_len, "cannot remove the earlier run's '%s': %s", path, strerror(errno));
            sim_staged_abort(s);
            return -1;
        }
    }
    rmdir(s->stage);
    s->open = 0;
    return 0;
}

void sim_staged_abort(sim_staged_dir_t *s)
{
    if (!s->open) {
        return;
    }
    s->open = 0;
    for (int k = 0; k < s->n_files; ++k) {
        char staged[SIM_STAGED_PATH_LEN];
        if (join(s->stage, s->names[k], staged, sizeof staged) == 0) {
            unlink(staged);
        }
    }
    if (s->stage[0] != '\0') {
        rmdir(s->stage);
    }
    for (int k = s->n_parents - 1; k >= 0; --k) {
        rmdir(s->parents[k]);
    }
}
