/* SPDX-License-Identifier: BSD-3-Clause */
/* Lockstep tick loop and simulated clock for Betaflight's SITL.
 *
 * tools/betaflight/patch_sitl.py copies this file next to the SITL's
 * platform source (src/platform/SIMULATOR/sitl.c) of a build copy and
 * includes it at the end of that file, so it sees that file's statics
 * (stateLink, rcLink, pwmLink, fdmPkt, rcPkt, pwmPkt, updateState). It
 * replaces the wall-clock time base and the UDP receive threads:
 *
 *   - one FDM packet is one tick; the main thread receives it, applies the
 *     RC packets queued before it and the vehicle state, advances the clock
 *     by the packet's time step in 125 us sub-steps, runs the scheduler a
 *     fixed number of passes in each, and answers with exactly one motor
 *     packet;
 *   - micros()/millis() return that clock: it moves only by the packets'
 *     time steps and by the main thread's delay() calls (boot), never by
 *     the wall clock, so two runs fed the same packets compute the same
 *     motor outputs.
 *
 * Built only with -DSITL_LOCKSTEP=1 (tools/betaflight_sitl.sh sets it). */

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <sys/socket.h>
#include <sys/time.h>

/* The virtual gyro samples at 8 kHz (patch_sitl.py sets that rate in
 * gyro_init.c), so the scheduler's gyro task is due every 125 us of this
 * clock. The clock only moves in whole steps of it: the gyro task is then
 * never due a few microseconds ahead (the scheduler would spin on a clock
 * that only a packet can move), and a packet's time step is run as that many
 * 125 us sub-steps, one gyro sample each (after a jump of three or more
 * samples the scheduler's overrun recovery would skip the gyro task for
 * good). */
#define LOCKSTEP_GRID_US 125
/* A step above a second is taken for a unit error (timestamps are seconds). */
#define LOCKSTEP_MAX_STEP_US 1000000
/* scheduler() passes per sub-step: a pass runs the gyro/filter/PID group
 * when it is due and at most one other task; the rest give the other tasks
 * (RX, accelerometer, attitude, serial/MSP, ...) their slots at the time
 * they are due. */
#define LOCKSTEP_PASSES_PER_STEP 2
/* How long the main thread waits in one receive call before it waits again;
 * the wait for the next packet itself is unbounded. */
#define LOCKSTEP_RECEIVE_POLL_MS 100
/* How long the main thread polls for the next FDM packet before it sleeps. */
#ifndef LOCKSTEP_SPIN_NS
#define LOCKSTEP_SPIN_NS 100000
#endif

static pthread_t lockstepMainThread;
static uint64_t lockstepNowUs; /* the simulated clock, whole grid steps */
static bool lockstepStarted;   /* first FDM packet received */
static double lockstepLastTimestampS;
static unsigned lockstepPasses;
static uint64_t lockstepSubStepsLeft; /* 125 us sub-steps still to run in this tick */
static uint64_t lockstepTicks;

static void lockstepInit(void)
{
    lockstepMainThread = pthread_self();
}

static bool lockstepOnMainThread(void)
{
    return pthread_equal(pthread_self(), lockstepMainThread) != 0;
}

static uint64_t lockstepLoadUs(void)
{
    return __atomic_load_n(&lockstepNowUs, __ATOMIC_ACQUIRE);
}

static void lockstepAdvanceUs(uint64_t stepUs)
{
    __atomic_store_n(&lockstepNowUs, lockstepLoadUs() + stepUs, __ATOMIC_RELEASE);
}

static uint64_t lockstepRoundUpToGridUs(uint64_t us)
{
    return ((us + LOCKSTEP_GRID_US - 1) / LOCKSTEP_GRID_US) * LOCKSTEP_GRID_US;
}

uint64_t micros64(void)
{
    return lockstepLoadUs();
}

uint64_t millis64(void)
{
    return lockstepLoadUs() / 1000;
}

