#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The acceptance of HP-MLADRC's gate (docs/hp-gate.md): flies scenarios/hp_gate/ with ladrc_sil
and prints, per case and axis with a tone, the tone against the gyro noise in its band, HP's and
LP's tracking error over the tone's window (whole and in the tone's band), when the gate opened
and let go; and, over the tone-free flights, the seconds per hour the gate was open.

    tools/hp_gate.py [--bin ladrc_sil] [--out DIR] [--jobs 2] [--quick] [--docs FILE [--docs-block NAME]] [--no-run]

Exit status: 0 every run flew (the acceptance figures may be met or missed: they are what the gate
work has to reach); 1 a run failed (diverged, untunable, missing output), its figures not printed;
2 bad usage."""

import argparse
import glob
import math
import os
import subprocess
import sys

try:
    import numpy as np
except ImportError:  # ctest reports the quick form skipped (77), not failed, without numpy
    print("hp_gate.py: needs numpy (/usr/bin/python3 has it)", file=sys.stderr)
    sys.exit(77)

import sim_output
from output_files import refuse_inputs, whole_file, write_whole

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCEN_DIR = os.path.join(ROOT, "scenarios", "hp_gate")
HP, LP = "HP-MLADRC", "LP-MLADRC"

# The acceptance (docs/hp-gate.md).
BAND_LO, BAND_HI = 0.8, 1.25  # a tone's band: these times its frequency (its lowest and highest when it drifts)
HELD_SNR = 3.0                # tones at least this far above the gyro noise in their band are held to the figures
BAND_RATIO_MAX = 0.3          # HP's error in the tone's band at most this times LP's (aim BAND_RATIO_AIM)
BAND_RATIO_AIM = 0.1
WORSE_MAX = 1.02              # HP's whole-band RMS nowhere above LP's by more than 2 %
FALSE_S_PER_H_MAX = 1.0       # tone-free: seconds per hour with the weight above 0, all axes summed
# A tone is steady when its frequency in the window's two halves differs by at most this fraction:
# a 27 s window resolves its peak to better than 0.5 %, a throttle-driven drift of +-20 % is far above.
STEADY_TOL = 0.02
# The online search's range when the scenario does not set it: the library's defaults
# (AXIS_DEFAULT_HP_FREQ_MIN_RAD_S, AXIS_DEFAULT_HP_FREQ_MAX_RAD_S in src/axis.c).
SEARCH_MIN_RAD_S, SEARCH_MAX_RAD_S = 0.3, 40.0
# The gate's weight counts as 1 (fully open) from here: it moves in float steps towards 1.
WEIGHT_ONE = 1.0 - 1e-6
# The gate's evidence, 1 at the engage threshold: per tone, hp_evidence{k}_{axis}_ratio (k = 1 up to
# the build's LADRC_HP_MAX_TONES: columns up to this k are looked for), or one per axis, hp_evidence_{axis}.
EVIDENCE_TONES_MAX = 8

# The quick form (CI): the reference case, one other loop rate, and one tone-free flight cut to 120 s.
QUICK_CASES = ("reference", "loop_2khz")
QUICK_FREE = ("free_moderate", 120.0)

DEG = math.pi / 180.0


class RunFailed(Exception):
    """A run whose figures must not be printed: the reason says which and why."""


# ---------------------------------------------------------------- the scenario, as far as the noise needs it

def read_scenario(path):
    """{section: {key: value text}} of a scenario file (docs/scenario-format.md): '#' starts a comment,
    one key = value per line; signal keys, which may repeat, keep their last piece (not needed here)."""
    out, section = {}, None
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            if line.startswith("[") and line.endswith("]"):
                section = line[1:-1].strip()
                out.setdefault(section, {})
            elif "=" in line and section is not None:
                k, v = line.split("=", 1)
                out[section][k.strip()] = v.strip()
    return out


def read_series_rad_s(path):
    """(t s, values rad/s as rows x columns) of a recorded rate series (scenario-format.md, Recorded series)."""
    with open(path) as f:
        lines = [ln for ln in f if not ln.lstrip().startswith("#") and ln.strip()]
    header = [h.strip() for h in lines[0].split(",")]
    data = np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])
    t_scale = {"[ms]": 1e-3, "[s]": 1.0}[header[0].split()[-1]]
    v_scale = np.array([{"[rad/s]": 1.0, "[deg/s]": DEG}[h.split()[-1]] for h in header[1:]])
    return data[:, 0] * t_scale, data[:, 1:] * v_scale


def rate_noise_std_rad_s(scen):
    s = scen.get("sensors", {})
    if "rate_noise_std_deg_s" in s:
        return float(s["rate_noise_std_deg_s"]) * DEG
    if "rate_noise_var_deg2_s2" in s:
        return math.sqrt(float(s["rate_noise_var_deg2_s2"])) * DEG
    return 0.0


def noise_accel_rms(scen, scen_path, axis_index, f_lo_hz, f_hi_hz):
    """RMS (rad/s^2) in the band f_lo..f_hi Hz of the gyro noise's derivative, (meas_rate - true rate) w,
    from the scenario's noise: the white rate_noise_std (flat over 0..fs/2, one-sided PSD sigma^2 / (fs/2))
    and the recorded series, sampled at the control ticks as the simulator adds it (linear, looped): a
    looped series is periodic, so its power sits on lines k / period, each weighted by w^2."""
    dt = float(scen.get("run", {}).get("control_dt_s", "0.001"))
    fs = 1.0 / dt
    w_lo, w_hi = 2 * math.pi * f_lo_hz, 2 * math.pi * f_hi_hz
    sigma = rate_noise_std_rad_s(scen)
    # integral of S (2 pi f)^2 df over the band, S = sigma^2 / (fs / 2)
    power = sigma ** 2 / (fs / 2) * (w_hi ** 3 - w_lo ** 3) / (3 * 2 * math.pi)
    series = scen.get("sensors", {}).get("rate_noise_series")
    if series:
        t, v = read_series_rad_s(os.path.join(os.path.dirname(scen_path), series))
        if axis_index < v.shape[1]:
            period = t[-1] - t[0]
            n = int(round(period / dt))
            ticks = t[0] + np.arange(n) * dt
            x = np.interp(ticks, t, v[:, axis_index])
            spec = np.fft.rfft(x - x.mean())
            f = np.fft.rfftfreq(n, dt)
            line_power = 2.0 * np.abs(spec) ** 2 / n ** 2  # the mean square of each line k / (n dt)
            keep = (f >= f_lo_hz) & (f <= f_hi_hz)
            power += float(np.sum(line_power[keep] * (2 * math.pi * f[keep]) ** 2))
    return math.sqrt(power)


def search_range(scen):
    hp = scen.get("controller HP-MLADRC", {})
    return (float(hp.get("hp_freq_min_rad_s", SEARCH_MIN_RAD_S)), float(hp.get("hp_freq_max_rad_s", SEARCH_MAX_RAD_S)))


# ---------------------------------------------------------------- what a run wrote

def read_columns(path, names, optional=()):
    """{name: array} of the named columns of a ladrc_sil time series; of the optional ones, those it
    holds (a missing required column fails the run)."""
    if not os.path.exists(path):
        raise RunFailed("no time series %s" % path)
    with open(path) as f:
        header = f.readline().strip().split(",")
    for n in names:
        if n not in header:
            raise RunFailed("%s: no column %s" % (path, n))
    present = list(names) + [n for n in optional if n in header]
    cols = [header.index(n) for n in present]
    data = np.loadtxt(path, delimiter=",", skiprows=1, usecols=cols, ndmin=2)
    if data.shape[0] < 2:
        raise RunFailed("%s holds no flight" % path)
    return {n: data[:, i] for i, n in enumerate(present)}


def evidence_columns(axis):
    """The names a build may log the gate's evidence on an axis under."""
    return ["hp_evidence_%s" % axis] + ["hp_evidence%d_%s_ratio" % (k, axis) for k in range(1, EVIDENCE_TONES_MAX + 1)]


def evidence_series(run, axis):
    """[(name, array)] of the evidence columns the run holds for the axis (none on a build without)."""
    return [(n, run[n]) for n in evidence_columns(axis) if n in run]


def evidence_peak(run, axis, inside=None):
    """The largest evidence of any tone on the axis (over the ticks inside, else all); None without
    the columns, nan when no tone was active."""
    series = evidence_series(run, axis)
    if not series:
        return None
    v = np.concatenate([x if inside is None else x[inside] for _, x in series])
    v = v[np.isfinite(v)]
    return float(v.max()) if v.size else math.nan


def disturbance_windows(case_dir):
    """{axis: (from s, to s)} of each axis's disturbance pieces (signals.csv), their union's span."""
    path = os.path.join(case_dir, "signals.csv")
    if not os.path.exists(path):
        raise RunFailed("no signals.csv in %s" % case_dir)
    out = {}
    with open(path) as f:
        f.readline()
        for line in f:
            signal, axis, _, lo, hi = line.strip().split(",")
            if signal == "disturbance":
                a, b = float(lo), float(hi)
                old = out.get(axis)
                out[axis] = (a, b) if old is None else (min(old[0], a), max(old[1], b))
    return out


def check_run(case, case_dir, metrics):
    """Raises RunFailed when either controller did not fly the case to its end."""
    if metrics is None:
        raise RunFailed("%s: no metrics.csv in %s" % (case, case_dir))
    for c in (HP, LP):
        if sim_output.untunable(metrics, c):
            raise RunFailed("%s: %s untunable (tune = margins)" % (case, c))
        d = sim_output.divergence_text(metrics, c)
        if d:
            raise RunFailed("%s: %s %s" % (case, c, d))
        if not os.path.exists(os.path.join(case_dir, c + ".csv")):
            raise RunFailed("%s: no %s.csv in %s" % (case, c, case_dir))


# ---------------------------------------------------------------- the tones, from the disturbance flown

def tick_s(t):
    """The control period (s) from the time column: its span over its steps (t_s is printed to 0.1 ms,
    so one step of an 8 kHz loop reads 0.1 or 0.2 ms)."""
    return float(t[-1] - t[0]) / (len(t) - 1)


def spectrum_peaks(t, x, rel=0.25):
    """[(frequency rad/s, amplitude)] of the spectral peaks of x at least rel of the largest: Hann
    window, zero-padded 8x, the peak's bin refined by a parabola through its neighbours."""
    x = x - x.mean()
    n = len(x)
    win = np.hanning(n)
    nfft = 8 * (1 << int(math.ceil(math.log2(n))))
    mag = np.abs(np.fft.rfft(x * win, nfft)) * 2.0 / win.sum()
    dt = tick_s(t)
    df = 1.0 / (nfft * dt)
    top = mag.max()
    peaks = []
    for k in range(1, len(mag) - 1):
        if mag[k] >= rel * top and mag[k] >= mag[k - 1] and mag[k] > mag[k + 1]:
            a, b, c = mag[k - 1], mag[k], mag[k + 1]
            shift = 0.5 * (a - c) / (a - 2 * b + c) if a - 2 * b + c != 0 else 0.0
            peaks.append((2 * math.pi * (k + shift) * df, b))
    # a Hann peak's main lobe is 4 bins of the unpadded length wide: keep the tallest within it
    lobe = 2 * math.pi * 4.0 / (n * dt)
    kept = []
    for w, a in sorted(peaks, key=lambda p: -p[1]):
        if all(abs(w - w2) > lobe for w2, _ in kept):
            kept.append((w, a))
    return sorted(kept)


def find_tones(t, x):
    """[{w, amp, lo, hi, steady}] of the tones of the disturbance x over its window: the peaks of the
    whole window, tallest first, each checked in the window's two halves (steady when it stays within
    STEADY_TOL). A drifting tone's range and amplitude are its peak's over windows of 4 periods (the
    whole window's spectrum spreads it over sidebands, which are that tone, not others)."""
    tones = []
    half = len(t) // 2
    dt = tick_s(t)
    for w, amp in sorted(spectrum_peaks(t, x), key=lambda p: -p[1]):
        if any(tone["lo"] <= w <= tone["hi"] for tone in tones):
            continue
        w1 = min(spectrum_peaks(t[:half], x[:half]), key=lambda p: abs(p[0] - w))[0]
        w2 = min(spectrum_peaks(t[half:], x[half:]), key=lambda p: abs(p[0] - w))[0]
        steady = abs(w1 - w2) <= STEADY_TOL * w
        lo = hi = w
        if not steady:
            m = max(int(4 * 2 * math.pi / w / dt), 16)
            seen = [min(spectrum_peaks(t[i:i + m], x[i:i + m]), key=lambda p: abs(p[0] - w))
                    for i in range(0, len(t) - m, m // 4)]
            if seen:
                amp = float(np.median([a for _, a in seen]))
            else:  # a window under 4 periods: its halves
                seen = [(w1, amp), (w2, amp)]
            lo, hi = min([w] + [v for v, _ in seen]), max([w] + [v for v, _ in seen])
        tones.append({"w": w, "amp": amp, "lo": lo, "hi": hi, "steady": steady})
    return sorted(tones, key=lambda tone: tone["w"])


def band_rms(x, dt, w_lo, w_hi):
    """RMS of x's part in the band w_lo..w_hi rad/s: its DFT over the window, the band's bins kept
    (Parseval, one-sided)."""
    n = len(x)
    spec = np.fft.rfft(x)
    w = 2 * math.pi * np.fft.rfftfreq(n, dt)
    keep = (w >= w_lo) & (w <= w_hi)
    return math.sqrt(2.0 * float(np.sum(np.abs(spec[keep]) ** 2))) / n


def rms(x):
    return math.sqrt(float(np.mean(np.square(x))))


def first_time(t, cond):
    idx = np.flatnonzero(cond)
    return t[idx[0]] if idx.size else None


# ---------------------------------------------------------------- the figures of one case

def tone_rows(case, case_dir, scen_path):
    scen = read_scenario(scen_path)
    windows = disturbance_windows(case_dir)
    names, evidence = ["t_s"], []
    for axis in windows:
        names += ["dist_%s_rad_s2" % axis, "error_%s_deg" % axis, "hp_weight_%s_frac" % axis]
        evidence += evidence_columns(axis)
    hp = read_columns(os.path.join(case_dir, HP + ".csv"), names, evidence)
    lp = read_columns(os.path.join(case_dir, LP + ".csv"), ["t_s"] + ["error_%s_deg" % a for a in windows])
    t = hp["t_s"]
    dt = tick_s(t)
    smin, smax = search_range(scen)
    rows = []
    for axis, (a, b) in windows.items():
        a, b = max(a, t[0]), min(b, t[-1])
        inside = (t > a) & (t <= b)
        x = hp["dist_%s_rad_s2" % axis][inside]
        e_hp, e_lp = hp["error_%s_deg" % axis][inside], lp["error_%s_deg" % axis][inside]
        weight = hp["hp_weight_%s_frac" % axis]
        open_at = first_time(t[inside] - a, weight[inside] >= WEIGHT_ONE)
        after = t > b
        open_at_end = bool(weight[inside][-1] > 0)
        let_go = first_time(t[after] - b, weight[after] <= 0.0) if open_at_end else None
        shut_from = b if not open_at_end else None if let_go is None else b + let_go
        reopened = None if shut_from is None else first_time(t[t > shut_from], weight[t > shut_from] > 0)
        whole = rms(e_hp) / rms(e_lp)
        for tone in find_tones(t[inside], x):
            w_lo, w_hi = BAND_LO * tone["lo"], BAND_HI * tone["hi"]
            noise = noise_accel_rms(scen, scen_path, sim_output.AXES.index(axis), w_lo / (2 * math.pi),
                                    w_hi / (2 * math.pi))
            snr = tone["amp"] / math.sqrt(2) / noise if noise > 0 else math.inf
            in_range = smin <= tone["lo"] and tone["hi"] <= smax
            held = snr >= HELD_SNR and tone["steady"] and in_range
            why_not = ("" if held else "below %gx the noise" % HELD_SNR if snr < HELD_SNR else
                       "drifting" if not tone["steady"] else "beyond the search range %g-%g rad/s" % (smin, smax))
            band_hp, band_lp = band_rms(e_hp, dt, w_lo, w_hi), band_rms(e_lp, dt, w_lo, w_hi)
            rows.append({
                "case": case, "axis": axis, "w": tone["w"], "lo": tone["lo"], "hi": tone["hi"],
                "steady": tone["steady"], "amp": tone["amp"], "noise": noise, "snr": snr, "held": held,
                "why_not": why_not, "rms_hp": rms(e_hp), "rms_lp": rms(e_lp), "whole": whole,
                "band_ratio": band_hp / band_lp, "open_at": open_at, "open_at_end": open_at_end,
                "let_go": let_go, "reopened": reopened,
                "evidence_peak": evidence_peak(hp, axis, inside),
            })
    return rows


def free_figures(case, case_dir, metrics):
    """Seconds with the weight above 0 and at 1, per axis, the flight's length, HP/LP RMS per axis
    (whole flight, metrics.csv's error window), and the evidence's peak when the build logs it."""
    names = ["t_s"] + ["hp_weight_%s_frac" % a for a in sim_output.AXES]
    evidence = [n for a in sim_output.AXES for n in evidence_columns(a)]
    hp = read_columns(os.path.join(case_dir, HP + ".csv"), names, evidence)
    t = hp["t_s"]
    dt = tick_s(t)
    out = {"case": case, "hours": len(t) * dt / 3600.0, "axes": {}}  # each tick counts dt, as the open seconds
    for axis in sim_output.AXES:
        w = hp["hp_weight_%s_frac" % axis]
        rms_hp = metrics.get((HP, "4", "error_rms_deg", axis))
        rms_lp = metrics.get((LP, "4", "error_rms_deg", axis))
        out["axes"][axis] = {
            "open_s": float(np.count_nonzero(w > 0)) * dt, "full_s": float(np.count_nonzero(w >= WEIGHT_ONE)) * dt,
            "whole": rms_hp / rms_lp if sim_output.is_number(rms_hp) and sim_output.is_number(rms_lp) else None,
            "evidence_peak": evidence_peak(hp, axis),
        }
    return out


# ---------------------------------------------------------------- the table

def verdict(ok):
    return "met" if ok else "missed"


def fmt_s(v):
    return "never" if v is None else "%.3f s" % v


def evidence_text(peak):
    return "not logged by this build" if peak is None else "no tone active" if peak != peak else "%.3g" % peak


def md_row(cells):
    return "| " + " | ".join(cells) + " |"


def tone_table(rows):
    titles = ["case", "axis", "tone (rad/s)", "amplitude (rad/s²)", "gyro noise in band (rad/s² RMS)", "tone / noise",
              "held", "HP / LP RMS over the tone (deg)", "HP/LP", "HP/LP in band", "gate open (weight 1) after onset",
              "let go (weight 0) after the end", "in band ≤ %g×" % BAND_RATIO_MAX, "whole ≤ %g×" % WORSE_MAX,
              "evidence's peak in the window (threshold 1)"]
    lines = [md_row(titles), "|" + "---|" * len(titles)]
    for r in rows:
        if "failed" in r:
            lines.append(md_row(["`%s`" % r["case"], "-", "run failed: %s" % r["failed"]] + [""] * (len(titles) - 3)))
            continue
        tone = "%.2f" % r["w"] if r["steady"] else "drifts %.2f-%.2f" % (r["lo"], r["hi"])
        if not r["open_at_end"]:
            let_go = "- (shut at the end)"
        elif r["let_go"] is None:
            let_go = "held open to the flight's end"
        else:
            let_go = fmt_s(r["let_go"])
        if r["reopened"] is not None:
            let_go += "; open again from t = %.2f s" % r["reopened"]
        lines.append(md_row([
            "`%s`" % r["case"], r["axis"], tone, "%.1f" % r["amp"], "%.3g" % r["noise"], "%.3g" % r["snr"],
            "yes" if r["held"] else "no: " + r["why_not"], "%.3f / %.3f" % (r["rms_hp"], r["rms_lp"]),
            "%.3f" % r["whole"], "%.3f" % r["band_ratio"], fmt_s(r["open_at"]), let_go,
            verdict(r["band_ratio"] <= BAND_RATIO_MAX) if r["held"] else "(not held)",
            verdict(r["whole"] <= WORSE_MAX), evidence_text(r["evidence_peak"])]))
    return lines


def free_table(frees):
    lines = ["| tone-free flight | length (s) | axis | weight > 0 (s) | weight = 1 (s) | HP/LP RMS, whole flight | "
             "evidence's peak (threshold 1) |", "|---|---|---|---|---|---|---|"]
    for f in frees:
        if "failed" in f:
            lines.append("| `%s` | run failed: %s | | | | | |" % (f["case"], f["failed"]))
            continue
        for axis, a in f["axes"].items():
            lines.append("| `%s` | %.0f | %s | %.3f | %.3f | %s | %s |" % (
                f["case"], f["hours"] * 3600, axis, a["open_s"], a["full_s"],
                "-" if a["whole"] is None else "%.4f (%s)" % (a["whole"], verdict(a["whole"] <= WORSE_MAX)),
                evidence_text(a["evidence_peak"])))
    return lines


def summarise(rows, frees):
    """(lines of the false-engage rates, the summary line, every figure met)."""
    flown = [f for f in frees if "failed" not in f]
    hours = sum(f["hours"] for f in flown)
    lines = []
    total_open = total_full = 0.0
    for axis in sim_output.AXES:
        o = sum(f["axes"][axis]["open_s"] for f in flown)
        u = sum(f["axes"][axis]["full_s"] for f in flown)
        total_open += o
        total_full += u
        if hours > 0:
            lines.append("false engage, %s: %.3f s/h with weight > 0, %.3f s/h at 1" % (axis, o / hours, u / hours))
    ok = True
    good = [r for r in rows if "failed" not in r]
    held = [r for r in good if r["held"]]
    band_met = [r for r in held if r["band_ratio"] <= BAND_RATIO_MAX]
    aim_met = [r for r in held if r["band_ratio"] <= BAND_RATIO_AIM]
    whole_rows = {(r["case"], r["axis"]): r["whole"] for r in good}
    for f in flown:
        for axis, a in f["axes"].items():
            if a["whole"] is not None:
                whole_rows[(f["case"], axis)] = a["whole"]
    whole_met = [k for k, v in whole_rows.items() if v <= WORSE_MAX]
    ok &= len(band_met) == len(held) and len(whole_met) == len(whole_rows)
    if hours > 0:
        rate = total_open / hours
        lines.append("false engage, all axes: %.3f s/h with weight > 0 (%s: <= %g s/h), %.3f s/h at 1, over %.2f h" % (
            rate, verdict(rate <= FALSE_S_PER_H_MAX), FALSE_S_PER_H_MAX, total_full / hours, hours))
        ok &= rate <= FALSE_S_PER_H_MAX
        if hours < 1.0 - 1e-6:
            lines.append("(the tone-free flights add up to %.2f h: the full form flies 1 h)" % hours)
    failed = [r for r in rows if "failed" in r] + [f for f in frees if "failed" in f]
    summary = ("summary: HP <= %gx LP in the tone's band on %d of %d held tones (%d at the %gx aim); within %d %% of "
               "LP's RMS on %d of %d case-axes; %s%s" % (
                   BAND_RATIO_MAX, len(band_met), len(held), len(aim_met), BAND_RATIO_AIM, round((WORSE_MAX - 1) * 100),
                   len(whole_met), len(whole_rows),
                   "false engage %.3f s/h; " % (total_open / hours) if hours > 0 else "",
                   "acceptance met" if ok and not failed else
                   "acceptance missed" + ("; %d run(s) failed" % len(failed) if failed else "")))
    return lines, summary, ok and not failed


def write_docs(path, text, block_name="hp_gate"):
    begin, end = "<!-- %s:begin -->" % block_name, "<!-- %s:end -->" % block_name
    block = begin + "\n" + text + end
    if os.path.exists(path):
        with open(path) as f:
            doc = f.read()
        if begin not in doc or end not in doc:
            sys.exit("hp_gate.py: %s has no %s ... %s block to replace" % (path, begin, end))
        doc = doc[:doc.index(begin)] + block + doc[doc.index(end) + len(end):]
    else:
        doc = block + "\n"
    write_whole(path, doc)


# ---------------------------------------------------------------- running

def fly(args, cases, sets=()):
    """ladrc_sil on the cases' scenarios into args.out; its exit status (1 and 2 stop the tool)."""
    cmd = [args.bin] + [os.path.join(SCEN_DIR, c + ".ini") for c in cases] + [
        "--jobs", str(args.jobs), "--out", args.out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    print("+ " + " ".join(cmd), flush=True)
    with whole_file(os.path.join(args.out, "ladrc_sil_%s.txt" % cases[0])) as log:
        rc = subprocess.call(cmd, stdout=log)  # kept when the run fails: it is that run's record
    if rc in (1, 2) or rc < 0:
        sys.exit("hp_gate.py: ladrc_sil exited with status %d (cases %s)" % (rc, ", ".join(cases)))
    return rc


def all_cases():
    names = sorted(f[:-4] for f in os.listdir(SCEN_DIR) if f.endswith(".ini"))
    return names


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bin", default=os.path.join(ROOT, "build", "host-release", "sim", "ladrc_sil"),
                   help="ladrc_sil to fly (default build/host-release's)")
    p.add_argument("--out", default=None, help="output folder (default build/hp_gate, build/hp_gate_quick)")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--quick", action="store_true",
                   help="the CI subset: the reference case, the 2 kHz loop and a 120 s tone-free flight")
    p.add_argument("--docs", metavar="FILE", help="write the tables into FILE's hp_gate block (Markdown)")
    p.add_argument("--docs-block", default="hp_gate", metavar="NAME",
                   help="the block --docs rewrites: <!-- NAME:begin --> to <!-- NAME:end --> (default hp_gate)")
    p.add_argument("--no-run", action="store_true", help="read a previous run in --out instead of flying")
    args = p.parse_args()
    if args.out is None:
        args.out = os.path.join(ROOT, "build", "hp_gate_quick" if args.quick else "hp_gate")
    # what it reads: the cases' scenarios and each case's run folder
    refuse_inputs("hp_gate.py", {"--docs": args.docs},
                  glob.glob(os.path.join(SCEN_DIR, "*.ini")) + glob.glob(os.path.join(args.out, "*", "*")))
    os.makedirs(args.out, exist_ok=True)

    if args.quick:
        tone_cases, free_cases = list(QUICK_CASES), [QUICK_FREE[0]]
        free_sets = ("run.duration_s=%g" % QUICK_FREE[1], "metrics.error_window_s=0 %g" % QUICK_FREE[1])
    else:
        names = all_cases()
        free_cases = [c for c in names if c.startswith("free_")]
        tone_cases = [c for c in names if c not in free_cases]
        free_sets = ()
    if not args.no_run:
        if not os.path.exists(args.bin):
            sys.exit("hp_gate.py: no ladrc_sil at %s (--bin; build it: cmake --build build/host-release "
                     "--target ladrc_sil)" % args.bin)
        fly(args, tone_cases)
        fly(args, free_cases, free_sets)

    rows, frees = [], []
    for case in tone_cases:
        case_dir = os.path.join(args.out, case)
        try:
            check_run(case, case_dir, sim_output.load_metrics(case_dir))
            rows += tone_rows(case, case_dir, os.path.join(SCEN_DIR, case + ".ini"))
        except RunFailed as e:
            print("hp_gate.py: %s" % e, file=sys.stderr)
            rows.append({"case": case, "failed": str(e)})
    for case in free_cases:
        case_dir = os.path.join(args.out, case)
        try:
            metrics = sim_output.load_metrics(case_dir)
            check_run(case, case_dir, metrics)
            frees.append(free_figures(case, case_dir, metrics))
        except RunFailed as e:
            print("hp_gate.py: %s" % e, file=sys.stderr)
            frees.append({"case": case, "failed": str(e)})

    rate_lines, summary, _ = summarise(rows, frees)
    text = "\n".join(tone_table(rows)) + "\n\n" + "\n".join(free_table(frees)) + "\n\n" + \
        "\n".join("- " + ln for ln in rate_lines) + "\n\n" + summary + "\n"
    print(text, end="")
    if args.docs:
        write_docs(args.docs, text, args.docs_block)
    failed = any("failed" in r for r in rows) or any("failed" in f for f in frees)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
