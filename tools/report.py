#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes a Markdown report that sets the simulator's Tables 3-7 beside the paper's.

Usage: report.py OUT_DIR REPORT_MD [--paper NAME] [--noisy NAME] [--known NAME] [--noisy-known NAME]
                 [--diff NAME] [--docs DIR] [--front-page MD] [--suite-page MD]

--docs DIR rewrites the incumbents and real-airframes blocks of DIR/comparisons.md,
--front-page MD the headline block of MD (README.md), --suite-page MD the suite block of MD
(docs/suite.md, from tools/suite.sh's output), each between its
<!-- NAME:begin --> and <!-- NAME:end --> markers.

OUT_DIR holds one directory per scenario with its metrics.csv, as written by
`ladrc_sil --out OUT_DIR`. If OUT_DIR/tables.txt holds ladrc_sil's printed tables, their
headings (the averaging windows and definitions) are quoted in the report.
Every number of ours comes from metrics.csv; the paper's are the data below.
"""
import argparse
import glob
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sim_output import (AXES, CONTROLLERS, NOT_SETTLED, divergence, divergence_text, is_number,  # noqa: E402
                        load_metrics)
from suite_report import front_page_lines, hp_lp_block, suite_block  # noqa: E402
from output_files import refuse_inputs, write_whole  # noqa: E402

# Dong, Y. et al., "Decoupling-Free Attitude Control of UAV Considering High-Frequency
# Disturbances: A Modified Linear Active Disturbance Rejection Method", Actuators 2025,
# 14(10), 504: the published values of Tables 3-7 (Section 5).
PAPER_REF = ("Dong et al., *Actuators* 2025, 14(10), 504, Section 5")
PAPER_T3_RMS = {"TD": 2.767, "Levant": 0.695}
# Table 4: (mean, std, RMS) in deg per controller and axis.
PAPER_T4 = {
    "HP-MLADRC": {"roll": (0.0078, 1.1823, 1.1823), "pitch": (0.0419, 1.1092, 1.1100),
                  "yaw": (0.0000, 1.3289, 1.3289)},
    "LP-MLADRC": {"roll": (-0.0231, 0.5680, 0.5684), "pitch": (0.0203, 0.5248, 0.5251),
                  "yaw": (-0.0034, 0.2474, 0.2474)},
    "LADRC": {"roll": (0.2188, 7.6786, 7.6816), "pitch": (0.1837, 8.1964, 8.1984),
              "yaw": (-0.1157, 7.8811, 7.8818)},
    "PID": {"roll": (0.0466, 1.4897, 1.4904), "pitch": (0.0352, 1.5643, 1.5646),
            "yaw": (-0.0299, 3.0787, 3.0788)},
}
# Table 5: max error (deg), settling time (s), steady-state band (+- deg); one value per
# controller, not per axis.
PAPER_T5 = {"HP-MLADRC": (9.43, 0.465, 0.0073), "LP-MLADRC": (1.78, 0.124, 0.3639),
            "LADRC": (16.941, 11.335, 13.8988), "PID": (11.4166, 0.395, 5.2999)}
# Table 6: disturbance estimate error (mean, std, RMS) in rad/s^2; one set, the controller
# is not named.
PAPER_T6 = {"roll": (0.805, 9.949, 9.981), "pitch": (-0.628, 9.957, 9.977),
            "yaw": (0.772, 10.244, 10.273)}
# Table 7: rotor speed squared (mean, std) in rad^2/s^2, LP-MLADRC.
PAPER_T7 = {"1": (100035, 51297), "2": (39612, 118466), "3": (75442, 119115), "4": (55776, 49497)}





def table_headings(path):
    """{scenario: {"run": line, "3": heading, "4": heading, ...}} from ladrc_sil's printed tables."""
    out, current = {}, None
    if not os.path.exists(path):
        return out
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line.startswith("== "):
                current = out.setdefault(line[3:].split(" ", 1)[0], {})
                current["run"] = line[3:]
            elif current is not None and line.startswith("Table "):
                current[line.split(".", 1)[0].split()[1]] = line
    return out


def num(v, digits=4):
    """A value of metrics.csv as text: the number, "diverged", "not settled", or — for none."""
    if isinstance(v, str):
        return "not settled" if v == NOT_SETTLED else ("—" if v == "-" else v)
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "—"
    if abs(v) >= 1e4:
        return "%.0f" % v
    if v != 0 and abs(v) < 10 ** -(digits - 1):
        return "%.2e" % v
    return "%.*f" % (digits, v)


def rel(ours, paper):
    """Relative difference (ours - paper) / |paper| in percent, with the ratio when it is far from 1."""
    if not is_number(ours) or not isinstance(paper, (int, float)) or paper == 0 or math.isnan(ours):
        return "—"
    text = "%+.0f %%" % (100.0 * (ours - paper) / abs(paper))
    ratio = ours / paper
    if ratio >= 10:
        text += ", ×%.0f" % ratio
    elif 0 < ratio <= 0.1:
        text += ", ×%.2g" % ratio
    return text


def absdiff(ours, paper, digits=4):
    if not is_number(ours) or math.isnan(ours) or paper is None:
        return "—"
    d = ours - paper
    return ("+" if d >= 0 else "") + num(d, digits)


class Report:
    def __init__(self):
        self.lines = []

    def add(self, *lines):
        self.lines.extend(lines)

    def table(self, header, rows):
        self.add("| " + " | ".join(header) + " |", "|" + "---|" * len(header))
        for r in rows:
            self.add("| " + " | ".join(r) + " |")
        self.add("")

    def heading_of(self, headings, scenario, table):
        h = headings.get(scenario, {}).get(table)
        if h:
            self.add("Definition, as printed by ladrc_sil: *%s*" % h, "")


def section_t3(rep, m, headings, scen):
    rep.add("## Table 3: reference differentiation, TD vs Levant", "")
    rep.heading_of(headings, scen, "3")
    rows = []
    for k in ("TD", "Levant"):
        ours = m.get((k, "3", "derivative_error_rms", "-"))
        rows.append([k, num(m.get((k, "3", "derivative_error_mean", "-"))),
                     num(m.get((k, "3", "derivative_error_std", "-"))), num(PAPER_T3_RMS[k], 3), num(ours),
                     rel(ours, PAPER_T3_RMS[k])])
    rep.table(["shaper", "error mean (ours)", "error std (ours)", "error RMS (paper)", "error RMS (ours)",
               "RMS: ours vs paper"], rows)
    td, lv = m.get(("TD", "3", "derivative_error_rms", "-")), m.get(("Levant", "3", "derivative_error_rms", "-"))
    if is_number(td) and is_number(lv) and td and lv:
        rep.add("TD / Levant RMS ratio: paper %.2f, ours %.2f." % (PAPER_T3_RMS["TD"] / PAPER_T3_RMS["Levant"],
                                                                   td / lv), "")


def section_t4(rep, m, headings, scen, with_paper, clean=None):
    rep.add("Definition, as printed by ladrc_sil: *%s*" % headings[scen]["4"] if "4" in headings.get(scen, {})
            else "Tracking error = reference − angle, in deg.", "")
    rows = []
    for c in CONTROLLERS:
        if (c, "4", "error_rms_deg", "roll") not in m:
            continue
        for axis in AXES:
            mean, std, rms = (m.get((c, "4", q, axis)) for q in ("error_mean_deg", "error_std_deg", "error_rms_deg"))
            if with_paper and c not in PAPER_T4:  # a baseline the paper does not fly
                rows.append([c, axis, "— / %s" % num(mean), "— / %s" % num(std), "— / %s" % num(rms)])
            elif with_paper:
                pm, ps, pr = PAPER_T4[c][axis]
                rows.append([c, axis, "%s / %s (%s)" % (num(pm), num(mean), absdiff(mean, pm)),
                             "%s / %s (%s)" % (num(ps), num(std), rel(std, ps)),
                             "%s / %s (%s)" % (num(pr), num(rms), rel(rms, pr))])
            else:
                row = [c, axis, num(mean), num(std), num(rms)]
                if clean:
                    v = clean.get((c, "4", "error_rms_deg", axis))
                    row += [num(v), rel(rms, v)]
                rows.append(row)
    if with_paper:
        rep.table(["controller", "axis", "mean, deg: paper / ours (Δ)", "std, deg: paper / ours (Δ)",
                   "RMS, deg: paper / ours (Δ)"], rows)
    else:
        rep.table(["controller", "axis", "mean (deg)", "std (deg)", "RMS (deg)"]
                  + (["RMS without noise (deg)", "noisy vs without"] if clean else []), rows)


def section_t5(rep, m, headings, scen, with_paper):
    rep.heading_of(headings, scen, "5")
    quantities = [("max_error_deg", "max error (deg)"), ("settling_s", "settling time (s)"),
                  ("steady_band_deg", "steady band (± deg)")]
    rows = []
    for c in CONTROLLERS:
        if (c, "5", "max_error_deg", "roll") not in m:
            continue
        for qi, (q, label) in enumerate(quantities):
            row = [c, label]
            if with_paper:
                row.append(num(PAPER_T5[c][qi]) if c in PAPER_T5 else "—")
            for axis in AXES:
                v = m.get((c, "5", q, axis))
                text = num(v)
                if with_paper and is_number(v) and c in PAPER_T5:
                    text += " (%s)" % rel(v, PAPER_T5[c][qi])
                row.append(text)
            rows.append(row)
    header = ["controller", "quantity"] + (["paper"] if with_paper else [])
    header += [a + (" (ours vs paper)" if with_paper else "") for a in AXES]
    rep.table(header, rows)


def section_t6(rep, m, headings, scen):
    rep.add("## Table 6: disturbance estimate error", "")
    rep.heading_of(headings, scen, "6")
    rep.add("The paper gives one set of values without naming the controller; each of our estimating "
            "controllers is set beside it. PID and CASCADED have no disturbance estimate.", "")
    present = [c for c in CONTROLLERS if (c, "6", "dist_error_rms", "roll") in m]
    rows = []
    for axis in AXES:
        for qi, q in enumerate(("mean", "std", "rms")):
            paper = PAPER_T6[axis][qi]
            row = [axis, q if q != "rms" else "RMS", num(paper, 3)]
            for c in present:
                v = m.get((c, "6", "dist_error_" + q, axis))
                row.append("%s (%s)" % (num(v, 3), absdiff(v, paper, 3) if q == "mean" else rel(v, paper)))
            rows.append(row)
    rep.table(["axis", "quantity", "paper (rad/s²)"] + ["%s (ours vs paper)" % c for c in present], rows)


def section_t7(rep, m, headings, scen):
    rep.add("## Table 7: rotor speed squared", "")
    rep.heading_of(headings, scen, "7")
    rep.add("The paper gives the LP-MLADRC row (the other controllers within a few %); each of our "
            "controllers is set beside it.", "")
    present = [c for c in CONTROLLERS if (c, "7", "w2_mean", "1") in m]
    rows = []
    for rotor in ("1", "2", "3", "4"):
        for qi, q in enumerate(("mean", "std")):
            paper = PAPER_T7[rotor][qi]
            row = [rotor, q, num(paper)]
            for c in present:
                v = m.get((c, "7", "w2_" + q, rotor))
                row.append("%s (%s)" % (num(v, 0), rel(v, paper)))
            rows.append(row)
    rep.table(["rotor", "quantity", "paper LP-MLADRC (rad²/s²)"] + ["%s (ours vs paper)" % c for c in present],
              rows)


def section_hp_modes(rep, cases):
    """HP-MLADRC with the frequency given (the paper's assumption) and estimated online, beside
    LP-MLADRC and LADRC: steady band and RMS per axis. cases: [(title, online metrics, known metrics)]."""
    rep.add("## HP-MLADRC: frequency known and estimated online", "",
            "The paper assumes HP-MLADRC knows the disturbance frequency; `paper_known.ini` and "
            "`paper_noisy_known.ini` tell it the steady tone's 3 rad/s, `paper.ini` and `paper_noisy.ini` "
            "let it estimate its frequencies online. Band: Table 5's steady band (±deg over the steady "
            "window, the paper's ±%s for HP-MLADRC); RMS: Table 4's RMS error." % num(PAPER_T5["HP-MLADRC"][2]), "")
    rows = []
    for title, online, known in cases:
        for label, m, c in (("HP-MLADRC, online", online, "HP-MLADRC"), ("HP-MLADRC, known", known, "HP-MLADRC"),
                            ("LP-MLADRC", online, "LP-MLADRC"), ("LADRC", online, "LADRC")):
            row = [title, label]
            for q in (("5", "steady_band_deg"), ("4", "error_rms_deg")):
                row.append(" / ".join(num(m.get((c, q[0], q[1], axis))) for axis in AXES))
            rows.append(row)
    rep.table(["case", "controller", "band roll / pitch / yaw (deg)", "RMS roll / pitch / yaw (deg)"], rows)


def health(rep, m, scen):
    """One line per scenario: the runs that diverged (their statistics read "diverged" in the tables)
    and those with controller faults."""
    bad = []
    for c in CONTROLLERS:
        finite = m.get((c, "-", "finite", "-"))
        faults = m.get((c, "-", "fault_ticks", "-"))
        if finite is None:
            continue
        if divergence(m, c) is not None:
            bad.append("%s: %s, the run stopped there; %d fault ticks"
                       % (c, divergence_text(m, c).replace("diverged", "DIVERGED", 1), faults or 0))
        elif faults:
            bad.append("%s: %d fault ticks" % (c, faults))
    rep.add("Run health (%s): %s" % (scen, "; ".join(bad) if bad else
                                     "no run diverged and no controller fault."), "")


# metrics.csv's tune table: the margins of the tuned loop; every other quantity is a gain.
TUNE_MARGINS = ("pm_deg", "gm_db", "gm_low_db", "crossover_rad_s", "ms")


def tuned_gains(m, c, axis):
    """"name value ..." of controller c's tuned gains on axis, as metrics.csv names them."""
    return " ".join("%s %s" % (q, num(v, 3)) for (cc, t, q, a), v in m.items()
                    if cc == c and t == "tune" and a == axis and q not in TUNE_MARGINS)


REAL_SCENARIOS = ["real_paper_lag20", "real_paper_lag30", "real_paper_lag40",
                  "real_heavy_lag20", "real_heavy_lag30", "real_heavy_lag40"]


def section_real(rep, out_dir, headings):
    """The real airframes (scenarios/real_*.ini): per scenario and controller the tuned gains and
    their margins (roll / yaw; pitch is roll's airframe), RMS error and steady band per axis, and
    whether the run diverged."""
    found = [(n, load_metrics(os.path.join(out_dir, n))) for n in REAL_SCENARIOS]
    found = [(n, m) for n, m in found if m is not None]
    if not found:
        return
    rep.add("## Real airframes: motor lag, sensor delay, limited rotors, noise", "",
            "Every controller tuned by `tune = margins` (PM >= 45 deg, GM >= 6 dB on the scenario's "
            "airframe, as `ladrc_margins` computes them); RMS over each scenario's error window, steady "
            "band over its steady window.", "")
    rows = []
    for name, m in found:
        for c in CONTROLLERS:
            if m.get((c, "-", "finite", "-")) is None:
                continue
            gains = []
            for axis in ("roll", "yaw"):
                gains.append("%s: %s, PM %s GM %s" % (axis, tuned_gains(m, c, axis),
                                                      num(m.get((c, "tune", "pm_deg", axis)), 3),
                                                      num(m.get((c, "tune", "gm_db", axis)), 3)))
            div = divergence_text(m, c)
            rows.append(["`%s`" % name, c, "<br>".join(gains),
                         " / ".join(num(m.get((c, "4", "error_rms_deg", a))) for a in AXES),
                         " / ".join(num(m.get((c, "5", "steady_band_deg", a))) for a in AXES),
                         div if div else "no"])
    rep.table(["scenario", "controller", "tuned gains (metrics.csv names, SI units), margins (deg, dB)",
               "RMS roll / pitch / yaw (deg)", "band roll / pitch / yaw (deg)", "diverged"], rows)


# docs/comparisons.md's answer to "against what people fly today": HP-MLADRC and LP-MLADRC against the
# better of the two incumbent baselines on each figure and axis.
INCUMBENTS = ("CASCADED", "INDI")
CHALLENGERS = ("HP-MLADRC", "LP-MLADRC")
INCUMBENT_SCENARIOS = (("paper", "`paper.ini`"), ("paper_noisy", "`paper_noisy.ini`"),
                       ("tone_sweep", "`tone_sweep.ini`"), ("real_paper_lag30", "`real_paper_lag30.ini`"))
FIGURES = (("4", "error_rms_deg", "RMS"), ("5", "steady_band_deg", "band"))


def ratio_text(r):
    return "—" if r is None else ("%.2f" % r if r >= 0.1 else "%.2g" % r)


def incumbents_block(out_dir):
    """Markdown lines: per scenario and axis, the best incumbent's RMS and band (and which), and
    HP-MLADRC's and LP-MLADRC's divided by them; then the figures where the ratio exceeds 1."""
    rows, losses, n_figures = [], [], 0
    for name, label in INCUMBENT_SCENARIOS:
        m = load_metrics(os.path.join(out_dir, name))
        if m is None:
            return None
        for axis in AXES:
            row, best = [label, axis], {}
            for t, q, fig in FIGURES:
                have = [(m.get((c, t, q, axis)), c) for c in INCUMBENTS]
                have = [(v, c) for v, c in have if is_number(v) and not math.isnan(v) and divergence(m, c) is None]
                best[fig] = min(have) if have else (None, None)
                row.append("%s (%s)" % (num(best[fig][0], 3), best[fig][1]) if have else "—")
            for c in CHALLENGERS:
                for t, q, fig in FIGURES:
                    v, (b, who) = m.get((c, t, q, axis)), best[fig]
                    r = v / b if is_number(v) and b and divergence(m, c) is None else None
                    row.append(ratio_text(r))
                    n_figures += 1
                    if r is None or r > 1.0:
                        losses.append((c, "%s %s %s %s" % (label, axis, fig, "%.2f" % r if r is not None else
                                                           "(no figure)")))
            rows.append(row)
    rep = Report()
    rep.table(["scenario", "axis", "best incumbent RMS (deg)", "best incumbent band (deg)",
               "HP-MLADRC RMS ratio", "HP-MLADRC band ratio", "LP-MLADRC RMS ratio", "LP-MLADRC band ratio"], rows)
    rep.add("Ratios above 1 (the LADRC-family controller worse than the better incumbent), of %d figures each:"
            % (n_figures // len(CHALLENGERS)), "")
    for c in CHALLENGERS:
        mine = [text for who, text in losses if who == c]
        rep.add("- %s: %d%s" % (c, len(mine), (": " + "; ".join(mine) + ".") if mine else "."))
    return rep.lines


def deg(v):
    """A figure in deg for the real-airframes and headline tables: two decimals, three below 0.1,
    two significant digits below 0.01 (HP-MLADRC's bands under a steady tone)."""
    if not is_number(v) or math.isnan(v):
        return num(v)
    return "%.2f" % v if abs(v) >= 0.1 else "%.3f" % v if abs(v) >= 0.01 else "%.2g" % v


def real_block(out_dir):
    """Markdown lines: the real airframes' RMS error and steady band per controller (all tuned)."""
    rep = Report()
    for prefix, title in (("real_paper_lag", "Paper airframe"), ("real_heavy_lag", "Heavy airframe (1.96 kg)")):
        rows = []
        for lag in ("20", "30", "40"):
            m = load_metrics(os.path.join(out_dir, prefix + lag))
            if m is None:
                return None
            for c in CONTROLLERS:
                if m.get((c, "-", "finite", "-")) is None:
                    continue
                div = divergence_text(m, c)
                rows.append(["%s ms" % lag, c, " / ".join(deg(m.get((c, "4", "error_rms_deg", a))) for a in AXES),
                             " / ".join(deg(m.get((c, "5", "steady_band_deg", a))) for a in AXES)
                             + (" (%s)" % div if div else "")])
        rep.add("%s: RMS error and steady band, roll / pitch / yaw (deg), every controller tuned" % title, "")
        rep.table(["lag", "controller", "RMS", "band"], rows)
    return rep.lines


# The front page's headline: per airframe class, the best of the LADRC family against the best
# incumbent on each axis, the figures of the real-airframes and incumbents tables.
FAMILY = ("LADRC", "LP-MLADRC", "HP-MLADRC", "RATE-ADRC")
HEADLINE_CLASSES = (("paper, ideal rotors", ("paper_tuned",)),
                    ("paper, real motors", ("real_paper_lag20", "real_paper_lag30", "real_paper_lag40")),
                    ("heavy, 1.96 kg", ("real_heavy_lag20", "real_heavy_lag30", "real_heavy_lag40")))


def best_of(m, controllers, t, q, axis):
    """(value, controller) of the smallest figure among the controllers that did not diverge."""
    have = [(m.get((c, t, q, axis)), c) for c in controllers if divergence(m, c) is None]
    have = [(v, c) for v, c in have if is_number(v) and not math.isnan(v)]
    return min(have) if have else (None, None)


def headline_block(out_dir):
    """Markdown lines: per class, scenario and axis, the best LADRC-family and the best incumbent
    RMS and band (deg, who); then every figure where the family's best is worse."""
    rows, losses, n_figures = [], [], 0
    for title, scenarios in HEADLINE_CLASSES:
        for name in scenarios:
            m = load_metrics(os.path.join(out_dir, name))
            if m is None:
                return None
            for axis in AXES:
                row = [title, "`%s.ini`" % name, axis]
                for t, q, fig in FIGURES:
                    ours, theirs = best_of(m, FAMILY, t, q, axis), best_of(m, INCUMBENTS, t, q, axis)
                    for v, who in (ours, theirs):
                        row.append("%s (%s)" % (deg(v), who) if who else "—")
                    n_figures += 1
                    if ours[0] is None or (theirs[0] is not None and ours[0] > theirs[0]):
                        losses.append("`%s.ini` %s %s %s against %s" % (name, axis, fig, deg(ours[0]), deg(theirs[0])))
                rows.append(row)
    rep = Report()
    rep.table(["airframe", "scenario", "axis", "RMS, LADRC family", "RMS, incumbent",
               "band, LADRC family", "band, incumbent"], rows)
    rep.add("The best of the LADRC family is worse than the best incumbent on %d of %d figures%s"
            % (len(losses), n_figures, (": " + "; ".join(losses) + ".") if losses else "."))
    suite = front_page_lines(out_dir)
    if suite is None:
        return None
    return rep.lines + [""] + suite


def rewrite_blocks(path, blocks):
    """Replaces the text between <!-- NAME:begin --> and <!-- NAME:end --> for each block; the page
    is rewritten whole (write_whole), or left as it was when a block is missing."""
    with open(path) as f:
        text = f.read()
    for name, lines in blocks.items():
        begin, end = "<!-- %s:begin -->" % name, "<!-- %s:end -->" % name
        i, j = text.find(begin), text.find(end)
        if i < 0 or j < i:
            print("report.py: %s has no %s ... %s block" % (path, begin, end), file=sys.stderr)
            return 1
        text = text[:i + len(begin)] + "\n" + "\n".join(lines).rstrip() + "\n" + text[j:]
    write_whole(path, text)
    print("report.py: rewrote", ", ".join(blocks), "in", path)
    return 0


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out_dir")
    p.add_argument("report_md")
    p.add_argument("--paper", default="paper")
    p.add_argument("--noisy", default="paper_noisy")
    p.add_argument("--known", default="paper_known")
    p.add_argument("--noisy-known", default="paper_noisy_known")
    p.add_argument("--diff", default="table3_differentiator")
    p.add_argument("--docs", metavar="DIR",
                   help="docs directory whose comparisons.md incumbents and real-airframes blocks to rewrite")
    p.add_argument("--front-page", metavar="MD", help="front page (README.md) whose headline block to rewrite")
    p.add_argument("--suite-page", metavar="MD", help="page (docs/suite.md) whose suite block to rewrite from "
                   "tools/suite.sh's output in OUT_DIR")
    a = p.parse_args(argv)
    pages_read = [os.path.join(a.docs, "comparisons.md") if a.docs else None, a.front_page, a.suite_page]
    # what it reads: OUT_DIR/tables.txt, each scenario's folder, and the pages it rewrites in place
    refuse_inputs("report.py", {"REPORT_MD": a.report_md},
                  [os.path.join(a.out_dir, "tables.txt")] + glob.glob(os.path.join(a.out_dir, "*", "*"))
                  + pages_read)
    headings = table_headings(os.path.join(a.out_dir, "tables.txt"))
    rep = Report()
    rep.add("# Simulation results beside the paper's", "",
            "Generated by `tools/report.py` from the metrics that `ladrc_sil` wrote (`tools/figures.sh` "
            "regenerates it); the paper's numbers are the published Tables 3-7 of %s. Relative differences "
            "are (ours − paper) / |paper|, with the ratio ours / paper added when it is beyond 10 or below 0.1; for means, which sit near zero, the difference ours − paper is "
            "given instead." % PAPER_REF, "")
    for scen in (a.diff, a.paper, a.noisy, a.known, a.noisy_known):
        if "run" in headings.get(scen, {}):
            rep.add("- `%s`" % headings[scen]["run"])
    rep.add("")
    missing = []

    m = load_metrics(os.path.join(a.out_dir, a.diff))
    if m is None:
        missing.append(a.diff)
    else:
        section_t3(rep, m, headings, a.diff)

    m = clean = load_metrics(os.path.join(a.out_dir, a.paper))
    if m is None:
        missing.append(a.paper)
    else:
        rep.add("## Table 4: tracking error", "")
        section_t4(rep, m, headings, a.paper, True)
        rep.add("## Table 5: max error, settling time, steady band", "")
        rep.add("The paper gives one value per controller; ours are per axis.", "")
        section_t5(rep, m, headings, a.paper, True)
        section_t6(rep, m, headings, a.paper)
        section_t7(rep, m, headings, a.paper)
        health(rep, m, a.paper)

    m = load_metrics(os.path.join(a.out_dir, a.noisy))
    if m is None:
        missing.append(a.noisy)
    else:
        rep.add("## Noisy case (Figs. 10-11): Tables 4 and 5", "",
                "The paper publishes no tables for this case; these are ours, with the RMS of the case "
                "without noise beside them.", "")
        section_t4(rep, m, headings, a.noisy, False, clean)
        section_t5(rep, m, headings, a.noisy, False)
        health(rep, m, a.noisy)

    cases = []
    for title, online_name, known_name in (("paper case", a.paper, a.known), ("noisy case", a.noisy, a.noisy_known)):
        online = load_metrics(os.path.join(a.out_dir, online_name))
        known = load_metrics(os.path.join(a.out_dir, known_name))
        if known is None:
            missing.append(known_name)
        elif online is not None:
            cases.append((title, online, known))
            health(rep, known, known_name)
    if cases:
        section_hp_modes(rep, cases)

    section_real(rep, a.out_dir, headings)

    incumbents, real = incumbents_block(a.out_dir), real_block(a.out_dir)
    if incumbents is None:
        rep.add("*No incumbents table: it needs the outputs of %s (`tools/figures.sh` flies them).*"
                % ", ".join(n for n, _ in INCUMBENT_SCENARIOS), "")
    else:
        rep.add("## Against the incumbents: HP-MLADRC and LP-MLADRC over the best of CASCADED and INDI", "",
                "RMS: Table 4's over each scenario's error window; band: Table 5's steady band. A ratio "
                "below 1: the LADRC-family controller is better than the better incumbent on that figure.", "")
        rep.add(*incumbents)
        rep.add("")

    for name in missing:
        rep.add("*No output of scenario `%s` was found; its tables are missing.*" % name, "")
        print("report.py: no metrics of scenario '%s' in %s" % (name, a.out_dir), file=sys.stderr)
    pages = []
    if a.docs:
        pages.append((os.path.join(a.docs, "comparisons.md"), {"incumbents": incumbents, "real-airframes": real}))
    if a.front_page:
        pages.append((a.front_page, {"headline": headline_block(a.out_dir)}))
    if a.suite_page:
        pages.append((a.suite_page, {"suite": suite_block(a.out_dir), "hp-lp": hp_lp_block(a.out_dir)}))
    for path, blocks in pages:
        if any(lines is None for lines in blocks.values()):
            print("report.py: %s not rewritten: the outputs of its scenarios are missing" % path, file=sys.stderr)
            missing.append(path)
        elif rewrite_blocks(path, blocks) != 0:
            missing.append(path)
    os.makedirs(os.path.dirname(os.path.abspath(a.report_md)), exist_ok=True)
    write_whole(a.report_md, "\n".join(rep.lines).rstrip() + "\n")
    print("report.py: wrote", a.report_md)
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
