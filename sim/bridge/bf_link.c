/* SPDX-License-Identifier: BSD-3-Clause */
/* A Betaflight SITL process and its lockstep UDP link (bf_link.h). */
#define _XOPEN_SOURCE 700
#include "bf_link.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#define BOOT_RETRY_MS 50
#define STOP_GRACE_MS 500
#define SITL_OUTPUT "sitl.out"
/* A motor output outside [0, 1] by more than this is garbage; within it,
 * rounding of the SITL's (value - idle) / range, clamped. */
#define MOTOR_SLACK 1e-3

/* The SITL's ports are the host's: one link at a time in this process. */
static pthread_mutex_t link_lock = PTHREAD_MUTEX_INITIALIZER;

static double wall_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* The last non-empty line of the SITL's output, or "(no output)". */
void bf_link_last_output(const bf_link_t *l, char *out, size_t out_len)
{
    char path[BF_LINK_PATH_LEN + 16], tail[2048];
    snprintf(path, sizeof path, "%s/%s", l->work, SITL_OUTPUT);
    snprintf(out, out_len, "(no output)");
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return;
    }
    long n = 0;
    if (fseek(f, 0, SEEK_END) == 0) {
        const long size = ftell(f);
        const long from = size > (long)sizeof tail - 1 ? size - (long)sizeof tail + 1 : 0;
        if (fseek(f, from, SEEK_SET) == 0) {
            n = (long)fread(tail, 1, sizeof tail - 1, f);
        }
    }
    fclose(f);
    while (n > 0 && (tail[n - 1] == '\n' || tail[n - 1] == '\r' || tail[n - 1] == ' ')) {
        --n;
    }
    tail[n] = '\0';
    const char *start = strrchr(tail, '\n');
    start = start == NULL ? tail : start + 1;
    if (*start != '\0') {
        snprintf(out, out_len, "'%s'", start);
    }
}

/* Why the SITL did not answer: dead (its exit and last output) or silent. */
static void no_answer(bf_link_t *l, const char *waited, double t_s, char *err, size_t err_len)
{
    char last[600];
    bf_link_last_output(l, last, sizeof last);
    int status = 0;
    if (l->pid > 0 && waitpid(l->pid, &status, WNOHANG) == l->pid) {
        l->pid = 0;
        if (WIFEXITED(status)) {
            snprintf(
                err, err_len,
                "Betaflight SITL %s/%s exited with status %d at its time %.6g s (exchange %ld); its last output: %s",
                l->dir, BF_SITL_PROGRAM, WEXITSTATUS(status), t_s, l->exchanges, last);
        } else {
            snprintf(err, err_len,
                     "Betaflight SITL %s/%s killed by signal %d at its time %.6g s (exchange %ld); its last output: %s",
                     l->dir, BF_SITL_PROGRAM, WIFSIGNALED(status) ? WTERMSIG(status) : 0, t_s, l->exchanges, last);
        }
        return;
    }
    snprintf(err, err_len,
             "Betaflight SITL %s/%s: no motor packet within %s of the state packet at its time %.6g s (exchange %ld); "
             "its last output: %s",
             l->dir, BF_SITL_PROGRAM, waited, t_s, l->exchanges, last);
}

/* Sends rc then the state to the SITL's ports; 0, or -1 with the message. */
static int send_pair(bf_link_t *l, const bf_rc_t *rc, const bf_fdm_t *s, char *err, size_t err_len)
{
    unsigned char rc_bytes[BF_RC_BYTES], fdm_bytes[BF_FDM_BYTES];
    bf_fdm_encode(s, fdm_bytes);
    struct sockaddr_in to;
    memset(&to, 0, sizeof to);
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    to.sin_port = htons(BF_PORT_RC);
    if (rc != NULL) {
        bf_rc_encode(rc, rc_bytes);
    }
    if (rc != NULL && sendto(l->sock, rc_bytes, sizeof rc_bytes, 0, (const struct sockaddr *)&to, sizeof to) < 0) {
        snprintf(err, err_len, "Betaflight SITL link: sending RC to port %d: %s", BF_PORT_RC, strerror(errno));
        return -1;
    }
    to.sin_port = htons(BF_PORT_FDM);
    if (sendto(l->sock, fdm_bytes, sizeof fdm_bytes, 0, (const struct sockaddr *)&to, sizeof to) < 0) {
        snprintf(err, err_len, "Betaflight SITL link: sending the state to port %d: %s", BF_PORT_FDM, strerror(errno));
        return -1;
    }
    return 0;
}

