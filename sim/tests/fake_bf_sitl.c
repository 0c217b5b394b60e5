/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A stand-in for Betaflight's SITL that speaks its UDP packets
 * (bridge/bf_packet.h), for testing the simulator's bridge where
 * Betaflight itself cannot be built: state in on 9003, RC in on 9004, one
 * motor packet out to 9002 per state packet. Its controller is a rate P loop
 * on the gyro (acro: linear rates, 700 deg/s at full stick; angle mode: an
 * angle P loop on the packet's attitude, 60 deg at full stick) through a
 * plus-frame mixer in Betaflight's QUADP motor order (rear, right, left,
 * front), motor outputs idle + (1 - idle) x mix when armed, 0 disarmed. It
 * arms as Betaflight does: the arm switch up with the throttle low, not
 * before CALIBRATION_PACKETS state packets (its gyro calibration).
 *
 * FAKE_BF_FAULT makes it misbehave, for the bridge's error paths:
 *   die@T       exit with status 3 at the first state packet of time >= T (s)
 *   silent@T    stop answering from there (alive)
 *   garbage@T   answer that one with 7 bytes
 *   nan@T       answer that one with a motor output that is not a number
 *   junk@T      answer that one with 1-64 random bytes (seeded by T)
 *   never-arm   never arm (prints an arming-disabled line now and then)
 *   no-start    exit with status 1 at once, saying why
 * FAKE_BF_KP: the rate loop's gain (motor fraction per rad/s), default 0.04,
 * times N / 100 when its configuration (eeprom.bin in its working folder)
 * holds a line `set simplified_master_multiplier = N`, as Betaflight's
 * master slider scales its gains. `--config FILE` stores FILE as that
 * configuration and exits, as Betaflight's SITL does.
 */
#define _POSIX_C_SOURCE 200809L
#include <arpa/inet.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "bridge/bf_packet.h"
#include "bridge/bf_pilot.h"

#define CALIBRATION_PACKETS 500
#define IDLE 0.055
#define RATE_MAX_RAD_S (700.0 * 3.14159265358979323846 / 180.0)
#define ANGLE_LIMIT_RAD (60.0 * 3.14159265358979323846 / 180.0)
#define ANGLE_KP_PER_S 6.0

typedef enum { FAULT_NONE, FAULT_DIE, FAULT_SILENT, FAULT_GARBAGE, FAULT_NAN, FAULT_JUNK, FAULT_NEVER_ARM } fault_t;

static int udp_bound(int port)
{
    const int s = socket(AF_INET, SOCK_DGRAM, 0);
    struct sockaddr_in a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons((uint16_t)port);
    if (s < 0 || bind(s, (const struct sockaddr *)&a, sizeof a) != 0) {
        printf("fake SITL: cannot bind UDP port %d\n", port);
        exit(1);
    }
    return s;
}

static double stick(uint16_t us)
{
    return ((double)us - BF_STICK_CENTRE_US) / BF_STICK_HALF_US;
}

/* Roll and pitch (rad, forward-right-down) of the packet's attitude: the
 * Gazebo form turned back by Rz(+pi/2). */
static void tilt_of(const double qg[4], double *roll, double *pitch)
{
    const double c = 0.70710678118654752440, s = 0.70710678118654752440;
    const double w = c * qg[0] - s * qg[3], x = c * qg[1] - s * qg[2], y = c * qg[2] + s * qg[1],
                 z = c * qg[3] + s * qg[0];
    *roll = atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y));
    const double sp = 2.0 * (w * y - z * x);
    *pitch = asin(sp > 1.0 ? 1.0 : sp < -1.0 ? -1.0 : sp);
}

/* The motor outputs for the state s and the sticks rc (forward-right-down
 * throughout: the pitch stick asks nose down). */
