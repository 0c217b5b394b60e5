#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""tools/hp_gate.py's measurements and tools/hp_gate_plot.py on made-up signals and run folders:
the tones found in a disturbance, the band RMS, the gyro noise in a band, the refusal of a failed
run, the docs block, and the figure with and without the evidence column. Exit 77 (skipped)
without numpy or matplotlib."""

import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
try:
    import numpy as np
    import matplotlib  # noqa: F401
except ImportError:
    print("hp_gate_test.py: needs numpy and matplotlib (/usr/bin/python3 has them)", file=sys.stderr)
    sys.exit(77)

import hp_gate  # noqa: E402

FAILURES = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        FAILURES.append(what)


def close(a, b, rel):
    return abs(a - b) <= rel * abs(b)


def test_tones():
    dt = 0.001
    t = np.arange(3.0, 30.0, dt)
    # Two steady tones: a 27 s window resolves a peak to a fraction of its 0.23 rad/s bin; 0.5 %
    # of the frequency and 2 % of the amplitude leave room for the Hann window's scalloping.
    x = 20 * np.sin(3 * t) + 25 * np.sin(8 * t + 1) + 5
    tones = hp_gate.find_tones(t, x)
    check(len(tones) == 2, "two tones found in 20 sin 3t + 25 sin 8t (found %d)" % len(tones))
    if len(tones) == 2:
        check(close(tones[0]["w"], 3.0, 0.005) and close(tones[1]["w"], 8.0, 0.005),
              "their frequencies within 0.5 %% (%.4f, %.4f rad/s)" % (tones[0]["w"], tones[1]["w"]))
        check(close(tones[0]["amp"], 20, 0.02) and close(tones[1]["amp"], 25, 0.02),
              "their amplitudes within 2 %% (%.3f, %.3f)" % (tones[0]["amp"], tones[1]["amp"]))
        check(tones[0]["steady"] and tones[1]["steady"], "both steady")
    # A tone drifting 4.8-7.2 rad/s (the throttle_drift case): not steady, its range within 5 %
    # (the 4-period windows' peaks smear the ends of the sweep a little).
    drift = 40 * np.sin(6 * t - 3.8197 * np.cos(0.31416 * t))
    d = hp_gate.find_tones(t, drift)
    check(len(d) == 1 and not d[0]["steady"], "a drifting tone is one tone, not steady (found %d)" % len(d))
    if d:
        # its amplitude from windows of 4 periods, over which it drifts by up to 13 %: 5 %
        check(close(d[0]["amp"], 40, 0.05), "its amplitude 40 within 5 %% (%.2f)" % d[0]["amp"])
        check(close(d[0]["lo"], 4.8, 0.05) and close(d[0]["hi"], 7.2, 0.05),
              "its range 4.8-7.2 rad/s within 5 %% (%.2f-%.2f)" % (d[0]["lo"], d[0]["hi"]))


def test_band_rms():
    dt = 0.001
    t = np.arange(0, 20 * 2 * math.pi / 3, dt)
    x = 2.0 * np.sin(3 * t) + 1.0 * np.sin(20 * t)
    # a whole number of periods of the 3 rad/s sine: its band holds sqrt(2) to float precision;
    # 1 % for the 20 rad/s sine's leakage into it
    got = hp_gate.band_rms(x, dt, 2.4, 3.75)
    check(close(got, math.sqrt(2.0), 0.01), "band RMS of 2 sin 3t + sin 20t in 2.4-3.75 rad/s is sqrt 2 (%.4f)" % got)


def test_noise():
    # White noise of sigma deg/s: the band formula against the RMS of a simulated draw differentiated
    # in the band; 1 h at 1 kHz leaves a sampling scatter of a few % in a band of 0.45 w wide at
    # 12 rad/s (about 3000 independent bins): 10 %.
    dt, sigma_deg_s = 0.001, 0.5
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "s.ini")
        with open(path, "w") as f:
            f.write("[run]\ncontrol_dt_s = %g\n[sensors]\nrate_noise_std_deg_s = %g\n" % (dt, sigma_deg_s))
        scen = hp_gate.read_scenario(path)
        lo, hi = 0.8 * 12 / (2 * math.pi), 1.25 * 12 / (2 * math.pi)
        formula = hp_gate.noise_accel_rms(scen, path, 0, lo, hi)
    rng = np.random.default_rng(1)
    n = rng.normal(0.0, sigma_deg_s * math.pi / 180, 3600000)
    spec = np.fft.rfft(n)
    w = 2 * math.pi * np.fft.rfftfreq(len(n), dt)
    keep = (w >= 0.8 * 12) & (w <= 1.25 * 12)
    drawn = math.sqrt(2 * np.sum(np.abs(spec[keep] * w[keep]) ** 2)) / len(n)
    check(close(formula, drawn, 0.10),
          "white noise in band: formula %.4g, drawn %.4g rad/s^2 (10 %%)" % (formula, drawn))


def write_case(d, evidence, diverged=False):
    """A made-up case folder: HP and LP time series with a tone on roll from 3 s to 18 s, the gate
    opening from 5 s and closing from 18 s, metrics.csv and signals.csv."""
    os.makedirs(d, exist_ok=True)
    t = np.arange(0, 20.0, 0.001)
    tone = np.where((t > 3) & (t <= 18), 40 * np.sin(3 * t), 0.0)
    weight = np.clip((t - 5) * 2, 0, 1) * np.clip((18.5 - t) * 2, 0, 1)
    cols = {"t_s": t}
    for a in ("roll", "pitch", "yaw"):
        on = a == "roll"
        cols["error_%s_deg" % a] = 0.01 * np.sin(3 * t) + 0.001
        cols["dist_%s_rad_s2" % a] = tone if on else 0 * t
        cols["hp_est_%s_rad_s2" % a] = tone * weight if on else 0 * t
        cols["hp_weight_%s_frac" % a] = weight if on else 0 * t
        if evidence:  # per tone, as the build logs it: tone 2 inactive (nan) but on roll after 10 s
            cols["hp_evidence1_%s_ratio" % a] = 2 * weight if on else 0.1 + 0 * t
            cols["hp_evidence2_%s_ratio" % a] = np.where(on & (t > 10), 0.5, np.nan)
    names = list(cols)
    for c in ("HP-MLADRC", "LP-MLADRC"):
        np.savetxt(os.path.join(d, c + ".csv"), np.column_stack([cols[n] for n in names]), delimiter=",",
                   header=",".join(names), comments="", fmt="%.6g")
    with open(os.path.join(d, "signals.csv"), "w") as f:
        f.write("signal,axis,piece,from_s,to_s\nreference,roll,1,-inf,inf\ndisturbance,roll,1,3,18\n")
    with open(os.path.join(d, "metrics.csv"), "w") as f:
        f.write("scenario,controller,table,quantity,axis,value\n")
        for c in ("HP-MLADRC", "LP-MLADRC"):
            f.write("x,%s,-,diverged,-,%d\n" % (c, 1 if diverged and c == "HP-MLADRC" else 0))
            if diverged and c == "HP-MLADRC":
                f.write("x,%s,-,diverged_at_s,roll,4.5\nx,%s,-,diverged_error_deg,roll,91\n" % (c, c))
            for a in ("roll", "pitch", "yaw"):
                value = "diverged" if diverged and c == "HP-MLADRC" else "0.01"
                f.write("x,%s,4,error_rms_deg,%s,%s\n" % (c, a, value))


def test_cases_and_plot():
    with tempfile.TemporaryDirectory() as root:
        good, bad = os.path.join(root, "good"), os.path.join(root, "bad")
        write_case(good, evidence=True)
        write_case(bad, evidence=False, diverged=True)
        hp_gate.check_run("good", good, hp_gate.sim_output.load_metrics(good))
        rows = hp_gate.tone_rows("good", good, os.path.join(hp_gate.SCEN_DIR, "reference.ini"))
        check(len(rows) == 1 and rows[0]["axis"] == "roll", "one tone row, on roll")
        if rows:
            # the weight reaches 1 at 5.5 s, 2.5 s after the onset; it is 0 again at 18.5 s
            check(close(rows[0]["open_at"], 2.5, 0.001),
                  "the gate opens 2.5 s after the onset (%.3f)" % rows[0]["open_at"])
            check(rows[0]["let_go"] is not None and close(rows[0]["let_go"], 0.5, 0.01),
                  "and lets go 0.5 s after the end (%s)" % rows[0]["let_go"])
            check(rows[0]["reopened"] is None, "and stays shut after")
            check(close(rows[0]["evidence_peak"], 2.0, 1e-6), "the evidence's peak is read (the larger tone's)")
        try:
            hp_gate.check_run("bad", bad, hp_gate.sim_output.load_metrics(bad))
            check(False, "a diverged run is refused")
        except hp_gate.RunFailed as e:
            check("diverged at 4.500 s on roll" in str(e), "a diverged run is refused: %s" % e)
        try:
            hp_gate.check_run("none", os.path.join(root, "none"), None)
            check(False, "a run without metrics.csv is refused")
        except hp_gate.RunFailed as e:
            check("no metrics.csv" in str(e), "a run without metrics.csv is refused: %s" % e)
        lines = hp_gate.tone_table([{"case": "bad", "failed": "HP-MLADRC diverged"}])
        check(not any(ch.isdigit() for ch in lines[-1].replace("HP-MLADRC", "")),
              "a failed run's row holds no number: %s" % lines[-1])
        plot = os.path.join(HERE, "hp_gate_plot.py")
        for d, evidence in ((good, True), (bad, False)):
            out = os.path.join(root, "fig_%s.png" % evidence)
            rc = subprocess.call([sys.executable, plot, d, "--out", out], stdout=subprocess.DEVNULL)
            check(rc == 0 and os.path.getsize(out) > 10000, "the figure %s the evidence is drawn" %
                  ("with" if evidence else "without"))
        rc = subprocess.call([sys.executable, plot, os.path.join(root, "none")], stderr=subprocess.DEVNULL)
        check(rc == 1, "the figure of a folder without HP-MLADRC.csv is refused")
        doc = os.path.join(root, "doc.md")
        with open(doc, "w") as f:
            f.write("before\n<!-- hp_gate:begin -->\nold\n<!-- hp_gate:end -->\nafter\n")
        hp_gate.write_docs(doc, "new\n")
        with open(doc) as f:
            text = f.read()
        check(text == "before\n<!-- hp_gate:begin -->\nnew\n<!-- hp_gate:end -->\nafter\n",
              "the docs block is replaced")


def main():
    test_tones()
    test_band_rms()
    test_noise()
    test_cases_and_plot()
    if FAILURES:
        print("%d check(s) failed" % len(FAILURES))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