/* Motor packets that came before they were asked for: dropped, counted. */
static void drain(bf_link_t *l)
{
    unsigned char buf[512];
    while (recv(l->sock, buf, sizeof buf, MSG_DONTWAIT) >= 0) {
        ++l->stale;
    }
}

/* Waits up to wait_ms for a motor packet: 1 with it checked, 0 on none, -1
 * with the message on a bad one. */
static int await_motors(bf_link_t *l, int wait_ms, double t_s, float motor[BF_MOTORS], char *err, size_t err_len)
{
    const double deadline = wall_ms() + wait_ms;
    for (;;) {
        const double left = deadline - wall_ms();
        if (left <= 0.0) {
            return 0;
        }
        struct pollfd p = {.fd = l->sock, .events = POLLIN, .revents = 0};
        const int ready = poll(&p, 1, (int)ceil(left));
        if (ready < 0 && errno == EINTR) {
            continue;
        }
        if (ready <= 0) {
            return 0;
        }
        unsigned char buf[512];
        const ssize_t n = recv(l->sock, buf, sizeof buf, 0);
        if (n < 0) {
            continue;
        }
        if (bf_motor_decode(buf, (size_t)n, motor) != 0) {
            snprintf(err, err_len,
                     "Betaflight SITL %s: a packet of %ld bytes on port %d at its time %.6g s (exchange %ld), where "
                     "the motor packet has %d",
                     l->dir, (long)n, BF_PORT_MOTORS, t_s, l->exchanges, BF_MOTOR_BYTES);
            return -1;
        }
        for (int m = 0; m < BF_MOTORS; ++m) {
            const double v = (double)motor[m];
            if (!(v >= -MOTOR_SLACK && v <= 1.0 + MOTOR_SLACK)) {
                snprintf(err, err_len,
                         "Betaflight SITL %s: motor %d output %g at its time %.6g s (exchange %ld), outside [0, 1]",
                         l->dir, m + 1, v, t_s, l->exchanges);
                return -1;
            }
            motor[m] = v < 0.0 ? 0.0f : v > 1.0 ? 1.0f : motor[m];
        }
        return 1;
    }
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    (void)remove(path);
    return 0;
}

/* Copies src to dst; 0, or -1. */
static int copy_file(const char *src, const char *dst)
{
    FILE *in = fopen(src, "rb");
    if (in == NULL) {
        return -1;
    }
    FILE *out = fopen(dst, "wb");
    int rc = out == NULL ? -1 : 0;
    char buf[8192];
    size_t n;
    while (rc == 0 && (n = fread(buf, 1, sizeof buf, in)) > 0) {
        rc = fwrite(buf, 1, n, out) == n ? 0 : -1;
    }
    rc = ferror(in) ? -1 : rc;
    fclose(in);
    if (out != NULL && fclose(out) != 0) {
        rc = -1;
    }
    return rc;
}

/* The child: into the working folder, its output to a file, the program. */
static void exec_sitl(const char *work, const char *program)
{
#ifdef __linux__
    (void)prctl(PR_SET_PDEATHSIG, SIGKILL); /* never outlives the simulator */
#endif
    if (chdir(work) != 0) {
        _exit(126);
    }
    const int fd = open(SITL_OUTPUT, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
        (void)dup2(fd, STDOUT_FILENO);
        (void)dup2(fd, STDERR_FILENO);
        close(fd);
    }
    execl(program, program, (char *)NULL);
    fprintf(stderr, "cannot run %s: %s\n", program, strerror(errno));
    _exit(127);
}