static void control(const bf_fdm_t *s, const bf_rc_t *rc, int armed, double kp, float motor[BF_MOTORS])
{
    double rate_sp[3];
    for (int i = 0; i < 3; ++i) {
        static const int CH[3] = {BF_CH_ROLL, BF_CH_PITCH, BF_CH_YAW};
        rate_sp[i] = (i == 1 ? -1.0 : 1.0) * stick(rc->channel_us[CH[i]]) * RATE_MAX_RAD_S;
    }
    if (rc->channel_us[BF_CH_ANGLE] > 1700) {
        double roll, pitch;
        tilt_of(s->quat_wxyz, &roll, &pitch);
        rate_sp[0] = ANGLE_KP_PER_S * (stick(rc->channel_us[BF_CH_ROLL]) * ANGLE_LIMIT_RAD - roll);
        rate_sp[1] = ANGLE_KP_PER_S * (-stick(rc->channel_us[BF_CH_PITCH]) * ANGLE_LIMIT_RAD - pitch);
    }
    double u[3];
    for (int i = 0; i < 3; ++i) { /* the packet's yaw is nose left (docs/betaflight.md) */
        u[i] = kp * (rate_sp[i] - (i == 2 ? -1.0 : 1.0) * s->gyro_rad_s[i]);
    }
    const double thr = ((double)rc->channel_us[BF_CH_THROTTLE] - 1000.0) / 1000.0;
    /* rear, right, left, front: pitch up on the front, roll right on the left, yaw on the side pair */
    const double mix[BF_MOTORS] = {thr - u[1] - u[2], thr - u[0] + u[2], thr + u[0] + u[2], thr + u[1] - u[2]};
    for (int m = 0; m < BF_MOTORS; ++m) {
        const double v = mix[m] < 0.0 ? 0.0 : mix[m] > 1.0 ? 1.0 : mix[m];
        motor[m] = armed ? (float)(IDLE + (1.0 - IDLE) * v) : 0.0f;
    }
}

/* Copies the CLI file into eeprom.bin; the exit status. */
static int store_config(const char *path)
{
    FILE *in = fopen(path, "rb"), *out = fopen("eeprom.bin", "wb");
    int c, rc = in != NULL && out != NULL ? 0 : 1;
    while (rc == 0 && (c = fgetc(in)) != EOF) {
        fputc(c, out);
    }
    if (in != NULL) {
        fclose(in);
    }
    if (out != NULL && fclose(out) != 0) {
        rc = 1;
    }
    printf("fake SITL: configuration %s %s\n", path, rc == 0 ? "saved" : "not saved");
    return rc;
}

