/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * An output folder written all at once: a command's files go to a staging
 * folder beside (or, when the folder is there already, inside) the output
 * folder and are renamed into place only when the run succeeds. A run that
 * fails, is refused or is interrupted leaves nothing: not its files, not
 * the folder, not the parent folders it made. An earlier run's folder never
 * mixes with a new run's files: on success the earlier run's outputs that
 * the new run did not write are removed (only the names the command owns;
 * other files in the folder are left alone).
 *
 * sim_staged_abort only joins strings with memcpy, unlinks and removes
 * folders, so a signal handler may call it.
 */
#ifndef LADRC_SIM_STAGED_DIR_H
#define LADRC_SIM_STAGED_DIR_H

#include <stddef.h>
#include <stdio.h>

#define SIM_STAGED_PATH_LEN 4096
#define SIM_STAGED_MAX_FILES 96 /* a scenario's outputs: 3 + 8 controllers x 11 files */
#define SIM_STAGED_NAME_LEN 64
#define SIM_STAGED_MAX_PARENTS 16

typedef struct {
    char final[SIM_STAGED_PATH_LEN]; /* the output folder */
    char stage[SIM_STAGED_PATH_LEN]; /* where the files are written until the commit */
    int existed;                     /* 1: the output folder was there before */
    int n_files;
    char names[SIM_STAGED_MAX_FILES][SIM_STAGED_NAME_LEN]; /* registered, in stage */
    int n_parents;                                         /* folders made above final, innermost last */
    char parents[SIM_STAGED_MAX_PARENTS][SIM_STAGED_PATH_LEN];
    volatile int open; /* 1 between open and commit or abort */
} sim_staged_dir_t;

/* 0 when no file the command owns in `dir` (names[0..n-1]) is the same file
 * (device and inode) as `input`, else -1 with the message in err: a run
 * would replace its own input. An input or a folder that is not there: 0. */
int sim_staged_check_input(const char *dir, const char *const *names, int n, const char *input, char *err,
                           size_t err_len);

/* sim_staged_check_input for each of inputs[0..n_inputs-1] (NULL or empty
 * entries skipped). */
int sim_staged_check_inputs(const char *dir, const char *const *names, int n, const char *const *inputs, int n_inputs,
                            char *err, size_t err_len);

/* 0 when the file at path is none of inputs[0..n_inputs-1], else -1 with
 * the message (also for a path that names no file: "dir/"). */
int sim_staged_check_file(const char *path, const char *const *inputs, int n_inputs, char *err, size_t err_len);

/* An output that is one file, written whole: to a temporary name beside
 * it, renamed into place by sim_staged_file_commit; a refusal or an abort
 * leaves nothing and the earlier file as it was. */
typedef struct {
    char final[SIM_STAGED_PATH_LEN];
    char tmp[SIM_STAGED_PATH_LEN + 32];
    FILE *f;
} sim_staged_file_t;

/* Refuses (-1 with the message) a path that is one of inputs[0..n_inputs-1],
 * else opens the temporary file: 0. */
int sim_staged_file_open(sim_staged_file_t *s, const char *path, const char *const *inputs, int n_inputs, char *err,
                         size_t err_len);

/* Closes and renames the file into place: 0, or -1 with the message (the
 * temporary file removed). */
int sim_staged_file_commit(sim_staged_file_t *s, char *err, size_t err_len);

/* Closes and removes the temporary file; nothing when not open. */
void sim_staged_file_abort(sim_staged_file_t *s);

/* Makes the staging folder for the output folder final (the parent folders
 * it needs, which an abort removes again). Returns 0, or -1 with the message
 * (final is a file, a folder cannot be made). */
int sim_staged_open(sim_staged_dir_t *s, const char *final, char *err, size_t err_len);

/* The staging path of output `name` (registered for the commit and the
 * abort) in buf; NULL when too many names or too long. */
const char *sim_staged_path(sim_staged_dir_t *s, const char *name, char *buf, size_t len);

/* The path `path` within the staging folder shown as within the output
 * folder (messages name where the file will be); other paths unchanged. */
const char *sim_staged_shown(const sim_staged_dir_t *s, const char *path, char *buf, size_t len);

/* Renames the registered files into the output folder and removes the
 * earlier run's outputs among owned[0..n_owned-1] not written this time.
 * Returns 0, or -1 with the message (then the abort has run). */
int sim_staged_commit(sim_staged_dir_t *s, const char *const *owned, int n_owned, char *err, size_t err_len);

/* Removes the registered files, the staging folder and the parents made;
 * nothing when not open. Async-signal-safe. */
void sim_staged_abort(sim_staged_dir_t *s);

#endif
