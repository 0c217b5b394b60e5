# SPDX-License-Identifier: BSD-3-Clause
"""docs/suite.md's generated block: per suite case and axis the RMS error of every controller, the
best of the LADRC family over the better incumbent, and every loss, tuning failure and divergence.

Reads what tools/suite.sh wrote: OUT_DIR/<case>/metrics.csv (a controller that tune = margins left
untunable has the status `untunable` and was not flown) and OUT_DIR/<case>/tables.txt (its reason,
"untunable CONTROLLER: not flown: ...").
"""
import glob
import math
import os
import re

from sim_output import AXES, CONTROLLERS, divergence, divergence_text, is_number, load_metrics, untunable

FAMILY = ("HP-MLADRC", "LP-MLADRC", "LADRC", "RATE-ADRC")
INCUMBENTS = ("CASCADED", "INDI")
# The target: the family's best at most this fraction of the better incumbent's RMS.
TARGET_RATIO = 0.5
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
PAPER_TUNED = "paper_tuned"


def suite_cases():
    """The suite's case names: scenarios/suite/*.ini, sorted."""
    return sorted(os.path.splitext(os.path.basename(p))[0]
                  for p in glob.glob(os.path.join(ROOT, "scenarios", "suite", "*.ini")))


def tune_failures(case_dir):
    """{controller: reason} of the controllers left untunable in a case (not flown)."""
    m = load_metrics(case_dir)
    if m is None:
        return {}
    out = {c: "untunable" for c in CONTROLLERS if untunable(m, c)}
    tables = os.path.join(case_dir, "tables.txt")
    if out and os.path.exists(tables):
        with open(tables) as f:
            for line in f:
                found = re.match(r"untunable (\S+): not flown: (.*)", line.strip())
                if found and found.group(1) in out:
                    out[found.group(1)] = found.group(2)
    return out


def rms(m, c, axis):
    """A controller's RMS error on an axis, or None when it has no number (diverged, not flown)."""
    v = m.get((c, "4", "error_rms_deg", axis))
    return v if is_number(v) and not math.isnan(v) and divergence(m, c) is None else None


def fmt(v):
    """An RMS in deg: three decimals, two significant digits below 0.1 (yaw's small figures)."""
    return "%.3f" % v if abs(v) >= 0.1 else "%.2g" % v


def cell(m, failed, c, axis):
    if c in failed:
        return "**untunable**"
    if divergence(m, c) is not None:
        return "**DIVERGED**"
    v = rms(m, c, axis)
    return "—" if v is None else fmt(v)


def best(m, controllers, axis):
    have = [(rms(m, c, axis), c) for c in controllers]
    have = [(v, c) for v, c in have if v is not None]
    return min(have) if have else (None, None)


def family_ratio(m, axis):
    """((best family RMS, who), (better incumbent RMS, who), their ratio or None) on an axis."""
    (fv, fc), (iv, ic) = best(m, FAMILY, axis), best(m, INCUMBENTS, axis)
    return (fv, fc), (iv, ic), (fv / iv if fv is not None and iv else None)


def case_table(out_dir, cases, controllers):
    """(table lines, [(case, axis, ratio or None, text)], failures, divergences) or None when a case
    has no output."""
    header = ["case", "axis"] + ["%s RMS (deg)" % c for c in controllers] + [
        "best LADRC family", "better incumbent", "ratio"]
    rows, results, failures, divs = [], [], [], []
    for case in cases:
        d = os.path.join(out_dir, case)
        m, failed = load_metrics(d), tune_failures(d)
        if m is None and not failed:
            return None
        m = m or {}
        failures += ["`%s` %s: %s" % (case, c, msg) for c, msg in sorted(failed.items())]
        divs += ["`%s` %s: %s" % (case, c, divergence_text(m, c)) for c in controllers
                 if divergence(m, c) is not None]
        for axis in AXES:
            (fv, fc), (iv, ic), r = family_ratio(m, axis)
            text = ("%s (%s) / %s (%s) = %.2f" % (fmt(fv), fc, fmt(iv), ic, r) if r is not None else
                    "no LADRC-family controller flew" if fv is None else "no incumbent flew")
            results.append((case, axis, r, text))
            rows.append(["`%s`" % case, axis] + [cell(m, failed, c, axis) for c in controllers]
                        + ["%s (%s)" % (fmt(fv), fc) if fc else "**none**", "%s (%s)" % (fmt(iv), ic) if ic else "**none**",
                           "%.2f" % r if r is not None else "**—**"])
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return lines + [""], results, failures, divs