/* The master slider in eeprom.bin, percent (100 without one). */
static double master_slider(void)
{
    FILE *f = fopen("eeprom.bin", "rb");
    char line[256];
    double pct = 100.0;
    while (f != NULL && fgets(line, sizeof line, f) != NULL) {
        (void)sscanf(line, "set simplified_master_multiplier = %lf", &pct);
    }
    if (f != NULL) {
        fclose(f);
    }
    return pct;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--config") == 0) {
        return store_config(argv[2]);
    }
    const char *f = getenv("FAKE_BF_FAULT");
    fault_t fault = FAULT_NONE;
    double at = INFINITY; /* the fault's time (s) */
    if (f != NULL && strcmp(f, "no-start") == 0) {
        printf("fake SITL: refusing to start as asked\n");
        return 1;
    }
    if (f != NULL && strcmp(f, "never-arm") == 0) {
        fault = FAULT_NEVER_ARM;
    } else if (f != NULL) {
        static const char *const NAMES[] = {"die@", "silent@", "garbage@", "nan@", "junk@"};
        static const fault_t KINDS[] = {FAULT_DIE, FAULT_SILENT, FAULT_GARBAGE, FAULT_NAN, FAULT_JUNK};
        for (int k = 0; k < 5; ++k) {
            if (strncmp(f, NAMES[k], strlen(NAMES[k])) == 0) {
                fault = KINDS[k];
                at = atof(f + strlen(NAMES[k]));
            }
        }
    }
    const char *kp_text = getenv("FAKE_BF_KP");
    const double kp = (kp_text != NULL ? atof(kp_text) : 0.04) * master_slider() / 100.0;
    const int fdm = udp_bound(BF_PORT_FDM), rcs = udp_bound(BF_PORT_RC);
    struct sockaddr_in to;
    memset(&to, 0, sizeof to);
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    to.sin_port = htons(BF_PORT_MOTORS);
    printf("fake SITL: listening on %d and %d\n", BF_PORT_FDM, BF_PORT_RC);
    fflush(stdout);
    bf_rc_t rc;
    memset(&rc, 0, sizeof rc);
    for (int k = 0; k < BF_RC_CHANNELS; ++k) {
        rc.channel_us[k] = k == BF_CH_THROTTLE || k == BF_CH_ARM || k == BF_CH_ANGLE ? 1000 : BF_STICK_CENTRE_US;
    }
    long n = 0;
    int armed = 0, faulted = 0;
    for (;;) {
        struct pollfd p[2] = {{.fd = rcs, .events = POLLIN, .revents = 0}, {.fd = fdm, .events = POLLIN, .revents = 0}};
        if (poll(p, 2, -1) <= 0) {
            continue;
        }
        unsigned char buf[512];
        if (p[0].revents & POLLIN) { /* the RC first: the bridge sends it before the state */
            const ssize_t len = recv(rcs, buf, sizeof buf, 0);
            (void)(len > 0 && bf_rc_decode(buf, (size_t)len, &rc) == 0);
            continue;
        }
        const ssize_t len = recv(fdm, buf, sizeof buf, 0);
        bf_fdm_t s;
        if (len <= 0 || bf_fdm_decode(buf, (size_t)len, &s) != 0) {
            continue;
        }
        ++n;
        const int due = s.t_s >= at && !faulted;
        faulted |= due;
        if (due && fault == FAULT_DIE) {
            printf("fake SITL: dying at time %g s as asked\n", s.t_s);
            return 3;
        }
        if (fault == FAULT_SILENT && s.t_s >= at) {
            continue;
        }
        const int arm_switch = rc.channel_us[BF_CH_ARM] > 1700;
        const int allowed = n > CALIBRATION_PACKETS && fault != FAULT_NEVER_ARM;
        if (arm_switch && !armed && allowed && rc.channel_us[BF_CH_THROTTLE] < 1050) {
            armed = 1;
        } else if (!arm_switch) {
            armed = 0;
        }
        if (arm_switch && !armed && n % 1000 == 0) {
            printf("fake SITL: arming disabled: %s\n", allowed ? "THROTTLE" : "CALIBRATING");
            fflush(stdout);
        }
        float motor[BF_MOTORS];
        control(&s, &rc, armed, kp, motor);
        unsigned char out[BF_MOTOR_BYTES];
        bf_motor_encode(motor, out);
        size_t out_len = sizeof out;
        if (due && fault == FAULT_GARBAGE) {
            out_len = 7;
        }
        if (due && fault == FAULT_NAN) {
            motor[2] = (float)NAN;
            bf_motor_encode(motor, out);
        }
        unsigned char junk[64];
        if (due && fault == FAULT_JUNK) { /* a 64-bit LCG from the fault's time */
            uint64_t x = (uint64_t)(at * 1e6) * 6364136223846793005ULL + 1442695040888963407ULL;
            out_len = 1 + (size_t)((x >> 33) % sizeof junk);
            for (size_t b = 0; b < sizeof junk; ++b) {
                x = x * 6364136223846793005ULL + 1442695040888963407ULL;
                junk[b] = (unsigned char)(x >> 56);
            }
        }
        (void)sendto(fdm, due && fault == FAULT_JUNK ? junk : out, out_len, 0, (const struct sockaddr *)&to, sizeof to);
    }
}
