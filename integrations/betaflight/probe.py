#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Probe a Betaflight SITL build over its UDP links, without a simulator.

    probe.py SITL_EXE [--pidsum-limit 500] [--motor-idle 550] [--workdir DIR]

Configures the SITL (its --config CLI file: ARM on AUX1, AIRMODE), starts it,
feeds it a level, still airframe (FDM packets to UDP 9003) and centred sticks
at low throttle (RC packets to UDP 9004), arms, then fakes body rates and
reads the four motor outputs it sends (UDP 9002). From Betaflight's quad X
mix and its motor range it reads each axis's pidSum back out of the motors:

    motor_i = (outputLow - mincommand) / 1000 + R (throttle + sum_a mix_ia pidSum_a / 1000)
    R = (maxthrottle - outputLow) / 1000,  outputLow = 1000 + motor_idle / 10

and checks the direction each axis's command takes against the faked rate
(a rate above the setpoint must be opposed) and, held, that the command ends
at the pidSum bound (the mixer's constrain): the faked rate does not answer
the motors, so the ladrc rate loop's observer takes the unanswered command
for a disturbance and the command runs to the bound. (Betaflight's own PID
at zero throttle holds its P term there: its I term is held until the
throttle is first raised, so a build without the hook fails that check.)
Prints one line per phase; exits 1 on a failed check, 2 when the SITL cannot
be driven (ports busy, not armed, no motor packets).
"""
import argparse
import os
import socket
import struct
import subprocess
import sys
import tempfile
import time

FDM_PORT, RC_PORT, MOTOR_PORT = 9003, 9004, 9002
FDM_FORMAT = "<d3d3d4d3d3dd"  # fdm_packet: timestamp, gyro rpy, accel, quat wxyz, velocity, position, pressure
RC_FORMAT = "<d16H"  # rc_packet: timestamp, 16 channels (AETR, AUX1..)
MOTOR_FORMAT = "<4f"  # servo_packet: motor_speed[4]
ARM_WAIT_S = 15.0  # boot grace time and re-arm hold-off, with room
G = 9.80665
DEG = 3.141592653589793 / 180.0
# Betaflight's QUAD X mix (mixer_init.c mixerQuadX): (roll, pitch, yaw) per motor, the
# yaw column negated as the mixer negates the yaw pidSum (yaw_motors_reversed off)
QUAD_X = [(-1.0, 1.0, 1.0), (-1.0, -1.0, -1.0), (1.0, 1.0, -1.0), (1.0, -1.0, 1.0)]


def axis_pidsums(motors, motor_range):
    """Least squares of the mix: each axis's pidSum from the four motors."""
    sums = []
    for a in range(3):
        # the QUAD X columns are orthogonal, each of norm^2 = 4
        sums.append(1000.0 * sum(m * QUAD_X[i][a] for i, m in enumerate(motors)) / (4.0 * motor_range))
    return sums


class Sitl:
    def __init__(self, exe, workdir, cli_lines):
        self.exe, self.workdir = exe, workdir
        # the SITL's ports are fixed: a SITL or a simulator bridge already on
        # them would take this probe's packets
        self.rx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            self.rx.bind(("127.0.0.1", MOTOR_PORT))
            for port in (FDM_PORT, RC_PORT):
                with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
                    s.bind(("0.0.0.0", port))
        except OSError as e:
            print(f"probe.py: UDP port busy ({e}): another Betaflight SITL or simulator bridge is running", file=sys.stderr)
            sys.exit(2)
        self.rx.settimeout(0.2)
        self.tx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        cli = os.path.join(workdir, "probe.cli")
        with open(cli, "w") as f:
            f.write("\n".join(cli_lines + ["save"]) + "\n")
        self.log = open(os.path.join(workdir, "sitl.log"), "w")
        subprocess.run([exe, "--config", cli], cwd=workdir, stdout=self.log, stderr=subprocess.STDOUT, timeout=60, check=True)
        self.proc = subprocess.Popen([exe], cwd=workdir, stdout=self.log, stderr=subprocess.STDOUT)
        self.t0 = time.monotonic()

    def close(self):
        self.proc.terminate()
        try:
            self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        self.log.close()

    def now(self):
        return time.monotonic() - self.t0

    def send(self, rates_rad_s, aux1, throttle=1000):
        t = self.now()
        fdm = struct.pack(FDM_FORMAT, t, *rates_rad_s, 0.0, 0.0, -G, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 101325.0)
        channels = [1500, 1500, throttle, 1500, aux1] + [1000] * 11
        self.tx.sendto(fdm, ("127.0.0.1", FDM_PORT))
        self.tx.sendto(struct.pack(RC_FORMAT, t, *channels), ("127.0.0.1", RC_PORT))

    def run(self, seconds, rates_rad_s, aux1, period_s=0.002):
        """Feeds the links for a while; returns the motor packets received."""
        got = []
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.send(rates_rad_s, aux1)
            try:
                while True:
                    self.rx.settimeout(period_s)
                    data = self.rx.recv(64)
                    if len(data) == struct.calcsize(MOTOR_FORMAT):
                        got.append((self.now(), struct.unpack(MOTOR_FORMAT, data)))
            except socket.timeout:
                pass
        return got


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sitl_exe")
    ap.add_argument("--pidsum-limit", type=float, default=500.0, help="Betaflight's pidsum_limit (roll, pitch)")
    ap.add_argument("--pidsum-limit-yaw", type=float, default=400.0, help="Betaflight's pidsum_limit_yaw")
    ap.add_argument("--motor-idle", type=float, default=550.0, help="Betaflight's motor_idle (percent x 100)")
    ap.add_argument("--workdir", help="where the SITL keeps eeprom.bin and its log (default: a new temporary folder)")
    args = ap.parse_args()
    workdir = args.workdir or tempfile.mkdtemp(prefix="bf_probe_")
    os.makedirs(workdir, exist_ok=True)
    output_low = 1000.0 + args.motor_idle / 10.0
    motor_range = (2000.0 - output_low) / 1000.0
    failed = []
    sitl = Sitl(os.path.abspath(args.sitl_exe), workdir, ["feature AIRMODE", "aux 0 0 0 1700 2100 0 0"])

    def phase(name, seconds, rates_deg_s, aux1=2000):
        packets = sitl.run(seconds, [r * DEG for r in rates_deg_s], aux1)
        if not packets:
            print(f"{name}: no motor packets on UDP {MOTOR_PORT} (see {workdir}/sitl.log)")
            sitl.close()
            sys.exit(2)
        motors = packets[-1][1]
        sums = axis_pidsums(motors, motor_range)
        print(f"{name}: {len(packets)} packets, motors {' '.join(f'{m:.4f}' for m in motors)}, "
              f"pidSum roll {sums[0]:+.1f} pitch {sums[1]:+.1f} yaw {sums[2]:+.1f}")
        return motors, sums, packets

    def arm(case):
        """Flips the ARM switch off and on until the motors idle (Betaflight
        refuses to arm during its boot grace time, and until it has seen the
        switch off after a refusal)."""
        waited = 0.0
        while waited < ARM_WAIT_S:
            sitl.run(0.5, (0.0, 0.0, 0.0), 1000)
            packets = sitl.run(0.5, (0.0, 0.0, 0.0), 2000)
            waited += 1.0
            if packets and min(packets[-1][1]) > 0.0:
                motors = packets[-1][1]
                if max(motors) - min(motors) > 1e-3:
                    failed.append(f"{case}: armed and still, motors {motors} not equal")
                print(f"{case}: armed after {waited:.0f} s, motors {' '.join(f'{m:.4f}' for m in motors)}")
                return
        print(f"{case}: not armed after {ARM_WAIT_S:.0f} s of flipping the ARM switch (see {workdir}/sitl.log)")
        sitl.close()
        sys.exit(2)

    try:
        phase("disarmed, still", 1.0, (0, 0, 0), aux1=1000)
        for axis, name in enumerate(("roll", "pitch", "yaw")):
            for sign in (+1, -1):
                # a fresh start for each case: the faked rate does not answer the
                # motors, so a disturbance observer (or an I term) keeps what it
                # learnt; disarming resets it
                arm(f"{name} {sign * 100:+.0f} deg/s case")
                rates = [0.0, 0.0, 0.0]
                rates[axis] = sign * 100.0
                _, first, _ = phase(f"{name} rate {sign * 100:+.0f} deg/s, 0.05 s", 0.05, rates)
                _, held, _ = phase(f"{name} rate {sign * 100:+.0f} deg/s, held 1 s", 1.0, rates)
                limit = args.pidsum_limit if axis < 2 else args.pidsum_limit_yaw
                # Betaflight's gyro pitch is the simulator's negated (sitl_gyro.h); the others keep theirs
                opposed = -sign if axis != 1 else sign
                if not (first[axis] * opposed > 0.0):
                    failed.append(f"{name} {sign * 100:+.0f} deg/s: first command {first[axis]:+.1f} does not oppose the rate")
                if abs(held[axis] - opposed * limit) > 0.02 * limit:
                    failed.append(f"{name} {sign * 100:+.0f} deg/s held: {held[axis]:+.1f}, not at the bound {opposed * limit:+.0f}")
        motors, sums, _ = phase("disarmed again", 0.5, (0, 0, 0), aux1=1000)
        if max(motors) > 1e-3:
            failed.append(f"disarmed: motors {motors} not stopped")
    finally:
        sitl.close()
    for f in failed:
        print("FAILED: " + f)
    print(f"SITL log: {workdir}/sitl.log")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
