#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The library inside Betaflight against the same controller flown natively.

Usage: betaflight_match.py SITL_LADRC_DIR [--sim LADRC_SIL] [--work DIR] [--config matched|defaults|both]
                           [--doc FILE|-] [--bf-commit HASH] [CASE.ini ...]

SITL_LADRC_DIR is the OUTDIR of tools/betaflight_sitl.sh CHECKOUT OUTDIR --ladrc
--ladrc-params FILE (any parameters file): its build copy OUTDIR/tree, with
the lockstep hooks and the library in, is what the script rebuilds with each
case's parameters (integrations/betaflight/apply.sh, then make TARGET=SITL
OPTIONS=SITL_LOCKSTEP=1, incremental: only the parameters' header changes;
one build per distinct parameters file and CLI configuration, kept under
DIR/<config>/sitl/; the tree is left with the last case's parameters,
OUTDIR's own betaflight_SITL.elf and eeprom.bin untouched). Each case (default: scenarios/suite,
scenarios/vibration, scenarios/large_angle) is flown twice with the same
pilot:

  native      ladrc_sil CASE --controllers RATE-ADRC, [controller RATE-ADRC]
              pilot = acro, pilot_pulse = yes: the library's RATE-ADRC rate
              loop in acro, its setpoint the pilot's stick pulse; its gains
              tuned by the case's own tune = margins;
  betaflight  ladrc_sil CASE --controllers BETAFLIGHT with that SITL: the same
              rate loop, gains (k_w, wo per axis) and airframe model (b0 from
              params.py, the case's motor lag and delay) compiled into
              Betaflight as its rate controller, configured by
              tools/betaflight/sitl.cli and the case's lines; in its own
              network namespace (the SITL's UDP ports are fixed machine-wide).

Configurations (CONFIGS below): matched (the same rotor floor, gyro low-pass
and no RC smoothing on both sides) and defaults (Betaflight's own). It
prints, and writes into --doc (docs/betaflight-match.md unless told; "-":
none), per case and axis the RMS tracking error of each and their ratio; a
ratio more than 5 % from 1 is marked as a miss. Exit status 0 when every
case flew (a miss is a result, not a failure), 1 when a build or a run
failed (its output named, the doc not written), 2 on bad usage.
"""

import argparse
import csv
import glob
import hashlib
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import output_files  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
DEFAULT_CASES = ["scenarios/suite/*.ini", "scenarios/vibration/*.ini", "scenarios/large_angle/*.ini"]
AXES = ("roll", "pitch", "yaw")
TOLERANCE = 0.05  # the acceptance: within 5 % RMS on every case and axis
# The lockstep SITL's virtual gyro samples at 8 kHz (tools/betaflight/
# patch_sitl.py), its PID loop every pid_process_denom samples (1..16,
# Betaflight's MAX_PID_PROCESS_DENOM): the case's control step must be a
# whole number of samples within that.
SITL_GYRO_DT_S = 1.0 / 8000
PID_DENOM_MAX = 16
# The bridge sends an RC frame with every state packet at 1 kHz and slower,
# with every n-th one faster (runner_bf.c BF_RC_PERIOD_S): a faster case's
# sticks would change every n-th tick in Betaflight and every tick in the
# native twin, so such a case flies at this step on both sides.
RC_FRAME_S = 1e-3
# The pilot's full stick (deg/s): the bridge's default and the SITL's linear
# rate; 1.4 deg/s per microsecond of pulse.
RATE_MAX_DEG_S = 700
# Betaflight's PWM idle is motor_idle / 10000 of full command (its lowest
# armed output, params.py --motor-idle); the match sets it to the rotors' own
# floor w2_min / w2_max (linear rotors), so both sides' rotors have the same range.
MOTOR_IDLE_MAX = 2000  # Betaflight's bound on motor_idle (20 %)
# The start-up line of the adapter's glue (ladrc_bf_hook.c): the loop it runs.
LOOP_LINE = re.compile(r"\[ladrc\] rate loop on: .* loop ([0-9.]+) s")
TUNED_LINE = re.compile(
    r"^tuned RATE-ADRC (roll|pitch|yaw): k_att \S+ 1/s k_w (\S+) 1/s wo (\S+) rad/s", re.MULTILINE)


# Betaflight's gyro low-pass 1 at its static default (gyro.h GYRO_LPF1_DYN_MIN_HZ_DEFAULT), a PT1.
BF_LPF1_HZ = 250.0


def pt1_twin_hz(cutoff_hz, samples, dt_s):
    """The cutoff (Hz) of the library's first-order low-pass at the control
    step dt_s (bilinear, gyro_filter.h: pole (1 - K) / (1 + K), K = tan(pi fc
    dt)) whose pole per tick is that of Betaflight's PT1 at cutoff_hz run
    over the `samples` gyro samples of a tick (each step y += k (x - y),
    k = dT / (dT + 1 / (2 pi fc)), dT = dt_s / samples: pole (1 - k)^samples)."""
    dt_gyro = dt_s / samples
    k = dt_gyro / (dt_gyro + 1.0 / (2.0 * math.pi * cutoff_hz))
    pole = (1.0 - k) ** samples
    return math.atan((1.0 - pole) / (1.0 + pole)) / (math.pi * dt_s)


class Refused(Exception):
    """A case or a build that cannot be flown: the message says where and why."""


def read_ini(path):
    """{section: {key: (value, line)}} of the keys this script reads (the last
    of a repeated key; [reference] and [disturbance] pieces are not read)."""
    sections, section = {}, None
    for number, raw in enumerate(Path(path).read_text().splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if line.startswith("["):
            section = line.strip("[]").strip()
            sections.setdefault(section, {})
        elif "=" in line and section is not None:
            key, value = (part.strip() for part in line.split("=", 1))
            sections[section][key] = (value, number)
    return sections


def need(ini, path, section, key, count=1, default=None):
    """The numbers of section.key; a missing key is refused naming it."""
    entry = ini.get(section, {}).get(key)
    if entry is None:
        if default is not None:
            return default
        raise Refused(f"{path}: [{section}] {key} missing: the match reads it (the SITL's airframe model and loop)")
    value, number = entry
    parts = value.split()
    try:
        numbers = [float(p) for p in parts]
    except ValueError:
        raise Refused(f"{path}:{number}:1: [{section}] {key} = {value}: not {count} number(s)") from None
    if len(numbers) != count:
        raise Refused(f"{path}:{number}:1: [{section}] {key} = {value}: {count} number(s) expected")
    return numbers


class Case:
    """One case as both sides fly it: its airframe, loop and the settings
    (ladrc_sil --set) common to both."""

    def __init__(self, path, config):
        self.path = Path(path)
        self.name = self.path.stem
        ini = read_ini(path)
        p = str(path)
        self.inertia = need(ini, p, "vehicle", "inertia_kg_m2", 3)
        scale = need(ini, p, "mismatch", "inertia_scale", 3, default=[1.0, 1.0, 1.0])
        self.model_inertia = [j * s for j, s in zip(self.inertia, scale)]  # what the controllers believe
        self.arm_m = need(ini, p, "vehicle", "arm_m")[0]
        self.thrust_coeff = need(ini, p, "vehicle", "thrust_coeff_N_s2")[0]
        self.yaw_coeff = need(ini, p, "vehicle", "yaw_coeff_Nm_s2")[0]
        self.w2_max = need(ini, p, "rotors", "w2_max_rad2_s2")[0]
        w2_min = need(ini, p, "rotors", "w2_min_rad2_s2")[0]
        self.motor_idle = int(round(10000 * w2_min / self.w2_max)) if config["idle"] == "floor" else config["idle"]
        if not 0 <= self.motor_idle <= MOTOR_IDLE_MAX:
            raise Refused(f"{p}: [rotors] w2_min_rad2_s2 / w2_max_rad2_s2 = {w2_min / self.w2_max:g}: no Betaflight "
                          f"motor_idle within 0..{MOTOR_IDLE_MAX} (0.01 %) gives that floor")
        if "thrust_curve" in ini.get("rotors", {}):
            raise Refused(f"{p}:{ini['rotors']['thrust_curve'][1]}:1: [rotors] thrust_curve: the match flies linear "
                          "rotors only (params.py --hover-command would need the hover command)")
        self.motor_tau_s = need(ini, p, "rotors", "motor_tau_s", default=[0.0])[0]
        dt = need(ini, p, "run", "control_dt_s")[0]
        delay = int(need(ini, p, "sensors", "delay_ticks", default=[0.0])[0])
        self.case_dt_s, self.case_delay = dt, delay
        self.sets = []
        denom = dt / SITL_GYRO_DT_S
        if dt < RC_FRAME_S - 1e-12 or abs(denom - round(denom)) > 1e-6 or not 1 <= round(denom) <= PID_DENOM_MAX:
            # both fly at the RC frame's step, with the same delay in time
            dt = RC_FRAME_S
            denom = dt / SITL_GYRO_DT_S
            delay = int(round(self.case_delay * self.case_dt_s / dt))
            self.sets += [f"run.control_dt_s={dt:g}", f"sensors.delay_ticks={delay}"]
        self.pid_denom, self.dt_s, self.delay_ticks = int(round(denom)), dt, delay
        self.filter_cli = []
        self.native_filter_note = ""
        self.rc_smoothing_cli = f"set rc_smoothing = {config['rc_smoothing']}"
        if config["filters"] == "matched":
            self.match_filters(ini, p)

    def match_filters(self, ini, p):
        """Betaflight's gyro filter set to one the native twin's [filter] has
        too: the case's low-pass when it has one; else Betaflight's own first
        stage at its static default (a 250 Hz PT1) and natively the first
        order with the same pole per control tick (pt1_twin_hz). The second
        low-pass off (the SITL has no dynamic notch, no RPM filter)."""
        f = ini.get("filter", {})
        on = f.get("enabled", ("yes", 0))[0] == "yes" and "lpf_hz" in f
        if on and "notch_hz" in f:
            raise Refused(f"{p}:{f['notch_hz'][1]}:1: [filter] notch_hz: no Betaflight twin of it in the matched "
                          "configuration")
        if on and "rpm_harmonics" in f:
            # the SITL has no RPM filter (no DShot telemetry): both fly the low-pass alone
            self.sets.append("filter.rpm_harmonics=0")
            self.native_filter_note = "RPM notches off on both (the SITL has no RPM filter)"
        order = int(need(ini, p, "filter", "lpf_order", default=[2.0])[0]) if on else 1
        hz = need(ini, p, "filter", "lpf_hz")[0] if on else BF_LPF1_HZ
        native_hz = hz if on else pt1_twin_hz(BF_LPF1_HZ, self.pid_denom, self.dt_s)
        if not on:
            self.native_filter_note = f"native first order at {native_hz:.1f} Hz"
        self.sets += ["filter.enabled=yes", "filter.angle=no", f"filter.lpf_order={order}",
                      f"filter.lpf_hz={native_hz:.6g}"]
        self.filter_cli = [
            "set simplified_gyro_filter = OFF",
            f"set gyro_lpf1_type = {'BIQUAD' if order == 2 else 'PT1'}",
            f"set gyro_lpf1_static_hz = {hz:g}",
            "set gyro_lpf1_dyn_min_hz = 0",
            "set gyro_lpf2_static_hz = 0",
        ]


def run(cmd, what, cwd=None):
    """stdout of a command; a failure raises Refused with its output's end."""
    proc = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if proc.returncode != 0:
        tail = "\n".join(proc.stdout.strip().splitlines()[-12:])
        raise Refused(f"{what} failed (exit status {proc.returncode}): {' '.join(map(str, cmd))}\n{tail}")
    return proc.stdout


def rms_of(out_dir, scenario, controller):
    """{axis: RMS tracking error (deg)} from a run's metrics.csv."""
    path = Path(out_dir) / scenario / "metrics.csv"
    found = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["controller"] == controller and row["quantity"] == "error_rms_deg":
                found[row["axis"]] = float(row["value"])
    missing = [a for a in AXES if a not in found]
    if missing:
        raise Refused(f"{path}: no error_rms_deg of {controller} on {', '.join(missing)}")
    return found


def trace_gap(out_bf, out_native, scenario):
    """{axis: RMS of the two runs' tracking-error difference (deg)} over the
    ticks both flew, from their time series."""
    series = []
    for out, ctrl in ((out_bf, "BETAFLIGHT"), (out_native, "RATE-ADRC")):
        with open(Path(out) / scenario / f"{ctrl}.csv", newline="") as f:
            series.append([[float(r[f"error_{a}_deg"]) for a in AXES] for r in csv.DictReader(f)])
    n = min(len(series[0]), len(series[1]))
    return {a: math.sqrt(sum((series[0][k][i] - series[1][k][i]) ** 2 for k in range(n)) / n)
            for i, a in enumerate(AXES)}


def params_file(case, gains, work):
    """The case's parameters file (params.py) for its tuned gains; its path."""
    path = Path(work) / "params" / f"{case.name}.params"
    path.parent.mkdir(parents=True, exist_ok=True)
    run([sys.executable, str(REPO / "integrations/betaflight/params.py"),
         "--inertia", *map(repr, case.model_inertia), "--arm-m", repr(case.arm_m),
         "--thrust-coeff", repr(case.thrust_coeff), "--yaw-coeff", repr(case.yaw_coeff),
         "--w2-max", repr(case.w2_max), "--frame", "quadp", "--motor-idle", str(case.motor_idle),
         "--k-w", *[repr(gains[a][0]) for a in AXES], "--wo", *[repr(gains[a][1]) for a in AXES],
         "--motor-tau-s", repr(case.motor_tau_s), "--delay-ticks", str(case.delay_ticks), "-o", str(path)],
        "params.py")
    return path


def sitl_for(case, params, tree, work):
    """A SITL folder (program, eeprom.bin) with the case's parameters and CLI
    configuration; built once per distinct pair."""
    base = (REPO / "tools/betaflight/sitl.cli").read_text().splitlines()
    cli = [line for line in base if line.strip() != "save"]  # one save, at the end
    cli += ["# ---- tools/betaflight_match.py: the case's lines",
            f"set pid_process_denom = {case.pid_denom}", f"set motor_idle = {case.motor_idle}"]
    cli += [f"set {axis}_rc_rate = {RATE_MAX_DEG_S // 10}" for axis in AXES]
    cli += [f"set {axis}_srate = {RATE_MAX_DEG_S // 10}" for axis in AXES]
    cli += case.filter_cli + [case.rc_smoothing_cli, "save"]
    cli_text = "\n".join(cli) + "\n"
    digest = hashlib.sha256(Path(params).read_bytes() + cli_text.encode()).hexdigest()[:12]
    out = Path(work) / "sitl" / digest
    if (out / "eeprom.bin").is_file():
        return out
    run(["bash", str(REPO / "integrations/betaflight/apply.sh"), str(tree), str(REPO), str(params)], "apply.sh")
    run(["make", "-C", str(tree), "TARGET=SITL", "OPTIONS=SITL_LOCKSTEP=1", f"-j{os.environ.get('JOBS', '2')}"],
        "make TARGET=SITL")
    built = Path(tree) / "obj/main/betaflight_SITL.elf"
    tmp = out.with_suffix(".tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir(parents=True)
    shutil.copy2(built, tmp / "sitl.elf")
    (tmp / "match.cli").write_text(cli_text)
    # the program the bridge starts: the build with its output kept beside it
    # (the bridge removes its working folder; the loop check reads the output)
    wrapper = tmp / "betaflight_SITL.elf"
    wrapper.write_text(f'#!/bin/sh\nexec "{out}/sitl.elf" "$@" > "{out}/last_output.txt" 2>&1\n')
    wrapper.chmod(0o755)
    log = run(["unshare", "-n", "sh", "-c", "ip link set lo up; exec ./sitl.elf --config match.cli"],
              "SITL --config", cwd=tmp)
    (tmp / "config.log").write_text(log)
    refused = [line for line in log.splitlines() if "###ERROR" in line]
    if refused:
        raise Refused(f"{tmp}/config.log: the SITL refused CLI lines of match.cli: " + "; ".join(refused))
    if "EEPROM saved" not in log or not (tmp / "eeprom.bin").is_file():
        raise Refused(f"{tmp}/config.log: the SITL saved no eeprom.bin from match.cli")
    tmp.rename(out)
    return out


def fly_case(case, args, work):
    native_out, bf_out = work / "native", work / "betaflight"
    sets = [x for s in case.sets for x in ("--set", s)]
    pilot = ["--set", "controller:RATE-ADRC.pilot=acro", "--set", "controller:RATE-ADRC.pilot_pulse=yes",
             "--set", f"controller:RATE-ADRC.pilot_rate_max_deg_s={RATE_MAX_DEG_S}"]
    text = run([args.sim, str(case.path), "--controllers", "RATE-ADRC", "--quiet", "--out", str(native_out), *sets,
                *pilot], f"ladrc_sil (native) {case.path}")
    gains = {m.group(1): (float(m.group(2)), float(m.group(3))) for m in TUNED_LINE.finditer(text)}
    missing = [a for a in AXES if a not in gains]
    if missing:
        raise Refused(f"{case.path}: no tuned RATE-ADRC gains printed for {', '.join(missing)} "
                      "(the match takes the gains of [controller RATE-ADRC] tune = margins)")
    params = params_file(case, gains, work)
    sitl = sitl_for(case, params, args.tree, work)
    run(["unshare", "-n", "sh", "-c", 'ip link set lo up; exec "$0" "$@"', args.sim, str(case.path), "--controllers",
         "BETAFLIGHT", "--quiet", "--betaflight", str(sitl), "--out", str(bf_out), *sets,
         "--set", f"controller:BETAFLIGHT.rate_max_deg_s={RATE_MAX_DEG_S}"],
        f"ladrc_sil (BETAFLIGHT) {case.path}")
    loop = LOOP_LINE.search((sitl / "last_output.txt").read_text(errors="replace"))
    if loop is None or abs(float(loop.group(1)) - case.dt_s) > 1e-6:
        raise Refused(f"{sitl}/last_output.txt: the SITL's rate loop ran at "
                      f"{loop.group(1) if loop else 'an unknown period'} s, the case at {case.dt_s:g} s")
    return {"gains": gains, "bf": rms_of(bf_out, case.name, "BETAFLIGHT"),
            "native": rms_of(native_out, case.name, "RATE-ADRC"), "gap": trace_gap(bf_out, native_out, case.name)}


def bf_commit(args):
    """The checkout's commit as BUILD_INFO records it, or --bf-commit."""
    info = Path(args.sitl_dir) / "BUILD_INFO"
    text = info.read_text()
    if "ladrc rate controller: yes" not in text:
        raise Refused(f"{info}: not a --ladrc build (tools/betaflight_sitl.sh CHECKOUT OUTDIR --ladrc "
                      "--ladrc-params FILE makes one)")
    found = re.search(r"^commit: (\S+)", text, re.MULTILINE)
    if args.bf_commit:
        return args.bf_commit
    if found is None or found.group(1) == "unknown":
        raise Refused(f"{info}: no commit recorded (a checkout without git): give it with --bf-commit HASH")
    return found.group(1)


def relative(path):
    try:
        return str(Path(path).resolve().relative_to(REPO))
    except ValueError:
        return str(path)


def report(rows, name, commit):
    """The table (markdown lines) of the cases flown in one configuration."""
    lines = [
        "| case | flown at | axis | k_w (1/s) | wo (rad/s) | Betaflight RMS (deg) | native RMS (deg) | ratio - 1 "
        "| traces' gap RMS (deg) | within 5 % |",
        "|---|---|---|---|---|---|---|---|---|---|"]
    misses = 0
    for case, r in rows:
        flown = f"{case.dt_s * 1e3:g} ms, {case.delay_ticks} tick(s)"
        if case.dt_s != case.case_dt_s:
            flown += f" (file: {case.case_dt_s * 1e3:g} ms, {case.case_delay})"
        flown += f"; motor_idle {case.motor_idle}"
        if case.native_filter_note:
            flown += f"; {case.native_filter_note}"
        for a in AXES:
            ratio = r["bf"][a] / r["native"][a] - 1.0 if r["native"][a] > 0 else math.inf
            ok = abs(ratio) <= TOLERANCE
            misses += not ok
            lines.append(f"| {relative(case.path) if a == 'roll' else ''} | {flown if a == 'roll' else ''} | {a} "
                         f"| {r['gains'][a][0]:.4g} | {r['gains'][a][1]:.4g} | {r['bf'][a]:.4f} | {r['native'][a]:.4f} "
                         f"| {ratio * 100:+.1f} % | {r['gap'][a]:.4f} | {'yes' if ok else '**no**'} |")
    total = 3 * len(rows)
    lines += ["", f"{total - misses} of {total} case-axes within 5 % (configuration `{name}`, Betaflight {commit})."]
    return lines


# The configurations flown: "matched" gives both sides the same rotor range
# (motor_idle at the rotors' floor), the same gyro low-pass and no RC
# smoothing (Betaflight's smoothing of the setpoint has no twin in the
# native run); "defaults" keeps Betaflight's own filters, RC smoothing and
# idle, the native run the case's own [filter].
CONFIGS = {
    "matched": {"filters": "matched", "rc_smoothing": "OFF", "idle": "floor"},
    "defaults": {"filters": "default", "rc_smoothing": "ON", "idle": 550},
}


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("sitl_dir", metavar="SITL_LADRC_DIR")
    ap.add_argument("cases", nargs="*")
    ap.add_argument("--sim", default=str(REPO / "build/host-release/sim/ladrc_sil"))
    ap.add_argument("--work", default=str(REPO / "build/betaflight-match"))
    ap.add_argument("--config", choices=(*CONFIGS, "both"), default="both")
    ap.add_argument("--doc", default=str(REPO / "docs/betaflight-match.md"))
    ap.add_argument("--bf-commit")
    args = ap.parse_intermixed_args(argv)
    cases = args.cases or sorted(p for g in DEFAULT_CASES for p in glob.glob(str(REPO / g)))
    if args.doc != "-":
        template = str(REPO / "tools/betaflight_match_doc.md")
        output_files.refuse_inputs("betaflight_match.py", {"--doc": args.doc}, [template, *cases])
    names = list(CONFIGS) if args.config == "both" else [args.config]
    tables = {}
    try:
        args.tree = Path(args.sitl_dir) / "tree"
        for need in ("BUILD_INFO", "tree/src/platform/SIMULATOR/sitl_lockstep.c", "tree/src/main/ladrc"):
            if not (Path(args.sitl_dir) / need).exists():
                raise Refused(f"{args.sitl_dir}/{need}: missing: SITL_LADRC_DIR must be the OUTDIR of "
                              "tools/betaflight_sitl.sh CHECKOUT OUTDIR --ladrc --ladrc-params FILE")
        if not os.access(args.sim, os.X_OK):
            raise Refused(f"{args.sim}: no ladrc_sil there (--sim PATH)")
        commit = bf_commit(args)
        for name in names:
            rows = []
            for path in cases:
                case = Case(path, CONFIGS[name])
                print(f"{name}: {relative(path)}: flying", file=sys.stderr, flush=True)
                rows.append((case, fly_case(case, args, Path(args.work) / name)))
            tables[name] = report(rows, name, commit)
    except Refused as exc:
        print(f"betaflight_match.py: {exc}", file=sys.stderr)
        return 1
    for name in names:
        print(f"{name}:")
        print("\n".join(tables[name]))
    if args.doc != "-":
        write_doc(args.doc, tables, commit, cases)
    return 0


def write_doc(path, tables, commit, cases):
    text = (REPO / "tools/betaflight_match_doc.md").read_text().replace("@COMMIT@", commit)
    text = text.replace("@CASES@", " ".join(f"`{relative(c)}`" for c in cases))
    for name in CONFIGS:
        text = text.replace(f"@TABLE_{name.upper()}@", "\n".join(tables.get(name, ["(not flown in this run)"])))
    output_files.write_whole(path, text)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