/* A wait on the main thread (boot code waiting for hardware that is
 * simulated) moves the clock instead of sleeping: nothing else runs while it
 * waits, so only the elapsed time matters. Rounded up to the grid; other
 * threads (TCP) sleep for real and leave the clock alone. */
void delayMicroseconds(uint32_t us)
{
    if (lockstepOnMainThread()) {
        lockstepAdvanceUs(lockstepRoundUpToGridUs(us));
    } else {
        microsleep(us);
    }
}

void delay(uint32_t ms)
{
    delayMicroseconds(ms * 1000);
}

static void lockstepFail(const char *what, double timestampS)
{
    fprintf(stderr,
            "[SITL lockstep] FDM packet %llu (timestamp %.9f s): %s; the lockstep build needs timestamps "
            "in seconds that increase by a whole multiple of 125 us (8 kHz, 4 kHz, 2 kHz, 1 kHz, ...) "
            "from one packet to the next; restart the SITL for each run\n",
            (unsigned long long)lockstepTicks, timestampS, what);
    exit(1);
}

/* RC packets queued before this tick's FDM packet: the bridge sends them
 * first, so they are in the socket when the FDM packet is; the last one
 * wins. Read here, on the main thread, so the RX task sees them at the same
 * tick in every run. One non-blocking recv per packet, one more that finds
 * the socket empty (system calls are most of a tick's cost). */
static void lockstepApplyQueuedRc(void)
{
    bool received = false;
    for (;;) {
        const ssize_t n = recv(rcLink.fd, &rcPkt, sizeof(rc_packet), MSG_DONTWAIT);
        if (n < 0) {
            break;
        }
        if (n != (ssize_t)sizeof(rc_packet)) {
            fprintf(stderr, "[SITL lockstep] RC packet of %d bytes ignored: expected %u (rc_packet)\n", (int)n,
                    (unsigned)sizeof(rc_packet));
            continue;
        }
        received = true;
    }
    if (received) {
        if (!rc_received) {
            printf("[SITL lockstep] first RC packet at tick %llu: AETR %u %u %u %u AUX1-4 %u %u %u %u\n",
                   (unsigned long long)lockstepTicks, rcPkt.channels[0], rcPkt.channels[1], rcPkt.channels[2],
                   rcPkt.channels[3], rcPkt.channels[4], rcPkt.channels[5], rcPkt.channels[6], rcPkt.channels[7]);
            rc_received = true;
        }
        rxUpdateUdpChannels(rcPkt.channels, SIMULATOR_MAX_RC_CHANNELS);
    }
}

/* The FDM socket (opened non-blocking by udpInit) made blocking with a
 * receive timeout: one recv system call per packet instead of select + recv. */
static void lockstepMakeFdmSocketBlocking(void)
{
    const struct timeval poll = {.tv_sec = 0, .tv_usec = LOCKSTEP_RECEIVE_POLL_MS * 1000};
    const int flags = fcntl(stateLink.fd, F_GETFL, 0);
    if (flags < 0 || fcntl(stateLink.fd, F_SETFL, flags & ~O_NONBLOCK) != 0 ||
        setsockopt(stateLink.fd, SOL_SOCKET, SO_RCVTIMEO, &poll, sizeof(poll)) != 0) {
        fprintf(stderr, "[SITL lockstep] FDM socket (UDP %d): cannot make it blocking: %s\n", PORT_STATE,
                strerror(errno));
        exit(1);
    }
}