/* The program's absolute path, its configuration checked; 0, or -1. */
static int find_program(const char *dir, char *program, size_t len, char *err, size_t err_len)
{
    char real[BF_LINK_PATH_LEN];
    if (realpath(dir, real) == NULL) {
        snprintf(err, err_len, "Betaflight SITL folder %s: %s (tools/betaflight_sitl.sh CHECKOUT %s builds one)", dir,
                 strerror(errno), dir);
        return -1;
    }
    snprintf(program, len, "%s/%s", real, BF_SITL_PROGRAM);
    if (access(program, X_OK) != 0) {
        snprintf(err, err_len, "%s/%s: %s (tools/betaflight_sitl.sh CHECKOUT %s builds it)", dir, BF_SITL_PROGRAM,
                 strerror(errno), dir);
        return -1;
    }
    char config[BF_LINK_PATH_LEN + 16];
    snprintf(config, sizeof config, "%s/%s", real, BF_SITL_CONFIG);
    if (access(config, R_OK) != 0) {
        snprintf(err, err_len, "%s/%s: %s (the SITL's configuration: tools/betaflight_sitl.sh writes it)", dir,
                 BF_SITL_CONFIG, strerror(errno));
        return -1;
    }
    return 0;
}

/* The motor port, bound; 0, or -1 with the message. */
static int bind_motor_port(bf_link_t *l, char *err, size_t err_len)
{
    l->sock = socket(AF_INET, SOCK_DGRAM, 0);
    if (l->sock < 0) {
        snprintf(err, err_len, "Betaflight SITL link: UDP socket: %s", strerror(errno));
        return -1;
    }
    struct sockaddr_in me;
    memset(&me, 0, sizeof me);
    me.sin_family = AF_INET;
    me.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    me.sin_port = htons(BF_PORT_MOTORS);
    if (bind(l->sock, (const struct sockaddr *)&me, sizeof me) != 0) {
        snprintf(err, err_len, "Betaflight SITL link: UDP port %d: %s (another Betaflight SITL bridge running?)",
                 BF_PORT_MOTORS, strerror(errno));
        return -1;
    }
    return 0;
}

