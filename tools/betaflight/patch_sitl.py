#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Apply the lockstep hook edits to a build copy of a Betaflight tree.

Usage: patch_sitl.py TREE

TREE is a copy (tools/betaflight_sitl.sh makes it), never the user's
checkout. Every edit looks for a named piece of text in a named file and
stops with `file: hook not found: <text>` when that text is missing, so a
Betaflight version that moved the code fails here, not at run time; nothing
is written unless every hook was found. The edits (src/platform/SIMULATOR/
sitl.c: compiled only with SITL_LOCKSTEP=1; src/main/sensors/gyro_init.c:
the virtual gyro's rate) are documented in docs/betaflight-sitl.md; the code
the sitl.c edits switch on is sitl_lockstep.c, copied next to sitl.c.
"""

import re
import shutil
import sys
from pathlib import Path

SITL_C = "src/platform/SIMULATOR/sitl.c"
GYRO_INIT_C = "src/main/sensors/gyro_init.c"
LOCKSTEP_C = "sitl_lockstep.c"


class HookNotFound(Exception):
    pass


def find_once(text, needle, path):
    """Offset of the only occurrence of needle in text."""
    first = text.find(needle)
    if first < 0:
        raise HookNotFound(f"{path}: hook not found: {needle!r}")
    if text.find(needle, first + 1) >= 0:
        raise HookNotFound(f"{path}: hook found more than once: {needle!r}")
    return first


def insert_after(text, needle, addition, path):
    at = find_once(text, needle, path) + len(needle)
    return text[:at] + addition + text[at:]


def replace_once(text, needle, replacement, path):
    at = find_once(text, needle, path)
    return text[:at] + replacement + text[at + len(needle):]


def function_span(text, signature, path):
    """(start, end) of a function definition that begins with the line
    `signature` and ends at its matching closing brace."""
    match = re.search(r"^" + re.escape(signature) + r"\s*\n\{", text, re.MULTILINE)
    if not match:
        raise HookNotFound(f"{path}: hook not found: function definition {signature!r}")
    depth = 0
    for at in range(match.end() - 1, len(text)):
        if text[at] == "{":
            depth += 1
        elif text[at] == "}":
            depth -= 1
            if depth == 0:
                return match.start(), at + 1
    raise HookNotFound(f"{path}: no closing brace for {signature!r}")


def without_lockstep(text, signature, path):
    """Compile the original definition only in non-lockstep builds:
    sitl_lockstep.c defines its replacement."""
    start, end = function_span(text, signature, path)
    return text[:start] + "#if !SITL_LOCKSTEP\n" + text[start:end] + "\n#endif\n" + text[end:]


# The five SITL functions that sitl_lockstep.c replaces: the wall-clock time
# base (micros64/millis64 scale the wall clock by a measured simRate), the
# sleeping delays, and delayMicroseconds_real, which run() calls after every
# scheduler() pass and which becomes the tick loop.
REPLACED_FUNCTIONS = [
    "uint64_t micros64(void)",
    "uint64_t millis64(void)",
    "void delayMicroseconds(uint32_t us)",
    "void delay(uint32_t ms)",
    "void delayMicroseconds_real(uint32_t us)",
]

PRELUDE = """
#ifndef SITL_LOCKSTEP
#define SITL_LOCKSTEP 0
#endif
#if SITL_LOCKSTEP
static void lockstepInit(void);
#endif
"""


# The yaw rate's sign. Betaflight master maps the FDM gyro in one helper,
# sitlGyroBodyFromSim, and keeps the packet's yaw sign with the Gazebo bridge
# (ENABLE_GAZEBO_BRIDGE = 1, the SITL's default) and negates it for the
# legacy bridges (the fix of Betaflight issue #15294). Older trees, such as
# the ADRC fork, negate it for every bridge; there the negation is made to
# depend on the bridge as on master, so that one simulator flies both builds.
MASTER_GYRO_MAPPING = "sitlGyroBodyFromSim("
OLD_YAW_LINE = "    z = constrain(-pkt->imu_angular_velocity_rpy[2] * GYRO_SCALE * RAD2DEG, -32767, 32767);\n"
OLD_YAW_AS_MASTER = (
    "    // lockstep SITL: the yaw sign of Betaflight master's sitlGyroBodyFromSim\n"
    "    z = constrain((ENABLE_GAZEBO_BRIDGE ? 1 : -1) * pkt->imu_angular_velocity_rpy[2] * GYRO_SCALE * RAD2DEG,\n"
    "                  -32767, 32767);\n"
)


def gazebo_yaw_as_master(text, path):
    if MASTER_GYRO_MAPPING in text:
        return text
    if OLD_YAW_LINE in text:
        return replace_once(text, OLD_YAW_LINE, OLD_YAW_AS_MASTER, path)
    raise HookNotFound(f"{path}: hook not found: {MASTER_GYRO_MAPPING!r} (nor {OLD_YAW_LINE.strip()!r})")


def patch_sitl_c(text, path):
    # Lockstep switch and the prototype of the hook called from systemInit.
    text = insert_after(text, '#include "udplink.h"\n', PRELUDE, path)

    # systemInit: remember the main thread (delay() moves the simulated
    # clock only there).
    text = insert_after(
        text,
        "    clock_gettime(CLOCK_MONOTONIC, &start_time);\n    printf(\"[system]Init...\\n\");\n",
        "#if SITL_LOCKSTEP\n    lockstepInit();\n#endif\n",
        path,
    )

    # udpThread / udpRCThread: the main thread reads the FDM and RC sockets
    # itself, in tick order; the threads end at once (systemReset still
    # joins them).
    for thread in ("static void* udpThread(void* data)", "static void *udpRCThread(void *data)"):
        start, end = function_span(text, thread, path)
        body = text[start:end]
        body = replace_once(body, "    UNUSED(data);\n", "    UNUSED(data);\n    if (SITL_LOCKSTEP) {\n        return NULL;\n    }\n", path)
        text = text[:start] + body + text[end:]

    # updateState: the 500 ms wall-clock timeout answers a packet with the old
    # motor outputs and drops its state; a lockstep simulator may pause for
    # any time, and every packet must be applied.
    text = replace_once(
        text,
        "if (realtime_now > last_realtime + 500*1e3) {",
        "if (!SITL_LOCKSTEP && realtime_now > last_realtime + 500*1e3) {",
        path,
    )

    # pwmCompleteMotorUpdate: keep computing pwmPkt, but the tick loop sends
    # it, once per FDM packet, after the tick's scheduler passes.
    text = replace_once(
        text,
        "    if (pthread_mutex_trylock(&updateLock) != 0) return;\n",
        "    if (SITL_LOCKSTEP || pthread_mutex_trylock(&updateLock) != 0) return;\n",
        path,
    )

    for signature in REPLACED_FUNCTIONS:
        text = without_lockstep(text, signature, path)

    text = gazebo_yaw_as_master(text, path)

    return text + '\n#if SITL_LOCKSTEP\n#include "' + LOCKSTEP_C + '"\n#endif\n'


# Betaflight's virtual gyro samples at VIRTUAL_GYRO_SAMPLE_RATE_HZ (1 kHz), and
# its accelerometer at the same rate; the gyro task, and with it the filters
# and the PID loop, then run at 1 kHz / pid_process_denom. A real 8 kHz gyro
# (and gyroSetSampleRate's default for a sensor it does not know, which older
# trees, such as the ADRC fork, use for the virtual gyro too) samples at 8 kHz
# with the accelerometer at 1 kHz.
VIRTUAL_GYRO_RATE = """        gyroSensor->gyroDev.gyroSampleRateHz = VIRTUAL_GYRO_SAMPLE_RATE_HZ;
        gyroSensor->gyroDev.accSampleRateHz = VIRTUAL_GYRO_SAMPLE_RATE_HZ;
        gyroSensor->gyroDev.gyroRateKHz = GYRO_RATE_1_kHz;
"""
GYRO_RATE_8K = """        // lockstep SITL: an 8 kHz gyro with a 1 kHz accelerometer, as gyroSetSampleRate's default
        gyroSensor->gyroDev.gyroSampleRateHz = 8000;
        gyroSensor->gyroDev.accSampleRateHz = 1000;
        gyroSensor->gyroDev.gyroRateKHz = GYRO_RATE_8_kHz;
"""
GYRO_RATE_FROM_DETECTION = "    gyroSensor->gyroDev.gyroSampleRateHz = gyroSetSampleRate(&gyroSensor->gyroDev);\n    gyroSensor->gyroDev.initFn("


def patch_gyro_init_c(text, path):
    """The virtual gyro at 8 kHz; a tree that already takes every gyro's rate
    from gyroSetSampleRate (8 kHz for the virtual one) is left as it is."""
    if VIRTUAL_GYRO_RATE in text:
        return replace_once(text, VIRTUAL_GYRO_RATE, GYRO_RATE_8K, path), "virtual gyro at 8 kHz"
    if GYRO_RATE_FROM_DETECTION in text:
        return text, "virtual gyro already at gyroSetSampleRate's 8 kHz"
    raise HookNotFound(f"{path}: hook not found: {VIRTUAL_GYRO_RATE!r} (nor {GYRO_RATE_FROM_DETECTION!r})")


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    tree = Path(argv[1])
    sitl_c = tree / SITL_C
    if not sitl_c.is_file():
        print(f"{sitl_c}: not found: TREE must be a Betaflight source tree", file=sys.stderr)
        return 1
    gyro_init_c = tree / GYRO_INIT_C
    original = sitl_c.read_text()
    if "sitl_lockstep.c" in original:
        print(f"{sitl_c}: already patched", file=sys.stderr)
        return 1
    try:
        patched = patch_sitl_c(original, str(sitl_c))
        if not gyro_init_c.is_file():
            raise HookNotFound(f"{gyro_init_c}: not found")
        gyro_init, gyro_note = patch_gyro_init_c(gyro_init_c.read_text(), str(gyro_init_c))
    except HookNotFound as exc:
        print(f"{exc}", file=sys.stderr)
        return 1
    # nothing is written until every hook was found
    shutil.copyfile(Path(__file__).with_name(LOCKSTEP_C), sitl_c.parent / LOCKSTEP_C)
    sitl_c.write_text(patched)
    gyro_init_c.write_text(gyro_init)
    print(f"patched {SITL_C}: lockstep tick loop and simulated clock ({len(REPLACED_FUNCTIONS)} functions replaced)")
    if OLD_YAW_AS_MASTER in patched:
        print(f"patched {SITL_C}: the gyro's yaw sign as on Betaflight master (kept with the Gazebo bridge)")
    print(f"patched {GYRO_INIT_C}: {gyro_note}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
