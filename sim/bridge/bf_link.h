/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A Betaflight SITL process and its UDP link, in lockstep: each exchange
 * sends the RC channels and one state packet and waits for the one motor
 * packet the SITL answers it with (its gyro and PID loop run once per state
 * packet when built with the lockstep option: tools/betaflight_sitl.sh).
 *
 * bf_link_open starts DIR/betaflight_SITL.elf in a fresh working folder
 * holding a copy of DIR/eeprom.bin (its configuration: every run starts from
 * the same one), its output in that folder's sitl.out, and waits for it to
 * answer. bf_link_close stops it and removes the folder. The SITL's ports
 * are fixed (bf_packet.h), so one link is open at a time in a process:
 * bf_link_open waits for the previous one to close; another process holding
 * the ports is an error.
 *
 * Every failure is a message naming the SITL, the exchange and the
 * simulator's time: the program or its configuration missing, the ports
 * taken, no answer within the timeout (the process alive or, with its exit
 * status and last output line, dead), a packet of the wrong size, a motor
 * output not a number or outside [0, 1].
 */
#ifndef LADRC_SIM_BF_LINK_H
#define LADRC_SIM_BF_LINK_H

#include <stddef.h>
#include <sys/types.h>

#include "bf_packet.h"

#define BF_SITL_PROGRAM "betaflight_SITL.elf"
#define BF_SITL_CONFIG "eeprom.bin"
#define BF_LINK_PATH_LEN 4096
#define BF_LINK_TIMEOUT_MS_DEFAULT 2000 /* an exchange; a SITL answers in well under 1 ms */
#define BF_LINK_BOOT_TIMEOUT_MS 20000   /* the first answer after the start */

typedef struct {
    pid_t pid;                   /* the SITL process; 0: none */
    int sock;                    /* bound to the motor port; sends to the others */
    int locked;                  /* 1: holds the process's one link */
    int timeout_ms;              /* an exchange's */
    long exchanges;              /* answered so far */
    long stale;                  /* motor packets that came unasked (dropped) */
    char dir[BF_LINK_PATH_LEN];  /* where the program and its configuration are */
    char work[BF_LINK_PATH_LEN]; /* its working folder */
} bf_link_t;

/* Starts the SITL of dir and waits for its first answer to `boot` (sent
 * with rc every 50 ms of wall time until it answers, at most
 * BF_LINK_BOOT_TIMEOUT_MS); 0, or -1 with the message in err and nothing
 * left running. timeout_ms <= 0: the default. */
int bf_link_open(bf_link_t *l, const char *dir, int timeout_ms, const bf_rc_t *rc, const bf_fdm_t *boot,
                 float motor[BF_MOTORS], char *err, size_t err_len);

/* One lockstep exchange (rc NULL: no RC frame this time); 0 with the motor
 * outputs, or -1 with the message. */
int bf_link_exchange(bf_link_t *l, const bf_rc_t *rc, const bf_fdm_t *s, float motor[BF_MOTORS], char *err,
                     size_t err_len);

/* The SITL's last line of output, quoted, or "(no output)". */
void bf_link_last_output(const bf_link_t *l, char *out, size_t out_len);

/* Stops the SITL (if any) and removes its working folder; safe to call twice. */
void bf_link_close(bf_link_t *l);

#endif