int bf_link_open(bf_link_t *l, const char *dir, int timeout_ms, const bf_rc_t *rc, const bf_fdm_t *boot,
                 float motor[BF_MOTORS], char *err, size_t err_len)
{
    memset(l, 0, sizeof *l);
    l->sock = -1;
    l->timeout_ms = timeout_ms > 0 ? timeout_ms : BF_LINK_TIMEOUT_MS_DEFAULT;
    snprintf(l->dir, sizeof l->dir, "%s", dir);
    char program[BF_LINK_PATH_LEN + 32];
    if (find_program(dir, program, sizeof program, err, err_len) != 0) {
        return -1;
    }
    pthread_mutex_lock(&link_lock);
    l->locked = 1;
    if (bind_motor_port(l, err, err_len) != 0) {
        bf_link_close(l);
        return -1;
    }
    const char *tmp = getenv("TMPDIR");
    snprintf(l->work, sizeof l->work, "%s/ladrc-betaflight-XXXXXX", tmp != NULL && *tmp != '\0' ? tmp : "/tmp");
    char config_from[BF_LINK_PATH_LEN + 16], config_to[BF_LINK_PATH_LEN + 16];
    if (mkdtemp(l->work) == NULL) {
        snprintf(err, err_len, "Betaflight SITL: a working folder %s: %s", l->work, strerror(errno));
        l->work[0] = '\0';
        bf_link_close(l);
        return -1;
    }
    snprintf(config_from, sizeof config_from, "%s/%s", dir, BF_SITL_CONFIG);
    snprintf(config_to, sizeof config_to, "%s/%s", l->work, BF_SITL_CONFIG);
    if (copy_file(config_from, config_to) != 0) {
        snprintf(err, err_len, "Betaflight SITL: copying %s into %s: %s", config_from, l->work, strerror(errno));
        bf_link_close(l);
        return -1;
    }
    fflush(NULL);
    l->pid = fork();
    if (l->pid < 0) {
        l->pid = 0;
        snprintf(err, err_len, "Betaflight SITL: fork: %s", strerror(errno));
        bf_link_close(l);
        return -1;
    }
    if (l->pid == 0) {
        exec_sitl(l->work, program);
    }
    const double deadline = wall_ms() + BF_LINK_BOOT_TIMEOUT_MS;
    while (wall_ms() < deadline) {
        drain(l);
        if (send_pair(l, rc, boot, err, err_len) != 0) {
            bf_link_close(l);
            return -1;
        }
        const int got = await_motors(l, BOOT_RETRY_MS, boot->t_s, motor, err, err_len);
        if (got < 0) {
            bf_link_close(l);
            return -1;
        }
        if (got == 1) {
            /* the answers to the start's repeats come in now or never */
            const struct timespec settle = {0, 2 * BOOT_RETRY_MS * 1000000L};
            nanosleep(&settle, NULL);
            drain(l);
            ++l->exchanges;
            l->stale = 0;
            return 0;
        }
        int status;
        if (waitpid(l->pid, &status, WNOHANG) == l->pid) {
            l->pid = 0;
            char last[600];
            bf_link_last_output(l, last, sizeof last);
            snprintf(err, err_len, "Betaflight SITL %s/%s stopped while starting (%s %d); its last output: %s", dir,
                     BF_SITL_PROGRAM, WIFEXITED(status) ? "exit status" : "signal",
                     WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status), last);
            bf_link_close(l);
            return -1;
        }
    }
    no_answer(l, "its start (20 s)", boot->t_s, err, err_len);
    bf_link_close(l);
    return -1;
}

int bf_link_exchange(bf_link_t *l, const bf_rc_t *rc, const bf_fdm_t *s, float motor[BF_MOTORS], char *err,
                     size_t err_len)
{
    drain(l);
    if (send_pair(l, rc, s, err, err_len) != 0) {
        return -1;
    }
    const int got = await_motors(l, l->timeout_ms, s->t_s, motor, err, err_len);
    if (got == 1) {
        ++l->exchanges;
        return 0;
    }
    if (got == 0) {
        char waited[32];
        snprintf(waited, sizeof waited, "%d ms", l->timeout_ms);
        no_answer(l, waited, s->t_s, err, err_len);
    }
    return -1;
}

void bf_link_close(bf_link_t *l)
{
    if (l->pid > 0) {
        (void)kill(l->pid, SIGTERM);
        const double deadline = wall_ms() + STOP_GRACE_MS;
        int status, reaped = 0;
        while (!reaped && wall_ms() < deadline) {
            reaped = waitpid(l->pid, &status, WNOHANG) == l->pid;
            const struct timespec nap = {0, 2000000L};
            if (!reaped) {
                nanosleep(&nap, NULL);
            }
        }
        if (!reaped) {
            (void)kill(l->pid, SIGKILL);
            (void)waitpid(l->pid, &status, 0);
        }
        l->pid = 0;
    }
    if (l->sock >= 0) {
        close(l->sock);
        l->sock = -1;
    }
    if (l->work[0] != '\0') {
        (void)nftw(l->work, remove_entry, 8, FTW_DEPTH | FTW_PHYS);
        l->work[0] = '\0';
    }
    if (l->locked) {
        l->locked = 0;
        pthread_mutex_unlock(&link_lock);
    }
}