static void lockstepReceiveFdm(void)
{
    static bool blocking = false;
    if (!blocking) {
        lockstepMakeFdmSocketBlocking();
        blocking = true;
    }
    /* The simulator answers within tens of microseconds: poll for that long
     * before sleeping in recv, whose wake-up costs about as much again. */
    const uint64_t spinUntilNs = nanos64_real() + LOCKSTEP_SPIN_NS;
    while (nanos64_real() < spinUntilNs) {
        const ssize_t n = recv(stateLink.fd, &fdmPkt, sizeof(fdm_packet), MSG_DONTWAIT);
        if (n == (ssize_t)sizeof(fdm_packet)) {
            return;
        }
        if (n >= 0) {
            fprintf(stderr, "[SITL lockstep] FDM packet of %d bytes ignored: expected %u (fdm_packet)\n", (int)n,
                    (unsigned)sizeof(fdm_packet));
        }
    }
    for (;;) {
        const ssize_t n = recv(stateLink.fd, &fdmPkt, sizeof(fdm_packet), 0);
        if (n == (ssize_t)sizeof(fdm_packet)) {
            return;
        }
        if (n >= 0) {
            fprintf(stderr, "[SITL lockstep] FDM packet of %d bytes ignored: expected %u (fdm_packet)\n", (int)n,
                    (unsigned)sizeof(fdm_packet));
        }
    }
}

/* One tick: wait for the FDM packet, apply RC then the vehicle state, and
 * start the first 125 us sub-step of the packet's time step. */
static void lockstepStartTick(void)
{
    lockstepReceiveFdm();
    lockstepApplyQueuedRc();

    const double timestampS = fdmPkt.timestamp;
    if (!lockstepStarted) {
        printf("[SITL lockstep] first FDM packet: t=%.6f s, clock %llu us\n", timestampS,
               (unsigned long long)lockstepLoadUs());
        fdm_received = true;
        lockstepStarted = true;
        lockstepSubStepsLeft = 0;
    } else {
        const double stepS = timestampS - lockstepLastTimestampS;
        if (!(stepS > 0.0)) {
            lockstepFail("the timestamp did not increase", timestampS);
        }
        const long long stepUs = llround(stepS * 1e6);
        if (stepUs % LOCKSTEP_GRID_US != 0 || stepUs > LOCKSTEP_MAX_STEP_US) {
            lockstepFail("the time step is not a multiple of 125 us (or is above 1 s)", timestampS);
        }
        lockstepAdvanceUs(LOCKSTEP_GRID_US);
        lockstepSubStepsLeft = (uint64_t)stepUs / LOCKSTEP_GRID_US - 1;
    }
    lockstepLastTimestampS = timestampS;
    lockstepTicks++;

    updateState(&fdmPkt);
}

/* What stops arming, printed with the simulated time whenever it changes:
 * the boot's progress without a configurator. */
static void lockstepReportArmingFlags(void)
{
    static armingDisableFlags_e reported = (armingDisableFlags_e)-1;
    const armingDisableFlags_e flags = getArmingDisableFlags();
    if (flags == reported) {
        return;
    }
    reported = flags;
    printf("[SITL lockstep] t=%.4f s (FDM packet %llu): arming disabled by:", lockstepLastTimestampS,
           (unsigned long long)(lockstepTicks - 1));
    if (flags == 0) {
        printf(" nothing (arming allowed)");
    }
    for (unsigned i = 0; i < ARMING_DISABLE_FLAGS_COUNT; i++) {
        if (flags & (1u << i)) {
            printf(" %s", getArmingDisableFlagName((armingDisableFlags_e)(1u << i)));
        }
    }
    printf("\n");
}

/* run() calls this after every scheduler() pass (RUN_LOOP_DELAY_US). */
void delayMicroseconds_real(uint32_t us)
{
    UNUSED(us);
    if (++lockstepPasses < LOCKSTEP_PASSES_PER_STEP) {
        return;
    }
    lockstepPasses = 0;
    if (lockstepSubStepsLeft > 0) {
        lockstepSubStepsLeft--;
        lockstepAdvanceUs(LOCKSTEP_GRID_US);
        return;
    }
    if (lockstepStarted) {
        /* the answer to this tick's FDM packet: the motor outputs of the
         * last mixer run (zero until the motors are first written) */
        sendMotorUpdate();
        lockstepReportArmingFlags();
    }
    lockstepStartTick();
}
