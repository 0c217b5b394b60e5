#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""tools/betaflight/patch_sitl.py on hand-made trees: each hook the script
edits is present in a small stand-in for Betaflight's sitl.c and gyro_init.c
(our own text with the same hook lines). A complete tree, as master or as an
older tree such as the ADRC fork has it, must be patched with
every edit in place; a tree missing any one hook must fail naming the file and
the text, with nothing written; a second run must refuse; bad usage exits 2.
Usage: tools/betaflight/patch_sitl_test.py"""

import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
PATCH = os.path.join(HERE, "patch_sitl.py")

SITL_C = """#include "udplink.h"

static void sendMotorUpdate(void) {}

static void updateState(const fdm_packet* pkt)
{
    if (realtime_now > last_realtime + 500*1e3) { // 500ms timeout
        return;
    }
    GYRO_MAPPING
}

static void* udpThread(void* data)
{
    UNUSED(data);
    return NULL;
}

static void *udpRCThread(void *data)
{
    UNUSED(data);
    return NULL;
}

void systemInit(void)
{
    clock_gettime(CLOCK_MONOTONIC, &start_time);
    printf("[system]Init...\\n");
}

uint64_t micros64(void)
{
    return 1;
}

uint64_t millis64(void)
{
    return 1;
}

void delayMicroseconds(uint32_t us)
{
    if (us) { us--; }
}

void delayMicroseconds_real(uint32_t us)
{
    (void)us;
}

void delay(uint32_t ms)
{
    (void)ms;
}