def listing(title, items):
    return ["%s: %s" % (title, "none.") if not items else "%s (%d):" % (title, len(items))] + (
        [""] + ["- " + i for i in items] if items else []) + [""]


def suite_block(out_dir):
    """Markdown lines of docs/suite.md's generated block, or None when an output is missing."""
    suite = [c for c in CONTROLLERS if c in FAMILY + INCUMBENTS]
    got = case_table(out_dir, suite_cases(), suite)
    paper = case_table(out_dir, [PAPER_TUNED], CONTROLLERS)
    if got is None or paper is None:
        return None
    table, results, failures, divs = got
    over_target = [t for t in results if t[2] is None or t[2] > TARGET_RATIO]
    losses = [t for t in results if t[2] is None or t[2] > 1.0]
    lines = ["RMS tracking error over each case's error window (Table 4's), every controller tuned by "
             "`tune = margins`; ratio: the best LADRC-family RMS over the better incumbent's (below 1: the "
             "family wins). A controller left untunable did not fly; its cell says so and the ratio "
             "is over the others.", ""] + table
    lines += ["The best of the LADRC family is within %.1fx the better incumbent on %d of %d case-axes."
              % (TARGET_RATIO, len(results) - len(over_target), len(results)), ""]
    lines += listing("Losses: ratio above 1, or no ratio (a side did not fly)",
                     ["`%s` %s: %s" % (c, a, t) for c, a, _, t in losses])
    lines += listing("Above the %.1f target (losses included)" % TARGET_RATIO,
                     ["`%s` %s: %s" % (c, a, t) for c, a, _, t in over_target])
    lines += listing("Controllers untunable (the case flew without them)", failures)
    lines += listing("Runs that diverged", divs)
    ptable, presults, pfail, pdivs = paper
    lines += ["### The paper case, every controller tuned alike (`paper_tuned.ini`)", "",
              "`scenarios/paper.ini` with `tune = margins` for all six controllers, PID included.", ""]
    lines += ptable + listing("Losses (ratio above 1)", ["%s: %s" % (a, t) for _, a, r, t in presults
                                                          if r is None or r > 1.0])
    lines += listing("Controllers untunable", pfail) + listing("Runs that diverged", pdivs)
    return lines


def front_page_lines(out_dir):
    """Markdown lines for the front page: per suite case, each axis's ratio of the best LADRC-family
    RMS to the better incumbent's, with who; None when an output is missing."""
    rows, n, met, lost = [], 0, 0, 0
    for case in suite_cases():
        d = os.path.join(out_dir, case)
        m = load_metrics(d)
        if m is None and not tune_failures(d):
            return None
        m = m or {}
        row = ["`%s`" % case]
        for axis in AXES:
            (_, fc), (_, ic), r = family_ratio(m, axis)
            n += 1
            if r is None or r > 1.0:
                lost += 1
            elif r <= TARGET_RATIO:
                met += 1
            row.append("%.2f (%s / %s)" % (r, fc, ic) if r is not None else "**—**")
        rows.append(row)
    lines = ["| suite case | roll | pitch | yaw |", "|---|---|---|---|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    lines += ["", "Ratio: the best LADRC-family RMS over the better incumbent's (below 1: the family wins). "
              "The family's best loses on %d of %d case-axes and is within %.1fx the better incumbent on %d."
              % (lost, n, TARGET_RATIO, met)]
    return lines


# The cases whose HP-MLADRC is set against LP-MLADRC: every scenario flying both with the rate.
HP_LP_CASES = ("real_paper_lag20", "real_paper_lag30", "real_paper_lag40", "real_heavy_lag20",
               "real_heavy_lag30", "real_heavy_lag40", "tone_sweep", "paper_tuned", "paper", "paper_known")
