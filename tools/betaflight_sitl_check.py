#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Check a lockstep Betaflight SITL built by tools/betaflight_sitl.sh.

Acts as the simulator: sends FDM packets of a level vehicle at rest (UDP 9003)
at a fixed rate of simulated time, RC before the FDM packet of a tick every
few ticks (UDP 9004), and waits for the motor packet (UDP 9002) of each FDM
packet before it sends the next. Checks and reports:

  - lockstep: exactly one motor packet per FDM packet;
  - arming on AUX1 (the motors leave 0 for the idle value) and when arming
    is first allowed after boot;
  - the motor order: which motor indices rise for a roll/pitch/yaw stick,
    and for a faked body rate in each gyro field of the FDM packet, and for
    an accelerometer tilt in angle mode (the packet's sign conventions);
  - speed: round trips per second of wall time and the simulated-time factor;
  - with --launch and --runs 2 (the default there): determinism, the motor
    packets of two fresh runs compared byte for byte.

Usage:
  betaflight_sitl_check.py [--launch OUTDIR] [--runs N] [--rate-hz 4000]
                           [--rc-hz 250] [--isolate] [--log-dir DIR] [--keep-logs]

Without --launch it talks to a SITL already running on this machine (started
in a directory holding the eeprom.bin the build made, and not yet sent any
packet: the SITL needs a fresh start for every run). --launch OUTDIR starts
OUTDIR/betaflight_SITL.elf itself, in a temporary directory with a copy of
OUTDIR/eeprom.bin, once per run. --isolate runs everything in a private
network namespace (unshare -rn), so a SITL or simulator of someone else on
the same ports cannot interfere. Exit status 0 when every check passed, 1
when one failed, 2 on bad arguments.
"""

import argparse
import hashlib
import math
import os
import resource
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time

FDM_PORT = 9003
RC_PORT = 9004
MOTOR_PORT = 9002
HOST = "127.0.0.1"

FDM = struct.Struct("<18d")  # fdm_packet: timestamp, gyro[3], accel[3], quat[4], vel[3], pos[3], pressure
RC = struct.Struct("<d16H")  # rc_packet: timestamp, 16 channels (us)
MOTORS = struct.Struct("<4f")  # servo_packet: 4 motor outputs in [0, 1]

GRAVITY_M_S2 = 9.80665
SEA_LEVEL_PA = 101325.0

RC_LOW_US = 1000
RC_MID_US = 1500
RC_HIGH_US = 2000
# AETR channel order (map AETR1234): roll, pitch, throttle, yaw, AUX1, AUX2
CH_ROLL, CH_PITCH, CH_THROTTLE, CH_YAW, CH_AUX1, CH_AUX2 = range(6)

RC_RATE_HZ = 250  # default: a common radio link's frame rate; the failsafe needs RC well inside 1.5 s
ARM_TOGGLE_S = 0.1  # AUX1 low then high for this long each, until the motors arm
ARM_TIMEOUT_S = 10.0  # simulated seconds the boot may take before arming is allowed
# An armed motor output is at least the idle (0.055 with motor_idle 5.5 %); disarmed is exactly 0.
ARMED_MIN_OUTPUT = 0.01
HOVER_THROTTLE_US = 1300  # 26 % throttle: above airmode's 25 % start, so the PID acts fully
SETTLE_S = 0.3
REARM_S = 0.1
PROBE_S = 0.03  # long enough for an RC frame and its smoothing; the I term stays small against P and D
GYRO_PROBE_RAD_S = 1.0
STICK_PROBE_US = 100  # 140 deg/s with sitl.cli's linear 700 deg/s rates
TILT_PROBE_DEG = 10.0
TILT_PROBE_S = 1.0  # the attitude estimate follows the accelerometer within seconds
# A motor "rises" in a probe when its change is above half the largest change;
# the mixer moves the rising pair together and the other pair the other way.
RISE_FRACTION = 0.5
# A motor belongs to a stick's pattern when its change is above this fraction
# of the largest (QUADP's motors off the axis move by 0.000 to 0.001).
PATTERN_FRACTION = 0.25
# A gyro probe's own axis must carry this many times the command of any other
# axis in the motor change; measured about 10x or more (the other axes stay at
# zero but for output rounding to 0.001).
DOMINANT_FACTOR = 3.0
FIRST_REPLY_TIMEOUT_S = 30.0  # boot of the SITL before its first answer
REPLY_TIMEOUT_S = 5.0
DRAIN_S = 0.3
REALTIME_FACTOR_REQUIRED = 10.0


class CheckFailed(Exception):
    pass


def level_accel():
    """FDM accelerometer of a level vehicle at rest: the SITL reads
    -accel * 256 / g as Betaflight's body acceleration, so at rest the packet
    carries (0, 0, -g)."""
    return (0.0, 0.0, -GRAVITY_M_S2)


def rolled_accel(roll_deg):
    """FDM accelerometer of a vehicle at rest rolled right by roll_deg, as the
    level one above: the negated specific force in the body frame (x forward,
    y left, z up)."""
    phi = math.radians(roll_deg)
    return (0.0, -GRAVITY_M_S2 * math.sin(phi), -GRAVITY_M_S2 * math.cos(phi))


def own_cpu_s():
    """User plus system CPU time of this process so far (seconds)."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def quat_mul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )


def packet_quat(roll_deg):
    """FDM quaternion (w, x, y, z) of a vehicle rolled right by roll_deg at
    heading north, in the Gazebo-bridge convention the SITL undoes: it
    computes q = Rz(90 deg) * Rx(180 deg) * q_packet * Rx(180 deg), the
    attitude of the body (x forward, y left, z up) in the world (north, west,
    up). So the packet carries Rx(180) * Rz(-90) * q * Rx(180): the y and z
    parts of Rz(-90) * q negated."""
    half = math.radians(roll_deg) / 2.0
    roll = (math.cos(half), math.sin(half), 0.0, 0.0)
    rz_minus_90 = (math.sqrt(0.5), 0.0, 0.0, -math.sqrt(0.5))
    w, x, y, z = quat_mul(rz_minus_90, roll)
    return (w, x, -y, -z)


class Lockstep:
    """The simulator side: one FDM packet out, one motor packet back."""

    def __init__(self, rate_hz, rc_hz=RC_RATE_HZ):
        self.dt_s = 1.0 / rate_hz
        self.rc_every = max(1, round(rate_hz / rc_hz))
        self.out = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.inp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            self.inp.bind((HOST, MOTOR_PORT))
        except OSError as exc:
            raise CheckFailed(
                f"cannot bind UDP {HOST}:{MOTOR_PORT} for the motor packets ({exc}): another simulator "
                "runs on this machine; use --isolate"
            ) from exc
        self.tick = 0
        self.first_reply_wall_s = None
        self.digest = hashlib.sha256()
        self.replies = 0
        self.channels = [RC_MID_US] * 16
        self.channels[CH_THROTTLE] = RC_LOW_US
        self.channels[CH_AUX1] = RC_LOW_US
        self.channels[CH_AUX2] = RC_LOW_US
        self.gyro = [0.0, 0.0, 0.0]
        self.accel = list(level_accel())
        self.quat = list(packet_quat(0.0))

    def time_s(self):
        return self.tick * self.dt_s

    def step(self):
        """One tick: RC (every rc_every ticks), FDM, then the motor packet."""
        t = self.time_s()
        if self.tick % self.rc_every == 0:
            self.out.sendto(RC.pack(t, *self.channels), (HOST, RC_PORT))
        pkt = FDM.pack(
            t,
            *self.gyro,
            *self.accel,
            *self.quat,
            0.0, 0.0, 0.0,
            0.0, 0.0, 0.0,
            SEA_LEVEL_PA,
        )
        self.out.sendto(pkt, (HOST, FDM_PORT))
        if self.tick <= 1:
            self.inp.settimeout(FIRST_REPLY_TIMEOUT_S if self.tick == 0 else REPLY_TIMEOUT_S)
        try:
            data = self.inp.recv(64)
        except socket.timeout as exc:
            raise CheckFailed(
                f"no motor packet for FDM packet {self.tick} (t = {t:.6f} s) within "
                f"{self.inp.gettimeout():.0f} s: the SITL is not running, not a lockstep build, or dropped it"
            ) from exc
        if len(data) != MOTORS.size:
            raise CheckFailed(f"motor packet {self.replies}: {len(data)} bytes, expected {MOTORS.size}")
        if self.replies == 0:
            self.first_reply_wall_s = time.monotonic()  # the SITL's boot ends here
            self.first_reply_cpu_s = own_cpu_s()
        self.replies += 1
        self.digest.update(data)
        self.tick += 1
        return MOTORS.unpack(data)

    def run_for(self, seconds):
        motors = None
        for _ in range(round(seconds / self.dt_s)):
            motors = self.step()
        return motors

    def extra_replies(self):
        """Motor packets beyond one per FDM packet, counted after the last one."""
        self.inp.settimeout(DRAIN_S)
        extra = 0
        try:
            while True:
                self.inp.recv(64)
                extra += 1
        except socket.timeout:
            pass
        return extra

    def close(self):
        self.out.close()
        self.inp.close()


def rising(before, after):
    """Indices of the motors whose output rose by more than RISE_FRACTION of
    the largest change."""
    delta = [a - b for a, b in zip(after, before)]
    largest = max(abs(d) for d in delta)
    if largest <= 0.0:
        return frozenset(), delta
    return frozenset(i for i, d in enumerate(delta) if d > RISE_FRACTION * largest), delta


def fmt_motors(m):
    return "[" + ", ".join(f"{v:.3f}" for v in m) + "]"


def rearm(link):
    """Disarm, then arm again at hover throttle: each probe starts from a
    reset I term, not from the one the previous probe wound up (the vehicle in
    the packets never moves, so nothing unwinds it)."""
    link.channels[CH_AUX1] = RC_LOW_US
    link.channels[CH_THROTTLE] = RC_LOW_US
    link.run_for(REARM_S)
    link.channels[CH_AUX1] = RC_HIGH_US
    link.run_for(REARM_S)
    link.channels[CH_THROTTLE] = HOVER_THROTTLE_US
    return link.run_for(SETTLE_S)


def probe(link, name, apply, undo, seconds=PROBE_S):
    base = rearm(link)
    if min(base) < ARMED_MIN_OUTPUT:
        raise CheckFailed(f"{name}: not armed again after a disarm: outputs {fmt_motors(base)}")
    apply()
    first_change = None
    end = base
    for k in range(round(seconds / link.dt_s)):
        end = link.step()
        if first_change is None and end != base:
            first_change = k
    undo()
    up, delta = rising(base, end)
    return {"name": name, "up": up, "delta": delta, "first_change": first_change}


def fly(link, report):
    """The scenario; returns the findings as a dict."""
    found = {}

    # Boot and arm: toggle AUX1 until the motors leave 0.
    armed_at = None
    while link.time_s() < ARM_TIMEOUT_S:
        phase = int(link.time_s() / ARM_TOGGLE_S) % 2
        link.channels[CH_AUX1] = RC_HIGH_US if phase == 1 else RC_LOW_US
        motors = link.step()
        if any(v != 0.0 for v in motors):
            if min(motors) < ARMED_MIN_OUTPUT:
                raise CheckFailed(f"t = {link.time_s():.4f} s: motors moved but not all to idle: {fmt_motors(motors)}")
            armed_at = link.time_s()
            break
    if armed_at is None:
        raise CheckFailed(
            f"not armed after {ARM_TIMEOUT_S:.0f} s of simulated time with AUX1 toggled every "
            f"{ARM_TOGGLE_S} s: see the SITL's log for 'Arming disabled' flags"
        )
    link.channels[CH_AUX1] = RC_HIGH_US
    found["armed_at_s"] = armed_at
    found["armed_tick"] = link.tick
    idle = link.run_for(0.25)
    found["idle"] = idle
    report(f"armed at t = {armed_at:.3f} s (FDM packet {link.tick - round(0.25 / link.dt_s)}), idle outputs {fmt_motors(idle)}")

    link.channels[CH_THROTTLE] = HOVER_THROTTLE_US
    hover = link.run_for(SETTLE_S)
    found["hover"] = hover
    report(f"throttle {HOVER_THROTTLE_US} us: outputs {fmt_motors(hover)}")

    probes = []
    for axis, ch in (("roll", CH_ROLL), ("pitch", CH_PITCH), ("yaw", CH_YAW)):
        probes.append(
            probe(
                link,
                f"{axis} stick +{STICK_PROBE_US} us",
                lambda ch=ch: link.channels.__setitem__(ch, RC_MID_US + STICK_PROBE_US),
                lambda ch=ch: link.channels.__setitem__(ch, RC_MID_US),
            )
        )
    for i in range(3):
        probes.append(
            probe(
                link,
                f"FDM gyro[{i}] = +{GYRO_PROBE_RAD_S} rad/s",
                lambda i=i: link.gyro.__setitem__(i, GYRO_PROBE_RAD_S),
                lambda i=i: link.gyro.__setitem__(i, 0.0),
            )
        )
    link.channels[CH_AUX2] = RC_HIGH_US  # angle mode
    def tilt(roll_deg):
        link.accel[0:3] = rolled_accel(roll_deg)
        link.quat[0:4] = packet_quat(roll_deg)

    probes.append(
        probe(
            link,
            f"angle mode, FDM accel and quaternion of a {TILT_PROBE_DEG:.0f} deg right roll",
            lambda: tilt(TILT_PROBE_DEG),
            lambda: tilt(0.0),
            TILT_PROBE_S,
        )
    )
    link.channels[CH_AUX2] = RC_LOW_US
    for p in probes:
        report(
            f"{p['name']}: motors {sorted(p['up'])} rise, change {fmt_motors(p['delta'])}; first change in the "
            f"answer to the probe's FDM packet + {p['first_change']}"
        )
    found["probes"] = probes
    # speed over the ticks after the first answer (the first waits for the boot)
    found["wall_s"] = time.monotonic() - link.first_reply_wall_s
    found["client_cpu_s"] = own_cpu_s() - link.first_reply_cpu_s
    found["timed_ticks"] = link.tick - 1
    found["ticks"] = link.tick
    return found


def interpret(found, report):
    """Motor positions from the stick probes, the FDM sign conventions from
    the gyro and accelerometer probes; raises CheckFailed on a contradiction."""
    probes = found["probes"]
    # Each stick's pattern: per motor +1 (rises), -1 (falls) or 0 (stays), from
    # its change against the largest; QUADX moves every motor on every axis,
    # QUADP leaves the front and rear motors out of roll and the sides out of
    # pitch.
    patterns = []
    for name, p in zip(("roll", "pitch", "yaw"), probes[0:3]):
        largest = max(abs(d) for d in p["delta"])
        pattern = [0 if abs(d) <= PATTERN_FRACTION * largest else (1 if d > 0 else -1) for d in p["delta"]]
        if largest == 0.0 or 1 not in pattern or -1 not in pattern:
            raise CheckFailed(
                f"{name} stick: motor change {fmt_motors(p['delta'])}: no motor rose against another (Betaflight "
                "takes RC frames less than 800 us apart for an invalid rate: send RC at 1 kHz or less)"
            )
        patterns.append(pattern)
    roll, pitch, yaw = patterns
    positions = []
    for i in range(4):
        where = [w for w in ({1: "rear", -1: "front"}.get(pitch[i]), {1: "left", -1: "right"}.get(roll[i])) if w]
        if not where or yaw[i] == 0:
            raise CheckFailed(f"motor {i}: moved by no roll/pitch stick or by no yaw stick: no position")
        spin = "CCW" if yaw[i] > 0 else "CW"
        positions.append(f"{i}: {'-'.join(where)} ({spin} seen from above)")
    report("motor order (packet index: position, from the roll/pitch/yaw stick probes): " + "; ".join(positions))
    found["positions"] = positions

    # A probe's motor change split along the three stick patterns: how much of
    # it is a roll, pitch or yaw command in the stick's positive direction.
    def components(delta):
        return [sum(d * w for d, w in zip(delta, pattern)) / sum(w * w for w in pattern) for pattern in patterns]

    # A positive rate in a gyro field, if Betaflight reads it as the stick's
    # positive direction, is countered: a command against that direction. The
    # stick directions are the pilot's: roll right, nose down, nose right
    # (this last one with the motor spins above, Betaflight's default
    # props-in layout). The probed axis must carry most of the change.
    senses = []
    names = ("roll", "pitch", "yaw")
    for axis, positive, negative in (
        (0, "roll right", "roll left"),
        (1, "nose down", "nose up"),
        (2, "nose right (clockwise seen from above)", "nose left (counter-clockwise seen from above)"),
    ):
        comp = components(probes[3 + axis]["delta"])
        others = max(abs(c) for i, c in enumerate(comp) if i != axis)
        if abs(comp[axis]) <= DOMINANT_FACTOR * others:
            raise CheckFailed(
                f"FDM gyro[{axis}] probe: roll/pitch/yaw commands {fmt_motors(comp)}: the {names[axis]} "
                f"one is not {DOMINANT_FACTOR:.0f}x the others"
            )
        sense = positive if comp[axis] < 0.0 else negative
        senses.append(f"FDM gyro[{axis}] ({names[axis]}): a positive rate is read as {sense}")
    for line in senses:
        report(line)
    comp = components(probes[6]["delta"])
    report(f"accelerometer/quaternion tilt probe: roll/pitch/yaw commands {fmt_motors(comp)}")
    if abs(comp[0]) <= max(abs(comp[1]), abs(comp[2])):
        raise CheckFailed(f"tilt probe: roll/pitch/yaw commands {fmt_motors(comp)}: the roll one is not the largest")
    tilt_sense = "right" if comp[0] < 0.0 else "LEFT"
    report(
        f"FDM accel (0, -g sin r, -g cos r) with the quaternion of a right roll r is read as a {tilt_sense} roll "
        f"(angle mode commands a {'left' if comp[0] < 0.0 else 'right'} roll)"
    )
    found["senses"] = senses


def udp_port_bound(port):
    """Whether a UDP socket is bound to port in this network namespace."""
    hex_port = f":{port:04X}"
    with open("/proc/net/udp") as f:
        return any(line.split()[1].endswith(hex_port) for line in f.readlines()[1:])


def process_cpu_s(pid):
    """User plus system CPU time of a process so far (seconds)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    utime, stime = int(fields[11]), int(fields[12])  # fields 14 and 15 of proc(5)
    return (utime + stime) / os.sysconf("SC_CLK_TCK")


def start_sitl(outdir, workdir):
    elf = os.path.join(outdir, "betaflight_SITL.elf")
    eeprom = os.path.join(outdir, "eeprom.bin")
    for path in (elf, eeprom):
        if not os.path.isfile(path):
            raise CheckFailed(f"{path}: not found: build with tools/betaflight_sitl.sh CHECKOUT {outdir}")
    shutil.copyfile(eeprom, os.path.join(workdir, "eeprom.bin"))
    log_path = os.path.join(workdir, "sitl.log")
    log = open(log_path, "w")
    # line-buffered output (stdbuf) so the log is complete when the run is stopped
    command = ["stdbuf", "-oL", elf] if shutil.which("stdbuf") else [elf]
    proc = subprocess.Popen(command, cwd=workdir, stdout=log, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + FIRST_REPLY_TIMEOUT_S
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise CheckFailed(f"{elf} exited with status {proc.returncode} at start: see {log_path}")
        if udp_port_bound(FDM_PORT):
            return proc, log_path
        time.sleep(0.05)
    proc.kill()
    raise CheckFailed(f"{elf}: its FDM port {FDM_PORT} did not open within {FIRST_REPLY_TIMEOUT_S:.0f} s: see {log_path}")


def stop_sitl(proc):
    proc.terminate()
    try:
        proc.wait(timeout=3)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


def one_run(args, run_index, report):
    proc = None
    workdir = None
    link = None
    try:
        if args.launch:
            workdir = tempfile.mkdtemp(prefix=f"bf_sitl_run{run_index}_", dir=args.log_dir)
            link = Lockstep(args.rate_hz, args.rc_hz)  # bind the motor port before the SITL sends to it
            proc, log_path = start_sitl(args.launch, workdir)
            report(f"run {run_index}: SITL started, log {log_path}")
        else:
            link = Lockstep(args.rate_hz, args.rc_hz)
        found = fly(link, report)
        extra = link.extra_replies()
        found["extra"] = extra
        found["digest"] = link.digest.hexdigest()
        found["replies"] = link.replies
        if proc is not None:
            if proc.poll() is not None:
                raise CheckFailed(f"the SITL exited during the run with status {proc.returncode}")
            found["sitl_cpu_s"] = process_cpu_s(proc.pid)
        return found
    finally:
        if link is not None:
            link.close()
        if proc is not None:
            stop_sitl(proc)
        if workdir is not None and not args.keep_logs:
            shutil.rmtree(workdir, ignore_errors=True)


def parse_args(argv):
    parser = argparse.ArgumentParser(
        description="Check a lockstep Betaflight SITL built by tools/betaflight_sitl.sh (see the module docstring)."
    )
    parser.add_argument("--launch", metavar="OUTDIR", help="start OUTDIR/betaflight_SITL.elf for each run")
    parser.add_argument("--runs", type=int, help="runs to compare (default 2 with --launch, else 1)")
    parser.add_argument("--rate-hz", type=int, default=4000, help="FDM packets per simulated second (default 4000)")
    parser.add_argument(
        "--rc-hz", type=int, default=RC_RATE_HZ, help=f"RC packets per simulated second (default {RC_RATE_HZ})"
    )
    parser.add_argument("--isolate", action="store_true", help="run in a private network namespace (unshare -rn)")
    parser.add_argument("--log-dir", help="where the runs' directories go (default: the system temporary directory)")
    parser.add_argument("--keep-logs", action="store_true", help="keep each run's directory and SITL log")
    args = parser.parse_args(argv)
    if args.runs is None:
        args.runs = 2 if args.launch else 1
    if args.runs < 1:
        parser.error("--runs must be at least 1")
    if args.runs > 1 and not args.launch:
        parser.error("--runs above 1 needs --launch (every run needs a freshly started SITL)")
    if args.rate_hz <= 0 or 1_000_000 % args.rate_hz != 0 or (1_000_000 // args.rate_hz) % 125 != 0:
        parser.error("--rate-hz: the lockstep SITL needs a period that is a whole multiple of 125 us (8000, 4000, 2000, 1000, ...)")
    if args.rc_hz <= 0 or args.rc_hz > args.rate_hz or args.rate_hz % args.rc_hz != 0:
        parser.error("--rc-hz must divide --rate-hz (RC goes with every n-th FDM packet)")
    if args.launch and not os.path.isdir(args.launch):
        parser.error(f"--launch {args.launch}: not a directory")
    return args


def isolate(argv):
    """Re-run this script in a new network namespace with only loopback."""
    if not shutil.which("unshare"):
        print("--isolate needs unshare (util-linux)", file=sys.stderr)
        sys.exit(2)
    rest = [a for a in argv if a != "--isolate"]
    inner = " ".join(["ip link set lo up && exec", sys.executable, os.path.abspath(__file__)] + [f"'{a}'" for a in rest])
    os.execvp("unshare", ["unshare", "-rn", "sh", "-c", inner])


def main(argv):
    args = parse_args(argv)
    if args.isolate:
        isolate(argv)

    def report(line):
        print(line, flush=True)

    failures = []
    runs = []
    for run_index in range(1, args.runs + 1):
        try:
            found = one_run(args, run_index, report)
        except CheckFailed as exc:
            failures.append(f"run {run_index}: {exc}")
            break
        runs.append(found)
        sim_s = found["timed_ticks"] / args.rate_hz
        report(
            f"run {run_index}: {found['timed_ticks']} FDM packets after the first ({sim_s:.2f} s simulated) in "
            f"{found['wall_s']:.2f} s of wall time: {found['timed_ticks'] / found['wall_s']:.0f} round trips/s, "
            f"{sim_s / found['wall_s']:.1f}x real time"
        )
        report(
            f"run {run_index}: this script used {1e6 * found['client_cpu_s'] / found['timed_ticks']:.1f} us of CPU "
            "per FDM packet"
        )
        if "sitl_cpu_s" in found:
            report(
                f"run {run_index}: the SITL used {found['sitl_cpu_s']:.2f} s of CPU (boot included): "
                f"{1e6 * found['sitl_cpu_s'] / found['ticks']:.1f} us per FDM packet"
            )
        if found["extra"] != 0 or found["replies"] != found["ticks"]:
            failures.append(
                f"run {run_index}: lockstep broken: {found['ticks']} FDM packets, {found['replies']} answered, "
                f"{found['extra']} motor packets more after the last"
            )
        else:
            report(f"run {run_index}: lockstep: exactly one motor packet per FDM packet ({found['ticks']})")
        try:
            interpret(found, report)
        except CheckFailed as exc:
            failures.append(f"run {run_index}: {exc}")
        if sim_s / found["wall_s"] < REALTIME_FACTOR_REQUIRED:
            failures.append(
                f"run {run_index}: {sim_s / found['wall_s']:.1f}x real time, below the {REALTIME_FACTOR_REQUIRED:.0f}x needed "
                "(the machine's load counts: see the CPU figures above)"
            )
        report(f"run {run_index}: motor packets sha256 {found['digest']}")
    if len(runs) > 1:
        digests = {r["digest"] for r in runs}
        if len(digests) == 1 and len({r["ticks"] for r in runs}) == 1:
            report(f"determinism: {len(runs)} runs gave identical motor packets, byte for byte")
        else:
            failures.append(f"determinism: the {len(runs)} runs' motor packets differ")
    for f in failures:
        print(f"FAIL: {f}", file=sys.stderr)
    if not failures:
        report("all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