static void pwmCompleteMotorUpdate(void)
{
    if (pthread_mutex_trylock(&updateLock) != 0) return;
    send();
}
"""

MASTER_GYRO = "sitlGyroBodyFromSim(pkt->imu_angular_velocity_rpy, ENABLE_GAZEBO_BRIDGE, &r, &p, &y);"
FORK_GYRO = "z = constrain(-pkt->imu_angular_velocity_rpy[2] * GYRO_SCALE * RAD2DEG, -32767, 32767);"
SITL_C_FORK = SITL_C.replace("GYRO_MAPPING", FORK_GYRO)
SITL_C_NO_GYRO = SITL_C.replace("GYRO_MAPPING", "")
SITL_C = SITL_C.replace("GYRO_MAPPING", MASTER_GYRO)

GYRO_INIT_MASTER = """void gyroInitSensor(void)
{
    if (virtual) {
        gyroSensor->gyroDev.gyroSampleRateHz = VIRTUAL_GYRO_SAMPLE_RATE_HZ;
        gyroSensor->gyroDev.accSampleRateHz = VIRTUAL_GYRO_SAMPLE_RATE_HZ;
        gyroSensor->gyroDev.gyroRateKHz = GYRO_RATE_1_kHz;
    }
}
"""

GYRO_INIT_FORK = """void gyroInitSensor(void)
{
    gyroSensor->gyroDev.gyroSampleRateHz = gyroSetSampleRate(&gyroSensor->gyroDev);
    gyroSensor->gyroDev.initFn(&gyroSensor->gyroDev);
}
"""

# One text per hook: removing it from the stand-in must make the script fail.
SITL_HOOKS = [
    '#include "udplink.h"\n',
    "if (realtime_now > last_realtime + 500*1e3) {",
    "    if (pthread_mutex_trylock(&updateLock) != 0) return;\n",
    '    printf("[system]Init...\\n");\n',
    "static void* udpThread(void* data)",
    "static void *udpRCThread(void *data)",
    "uint64_t micros64(void)",
    "uint64_t millis64(void)",
    "void delayMicroseconds(uint32_t us)",
    "void delay(uint32_t ms)",
    "void delayMicroseconds_real(uint32_t us)",
]

failures = 0


def expect(what, cond, detail=""):
    global failures
    if cond:
        print(f"patch_sitl_test: ok: {what}")
    else:
        failures += 1
        print(f"patch_sitl_test: FAIL: {what}\n{detail}", file=sys.stderr)


def make_tree(root, sitl_c, gyro_init_c):
    for rel, text in (
        ("src/platform/SIMULATOR/sitl.c", sitl_c),
        ("src/main/sensors/gyro_init.c", gyro_init_c),
    ):
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)


def read(root, rel):
    with open(os.path.join(root, rel)) as f:
        return f.read()


def run(*args):
    r = subprocess.run([sys.executable, PATCH, *args], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def main():
    with tempfile.TemporaryDirectory() as work:
        good = os.path.join(work, "good")
        make_tree(good, SITL_C, GYRO_INIT_MASTER)
        code, out = run(good)
        expect("a tree with every hook is patched (exit 0)", code == 0, out)
        sitl = read(good, "src/platform/SIMULATOR/sitl.c")
        gyro = read(good, "src/main/sensors/gyro_init.c")
        expect("sitl_lockstep.c is copied next to sitl.c",
               os.path.isfile(os.path.join(good, "src/platform/SIMULATOR/sitl_lockstep.c")))
        expect("sitl.c includes sitl_lockstep.c at its end",
               sitl.rstrip().endswith('#include "sitl_lockstep.c"\n#endif'.rstrip()), sitl[-200:])
        expect("the 500 ms timeout is gated", "if (!SITL_LOCKSTEP && realtime_now >" in sitl)
        expect("the motor packet is not sent from pwmCompleteMotorUpdate",
               "if (SITL_LOCKSTEP || pthread_mutex_trylock(&updateLock) != 0) return;" in sitl)
        expect("both receive threads end at once in lockstep", sitl.count("if (SITL_LOCKSTEP) {\n        return NULL;") == 2)
        expect("systemInit calls lockstepInit", "lockstepInit();" in sitl.split("void systemInit(void)")[1].split("}")[0])
        for signature in ("uint64_t micros64(void)", "uint64_t millis64(void)", "void delay(uint32_t ms)",
                          "void delayMicroseconds(uint32_t us)", "void delayMicroseconds_real(uint32_t us)"):
            expect(f"{signature} only without lockstep", f"#if !SITL_LOCKSTEP\n{signature}\n{{" in sitl)
        expect("the virtual gyro at 8 kHz with the accelerometer at 1 kHz",
               "gyroSampleRateHz = 8000;" in gyro and "accSampleRateHz = 1000;" in gyro
               and "VIRTUAL_GYRO_SAMPLE_RATE_HZ" not in gyro, gyro)

        code, out = run(good)
        expect("a second run refuses (exit 1, 'already patched')", code == 1 and "already patched" in out, out)

        expect("master's gyro mapping is left as it is", MASTER_GYRO in sitl)

        fork = os.path.join(work, "fork")
        make_tree(fork, SITL_C_FORK, GYRO_INIT_FORK)
        code, out = run(fork)
        expect("a tree whose virtual gyro already uses gyroSetSampleRate is left at it",
               code == 0 and read(fork, "src/main/sensors/gyro_init.c") == GYRO_INIT_FORK and "already" in out, out)
        fork_sitl = read(fork, "src/platform/SIMULATOR/sitl.c")
        expect("an older tree's yaw negation depends on the bridge, as on master",
               FORK_GYRO not in fork_sitl
               and "(ENABLE_GAZEBO_BRIDGE ? 1 : -1) * pkt->imu_angular_velocity_rpy[2]" in fork_sitl, fork_sitl)

        tree = os.path.join(work, "noyaw")
        make_tree(tree, SITL_C_NO_GYRO, GYRO_INIT_MASTER)
        code, out = run(tree)
        expect("without either gyro mapping: exit 1 naming sitl.c, nothing written",
               code == 1 and "sitlGyroBodyFromSim" in out and read(tree, "src/platform/SIMULATOR/sitl.c") == SITL_C_NO_GYRO,
               out)

        for i, hook in enumerate(SITL_HOOKS):
            tree = os.path.join(work, f"missing{i}")
            broken = SITL_C.replace(hook, hook.replace("(", "[", 1) if "(" in hook else hook.replace("udplink", "udp_link"), 1)
            assert broken != SITL_C, hook
            make_tree(tree, broken, GYRO_INIT_MASTER)
            code, out = run(tree)
            unchanged = (read(tree, "src/platform/SIMULATOR/sitl.c") == broken
                         and read(tree, "src/main/sensors/gyro_init.c") == GYRO_INIT_MASTER
                         and not os.path.exists(os.path.join(tree, "src/platform/SIMULATOR/sitl_lockstep.c")))
            expect(f"without the hook {hook.strip()[:40]!r}: exit 1 naming sitl.c, nothing written",
                   code == 1 and "sitl.c: hook not found" in out and unchanged, out)

        tree = os.path.join(work, "nogyro")
        make_tree(tree, SITL_C, "void gyroInitSensor(void) {}\n")
        code, out = run(tree)
        expect("without the virtual gyro's rate lines: exit 1 naming gyro_init.c, nothing written",
               code == 1 and "gyro_init.c: hook not found" in out
               and read(tree, "src/platform/SIMULATOR/sitl.c") == SITL_C, out)

        code, out = run()
        expect("no TREE: usage, exit 2", code == 2 and "Usage" in out, out)
        code, out = run(os.path.join(work, "nothing"))
        expect("a directory without sitl.c: exit 1 naming it", code == 1 and "sitl.c: not found" in out, out)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