STEADY_TARGET = 0.5  # HP over LP over a steady tone's window
# HP over LP within this of 1 is a tie: the gate shut, the two fly alike (the fit's weight may stir)
TIE = 0.005
# The case-axes whose steady window holds a steady tone (from the scenario files; the other
# windows hold gusts, steps, a chirp or nothing periodic at all).
STEADY_TONE = {"racer_tones": AXES, "racer_yaw_wrap": ("roll", "pitch"), "heavy_tone_wander": ("pitch",),
               "real_paper_lag20": AXES, "real_paper_lag30": AXES, "real_paper_lag40": AXES,
               "real_heavy_lag20": AXES, "real_heavy_lag30": AXES, "real_heavy_lag40": AXES, "tone_sweep": AXES}


def hp_sample_of(case):
    """The HP-MLADRC sample a case's file sets: "gyro", or "observer" (the default)."""
    for p in (os.path.join(ROOT, "scenarios", "suite", case + ".ini"), os.path.join(ROOT, "scenarios", case + ".ini")):
        if os.path.exists(p):
            with open(p) as f:
                return "gyro" if re.search(r"^hp_sample\s*=\s*gyro\b", f.read(), re.M) else "observer"
    return "?"


def hp_lp_block(out_dir):
    """Markdown lines: per case and axis, HP-MLADRC's RMS over LP-MLADRC's, over the error window
    and over the steady window; None when an output is missing."""
    rows, worse, ties, steady = [], [], [], []
    for case in list(suite_cases()) + list(HP_LP_CASES):
        m = load_metrics(os.path.join(out_dir, case))
        if m is None:
            return None
        sample = hp_sample_of(case)
        for axis in AXES:
            hp, lp = rms(m, "HP-MLADRC", axis), rms(m, "LP-MLADRC", axis)
            hs, ls = (m.get((c, "5", "steady_rms_deg", axis)) for c in ("HP-MLADRC", "LP-MLADRC"))
            r = hp / lp if hp is not None and lp else None
            rs = hs / ls if is_number(hs) and is_number(ls) and ls else None
            if r is None or r > 1.0 + TIE:
                worse.append("`%s` %s (%s): %s" % (case, axis, sample, "%.3f" % r if r is not None else "no ratio"))
            elif r > 1.0:
                ties.append("`%s` %s: %.4f" % (case, axis, r))
            if sample == "gyro" and axis in STEADY_TONE.get(case, ()):
                steady.append((case, axis, rs))
            rows.append(["`%s`" % case, axis, sample, fmt(hp) if hp is not None else "**—**",
                         fmt(lp) if lp is not None else "**—**", "%.3f" % r if r is not None else "**—**",
                         "%.3f" % rs if rs is not None else "**—**"])
    lines = ["HP-MLADRC's RMS error over LP-MLADRC's, each tuned by the case's rule: over the error window "
             "(Table 4's) and over the steady window (`steady_rms_deg`); sample: what HP-MLADRC's fit takes "
             "(`hp_sample`, [method.md](method.md)).", "",
             "| case | axis | sample | HP-MLADRC RMS (deg) | LP-MLADRC RMS (deg) | ratio | ratio, steady window |",
             "|---|---|---|---|---|---|---|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows] + [""]
    met = [t for t in steady if t[2] is not None and t[2] <= STEADY_TARGET]
    lines += listing("HP-MLADRC above LP-MLADRC's RMS by more than %.1f %%" % (100 * TIE), worse)
    lines += listing("Above by less (ties)", ties)
    lines += ["On the gyro, over the steady window of a steady tone: at most %.1fx LP-MLADRC's RMS on %d of "
              "%d case-axes; the others:" % (STEADY_TARGET, len(met), len(steady)), ""]
    lines += ["- `%s` %s: %s" % (c, a, "%.3f" % r if r is not None else "no ratio")
              for c, a, r in steady if r is None or r > STEADY_TARGET] + [""]
    return lines
