#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""ctest check of tools/campaign.py on hand-made campaign output directories (the layout of
docs/campaigns.md, written here without the simulator): merge's rows, columns and values,
the diverged and not_settled words, byte-identical tables whatever order the runs were
written in, the errors (missing runs, OUT, plan.csv, unknown --x), and plot's figures.

Usage: campaign_test.py
Exit status: 0 all passed, 1 a check failed, 77 (ctest: skipped) when the merge checks passed
but matplotlib or numpy is missing for the plot checks.
"""
import contextlib
import io
import math
import os
import random
import shutil
import struct
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import campaign  # noqa: E402

failures = 0


def check(name, ok, detail=""):
    global failures
    print("campaign_test.py:%s:%s%s" % (name, "PASS" if ok else "FAIL", "" if ok or not detail else ": " + detail))
    if not ok:
        failures += 1


def run(argv):
    """(exit status, stdout, stderr) of campaign.py with these arguments."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            rc = campaign.main(argv)
        except SystemExit as e:
            rc = e.code
    return rc, out.getvalue(), err.getvalue()


def metrics_text(scenario, controllers):
    """A metrics.csv as ladrc_sil writes it. controllers: [(name, stats or None if diverged)],
    stats: {axis: (rms, band, max, settling)} as text; other rows filled in."""
    lines = ["scenario,controller,table,quantity,axis,value"]
    for name, stats in controllers:
        for axis in ("roll", "pitch", "yaw"):
            rms, band, mx, settle = stats[axis] if stats else ("diverged",) * 4
            mean = "diverged" if stats is None else "0.01"
            lines += ["%s,%s,4,error_mean_deg,%s,%s" % (scenario, name, axis, mean),
                      "%s,%s,4,error_std_deg,%s,%s" % (scenario, name, axis, mean),
                      "%s,%s,4,error_rms_deg,%s,%s" % (scenario, name, axis, rms),
                      "%s,%s,5,max_error_deg,%s,%s" % (scenario, name, axis, mx),
                      "%s,%s,5,settling_s,%s,%s" % (scenario, name, axis, settle),
                      "%s,%s,5,steady_band_deg,%s,%s" % (scenario, name, axis, band)]
        for k in "1234":
            lines.append("%s,%s,7,w2_mean,%s,%s" % (scenario, name, k, "diverged" if stats is None else "65000"))
        lines += ["%s,%s,-,finite,-,%d" % (scenario, name, stats is not None),
                  "%s,%s,-,fault_ticks,-,0" % (scenario, name),
                  "%s,%s,-,diverged,-,%d" % (scenario, name, stats is None)]
        if stats is None:
            lines += ["%s,%s,-,diverged_at_s,roll,1.234" % (scenario, name),
                      "%s,%s,-,diverged_error_deg,roll,90.5" % (scenario, name)]
        else:
            lines += ["%s,%s,-,diverged_at_s,-,-" % (scenario, name),
                      "%s,%s,-,diverged_error_deg,-,-" % (scenario, name)]
    return "\n".join(lines) + "\n"


def write_out(out, header, plan, runs, order=None):
    """An OUT directory: plan.csv from header and plan rows, runs/<r>/metrics.csv from
    runs[r] = [(controller, stats)], written in `order` (default 1..R)."""
    os.makedirs(os.path.join(out, "runs"), exist_ok=True)
    with open(os.path.join(out, "plan.csv"), "w") as f:
        f.write(",".join(header) + "\n" + "".join(",".join(row) + "\n" for row in plan))
    for r in order or sorted(runs):
        d = os.path.join(out, "runs", "%05d" % r)
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "metrics.csv"), "w") as f:
            f.write(metrics_text("%05d" % r, runs[r]))
        with open(os.path.join(d, "signals.csv"), "w") as f:
            f.write("kind,axis,from_s,to_s,expression\n")


def small_campaign():
    """3 runs, varying a grid variable and a drawn scenario key; run 2's PID diverged, run 3's
    LADRC did not settle on pitch."""
    header = ["run", "tone", "sensors.angle_noise_std_deg"]
    plan = [["1", "0.5", "0.012"], ["2", "0.5", "0.0871"], ["3", "2", "1e-05"]]

    def stats(base):
        return {a: ("%g" % (base + i), "%g" % (base / 10 + i), "%g" % (base * 3 + i), "0.25")
                for i, a in enumerate(("roll", "pitch", "yaw"))}
    not_settled = stats(3.0)
    not_settled["pitch"] = ("4.5", "0.4", "9.5", "not_settled")
    runs = {1: [("LADRC", stats(1.0)), ("PID", stats(2.0))],
            2: [("LADRC", stats(1.5)), ("PID", None)],
            3: [("LADRC", not_settled), ("PID", stats(2.5))]}
    return header, plan, runs


EXPECTED_SMALL = (
    "run,tone,sensors.angle_noise_std_deg,"
    "LADRC.roll.rms_deg,LADRC.roll.band_deg,LADRC.roll.max_deg,LADRC.roll.settling_s,LADRC.roll.diverged,"
    "LADRC.pitch.rms_deg,LADRC.pitch.band_deg,LADRC.pitch.max_deg,LADRC.pitch.settling_s,LADRC.pitch.diverged,"
    "LADRC.yaw.rms_deg,LADRC.yaw.band_deg,LADRC.yaw.max_deg,LADRC.yaw.settling_s,LADRC.yaw.diverged,"
    "PID.roll.rms_deg,PID.roll.band_deg,PID.roll.max_deg,PID.roll.settling_s,PID.roll.diverged,"
    "PID.pitch.rms_deg,PID.pitch.band_deg,PID.pitch.max_deg,PID.pitch.settling_s,PID.pitch.diverged,"
    "PID.yaw.rms_deg,PID.yaw.band_deg,PID.yaw.max_deg,PID.yaw.settling_s,PID.yaw.diverged\n"
    "1,0.5,0.012,1,0.1,3,0.25,no,2,1.1,4,0.25,no,3,2.1,5,0.25,no,"
    "2,0.2,6,0.25,no,3,1.2,7,0.25,no,4,2.2,8,0.25,no\n"
    "2,0.5,0.0871,1.5,0.15,4.5,0.25,no,2.5,1.15,5.5,0.25,no,3.5,2.15,6.5,0.25,no,"
    "diverged,diverged,diverged,diverged,yes,diverged,diverged,diverged,diverged,yes,"
    "diverged,diverged,diverged,diverged,yes\n"
    "3,2,1e-05,3,0.3,9,0.25,no,4.5,0.4,9.5,not_settled,no,5,2.3,11,0.25,no,"
    "2.5,0.25,7.5,0.25,no,3.5,1.25,8.5,0.25,no,4.5,2.25,9.5,0.25,no\n")


def read(path):
    with open(path, "rb") as f:
        return f.read()


def test_merge(work):
    out = os.path.join(work, "small")
    write_out(out, *small_campaign())
    rc, so, se = run(["merge", out])
    check("merge_succeeds", rc == 0, se)
    table = read(os.path.join(out, "campaign.csv")).decode() if rc == 0 else ""
    check("merge_columns_rows_values", table == EXPECTED_SMALL, "\n" + table)
    check("merge_reports_count", "3 runs merged" in so, so)

    # The same runs written backwards, and shuffled: the same bytes.
    for label, order in (("reverse", [3, 2, 1]), ("shuffled", [2, 3, 1])):
        other = os.path.join(work, "small_" + label)
        write_out(other, *small_campaign(), order=order)
        rc, _, se = run(["merge", other])
        check("merge_byte_identical_%s" % label,
              rc == 0 and read(os.path.join(other, "campaign.csv")) == read(os.path.join(out, "campaign.csv")), se)

    # A larger one, runs written in random order: run order in the table, same bytes.
    header, plan, runs = big_campaign(seed=7)
    a, b = os.path.join(work, "big_a"), os.path.join(work, "big_b")
    write_out(a, header, plan, runs)
    order = sorted(runs)
    random.Random(3).shuffle(order)
    write_out(b, header, plan, runs, order=order)
    ra, _, _ = run(["merge", a])
    rb, _, _ = run(["merge", b])
    ta, tb = read(os.path.join(a, "campaign.csv")), read(os.path.join(b, "campaign.csv"))
    check("merge_big_byte_identical_any_order", ra == 0 and rb == 0 and ta == tb)
    runs_col = [line.split(b",")[0] for line in ta.splitlines()[1:]]
    check("merge_rows_in_run_order", runs_col == [str(r).encode() for r in range(1, len(plan) + 1)])


def test_merge_errors(work):
    # 30 runs, 25 missing: the first 20 named, then a count; no table.
    header = ["run", "x"]
    plan = [[str(r), str(r)] for r in range(1, 31)]
    runs = {r: [("LADRC", {a: ("1", "1", "1", "1") for a in ("roll", "pitch", "yaw")})] for r in range(1, 31)}
    out = os.path.join(work, "missing")
    write_out(out, header, plan, runs)
    for r in list(range(2, 21)) + list(range(24, 30)):
        shutil.rmtree(os.path.join(out, "runs", "%05d" % r))
    rc, _, se = run(["merge", out])
    named = "run " + ", ".join(str(r) for r in list(range(2, 21)) + [24]) + " and 5 more"
    check("missing_runs_exit_1", rc == 1, "rc %s" % rc)
    check("missing_runs_named", "25 of 30 runs" in se and named in se, se)
    check("missing_runs_no_table", not os.path.exists(os.path.join(out, "campaign.csv")))

    # A run directory without metrics.csv counts as missing.
    out2 = os.path.join(work, "no_metrics")
    write_out(out2, header, plan[:3], {r: runs[r] for r in (1, 2, 3)})
    os.unlink(os.path.join(out2, "runs", "00002", "metrics.csv"))
    rc, _, se = run(["merge", out2])
    check("run_without_metrics_is_missing", rc == 1 and "1 of 3 runs" in se and "run 2" in se, se)

    rc, _, se = run(["merge", os.path.join(work, "nowhere")])
    check("missing_out_exit_1", rc == 1 and "no campaign output directory" in se, se)
    empty = os.path.join(work, "empty")
    os.makedirs(empty)
    rc, _, se = run(["merge", empty])
    check("missing_plan_exit_1", rc == 1 and "no plan.csv" in se, se)
    check("missing_plan_nothing_written", os.listdir(empty) == [])

    # A run of another campaign in runs/, controllers differing between runs, a metrics.csv
    # whose scenario column is not its directory.
    out3 = os.path.join(work, "extra")
    write_out(out3, header, plan[:3], {r: runs[r] for r in (1, 2, 3, 4)})
    rc, _, se = run(["merge", out3])
    check("extra_run_exit_1", rc == 1 and "not in plan.csv: 00004" in se, se)
    out4 = os.path.join(work, "ctrl")
    r2 = dict((r, runs[r]) for r in (1, 2))
    r2[2] = [("PID", runs[2][0][1])]
    write_out(out4, header, plan[:2], r2)
    rc, _, se = run(["merge", out4])
    check("controllers_differ_exit_1", rc == 1 and "controllers PID, run 1 flew LADRC" in se, se)
    out5 = os.path.join(work, "scen")
    write_out(out5, header, plan[:1], {1: runs[1]})
    p = os.path.join(out5, "runs", "00001", "metrics.csv")
    with open(p) as f:
        text = f.read().replace("00001,", "paper,")
    with open(p, "w") as f:
        f.write(text)
    rc, _, se = run(["merge", out5])
    check("scenario_column_checked", rc == 1 and "expected the run's directory name '00001'" in se, se)


def big_campaign(seed):
    """A grid of 5 motor lags x 40 log-uniform tones, 4 controllers; a controller diverges
    more often the larger the lag (PID never below 20 ms, always above 30 ms; LADRC never)."""
    rng = random.Random(seed)
    taus = ["0", "0.01", "0.02", "0.03", "0.04"]
    header = ["run", "rotors.motor_tau_s", "tone"]
    plan, runs = [], {}
    r = 0
    for tau in taus:
        for _ in range(40):
            r += 1
            tone = math.exp(rng.uniform(math.log(0.5), math.log(20)))
            plan.append([str(r), tau, repr(tone)])
            ctrls = []
            for k, name in enumerate(("HP-MLADRC", "LP-MLADRC", "LADRC", "PID")):
                limit = {"PID": 0.025, "HP-MLADRC": 0.035, "LP-MLADRC": 0.045, "LADRC": 1.0}[name]
                if float(tau) > limit or (float(tau) == 0.03 and name == "HP-MLADRC" and rng.random() < 0.4):
                    ctrls.append((name, None))
                    continue
                rms = (0.2 + k * 0.3) * (1 + 30 * float(tau)) * (1 + 0.05 * tone) * rng.uniform(0.8, 1.25)
                ctrls.append((name, {a: ("%.9g" % (rms * (1 + i)), "%.9g" % (rms / 5), "%.9g" % (rms * 4),
                                         "not_settled" if rng.random() < 0.1 else "%.4g" % rng.uniform(0.2, 1.5))
                                     for i, a in enumerate(("roll", "pitch", "yaw"))}))
            runs[r] = ctrls
    return header, plan, runs


def png_size(path):
    """(width, height) of a PNG file, or None if it is not one."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


MIN_PNG_BYTES = 20000      # a drawn map or box plot is well above; an empty canvas is ~5 kB
MIN_PNG_PIXELS = (700, 450)


def test_plot(work):
    header, plan, runs = big_campaign(seed=11)
    out = os.path.join(work, "robust")
    write_out(out, header, plan, runs)
    rc, _, se = run(["plot", out])
    check("plot_without_merge_exit_1", rc == 1 and "merge" in se and not os.path.exists(os.path.join(out, "figures")), se)
    run(["merge", out])
    rc, so, se = run(["plot", out])
    check("plot_succeeds", rc == 0, se)
    for fig in ("map_roll_rotors.motor_tau_s_tone.png", "rms_roll.png"):
        path = os.path.join(out, "figures", fig)
        size = png_size(path) if os.path.exists(path) else None
        nbytes = os.path.getsize(path) if size else 0
        print("%s: %s, %d bytes" % (fig, "%dx%d" % size if size else "missing or not a PNG", nbytes))
        check("plot_draws_" + fig, size is not None and size[0] >= MIN_PNG_PIXELS[0] and
              size[1] >= MIN_PNG_PIXELS[1] and nbytes > MIN_PNG_BYTES)
    # The other axis, x and y swapped.
    rc, _, se = run(["plot", out, "--x", "tone", "--y", "rotors.motor_tau_s", "--axis", "pitch",
                     "--label", "tone=tone frequency (rad/s)"])
    check("plot_swapped_axes_with_label", rc == 0 and os.path.exists(os.path.join(out, "figures", "map_pitch_tone_rotors.motor_tau_s.png")), se)

    # The log axis: the log-uniform tone is, the linear grid of lags is not.
    cols = campaign.read_campaign(out)[2]
    check("log_axis_for_log_uniform_draw", campaign.Axis("tone", cols["tone"]).log)
    check("linear_axis_for_linear_grid", not campaign.Axis("rotors.motor_tau_s", cols["rotors.motor_tau_s"]).log)
    check("linear_axis_for_uniform_draw",
          not campaign.Axis("u", [repr(0.1 + 19.9 * i / 199) for i in range(200)]).log)
    check("unit_in_label", campaign.label_of("rotors.motor_tau_s") == "rotors.motor_tau_s (s)")

    # Diverged runs are counted, not plotted: the labels say how many were left out.
    data, labels = campaign.box_data(["HP-MLADRC", "LADRC", "PID"], cols, "roll")
    n_pid_div = sum(1 for r in runs.values() for name, st in r if name == "PID" and st is None)
    check("box_pid_diverged_left_out", n_pid_div == 80 and len(data[2]) == 120 and
          labels[2] == "PID\n120 runs\n80 diverged, left out", repr(labels[2]))
    check("box_ladrc_none_diverged", len(data[1]) == 200 and labels[1].endswith("none diverged"), repr(labels[1]))

    # Unknown --x: an error naming the varied names, nothing written.
    shutil.rmtree(os.path.join(out, "figures"))
    rc, _, se = run(["plot", out, "--x", "nonesuch"])
    check("unknown_x_exit_1", rc == 1 and "--x nonesuch: not a varied name" in se and "rotors.motor_tau_s, tone" in se, se)
    rc, _, se = run(["plot", out, "--label", "nonesuch=x"])
    check("unknown_label_exit_1", rc == 1 and "--label nonesuch=x" in se, se)
    check("unknown_x_nothing_written", not os.path.exists(os.path.join(out, "figures")))

    # A controller that diverged in every run, and a one-name campaign: still drawn.
    small = os.path.join(work, "small_plot")
    header, plan, runs = small_campaign()
    write_out(small, header[:2], [row[:2] for row in plan], runs)
    run(["merge", small])
    rc, _, se = run(["plot", small])
    check("plot_one_varied_name", rc == 0 and os.path.exists(os.path.join(small, "figures", "map_roll_tone.png")), se)


def ratio_campaign():
    """A 2 x 2 grid (lag x kind), 2 runs per cell: LP-MLADRC at 0.4x the better incumbent's RMS
    (INDI 2, CASCADED 3: INDI is the better one), LADRC at 2x, RATE-ADRC diverged in run 8,
    INDI diverged in run 7 (then CASCADED is the better one)."""
    header = ["run", "rotors.motor_tau_s", "kind"]
    plan, runs = [], {}
    for r in range(1, 9):
        lag, kind = ("0.015" if r <= 4 else "0.06"), ("1" if (r - 1) % 4 < 2 else "2")
        plan.append([str(r), lag, kind])

        def st(v):
            return {a: ("%g" % v, "0.1", "1", "0.25") for a in ("roll", "pitch", "yaw")}
        indi = None if r == 7 else st(2.0)
        base = 3.0 if r == 7 else 2.0
        runs[r] = [("LP-MLADRC", st(0.4 * base)), ("LADRC", st(2.0 * base)),
                   ("RATE-ADRC", None if r == 8 else st(1.0 * base)), ("CASCADED", st(3.0)), ("INDI", indi)]
    return header, plan, runs


def test_ratio(work):
    out = os.path.join(work, "ratio")
    write_out(out, *ratio_campaign())
    run(["merge", out])
    varied, controllers, cols = campaign.read_campaign(out)
    import campaign_ratio
    ratios = campaign_ratio.run_ratios(controllers, cols, "roll", len(cols["run"]))
    check("ratio_lp_against_the_better_incumbent", all(abs(v - 0.4) < 1e-12 for v in ratios["LP-MLADRC"]),
          repr(ratios["LP-MLADRC"]))
    check("ratio_ladrc", all(abs(v - 2.0) < 1e-12 for v in ratios["LADRC"]), repr(ratios["LADRC"]))
    check("ratio_diverged_is_a_word", ratios["RATE-ADRC"][7] == "diverged" and abs(ratios["RATE-ADRC"][0] - 1.0) < 1e-12,
          repr(ratios["RATE-ADRC"]))
    check("ratio_family_best", all(abs(v - 0.4) < 1e-12 for v in ratios["family best"]), repr(ratios["family best"]))
    rc, so, se = run(["ratio", out, "--where", "kind=1"])
    path = os.path.join(out, "figures", "ratio_roll_rotors.motor_tau_s_kind1.png")
    size = png_size(path) if os.path.exists(path) else None
    check("ratio_draws_a_map", rc == 0 and size is not None and size[0] >= MIN_PNG_PIXELS[0], se)
    check("ratio_prints_the_target_count", "LP-MLADRC roll: ratio <= 0.5 in 4 of 4 runs" in so and
          "RATE-ADRC roll: ratio <= 0.5 in 0 of 4 runs with an incumbent, 0 diverged" in so, so)
    rc, so, se = run(["ratio", out])
    check("ratio_whole_campaign_counts_the_divergence", rc == 0 and
          "RATE-ADRC roll: ratio <= 0.5 in 0 of 7 runs with an incumbent, 1 diverged" in so, so)
    rc, _, se = run(["ratio", out, "--where", "kind=3"])
    check("ratio_where_without_runs_exit_1", rc == 1 and "no run" in se, se)
    rc, _, se = run(["ratio", out, "--where", "nonesuch=1"])
    check("ratio_where_unknown_name_exit_1", rc == 1 and "--where nonesuch=1" in se, se)
    small = os.path.join(work, "small")  # LADRC and PID only: no incumbent
    rc, _, se = run(["ratio", small])
    check("ratio_without_incumbent_exit_1", rc == 1 and "incumbent" in se, se)


def tune_metrics_text(scenario, controllers, status):
    """metrics_text with tuning outcomes: status {controller: token} adds its
    `tune,status,-,TOKEN` row; a controller whose token is `untunable` is written as the
    simulator writes one it did not fly: every statistic `untunable`, no diverged rows."""
    lines = metrics_text(scenario, [(n, st if status.get(n) != "untunable" else None)
                                    for n, st in controllers]).splitlines()
    out = []
    for line in lines:
        f = line.split(",")
        if len(f) == 6 and status.get(f[1]) == "untunable":
            if f[2] == "-" and f[3].startswith("diverged"):
                continue
            if f[5] == "diverged":
                f[5] = "untunable"
        out.append(",".join(f))
    for n, token in status.items():
        out.append("%s,%s,tune,status,-,%s" % (scenario, n, token))
    return "\n".join(out) + "\n"


def tune_campaign():
    """4 runs of LADRC and INDI over delay x J: LADRC tuned, defaults, untunable, and in run 4
    (an older simulator) no status at all; INDI tuned, scenario, diverged after tuning, none."""
    header = ["run", "sensors.delay_ticks", "J"]
    plan = [["1", "0", "0.7"], ["2", "0", "1.3"], ["3", "50", "0.7"], ["4", "50", "1.3"]]

    def stats(base):
        return {a: ("%g" % (base + i), "0.1", "%g" % (3 * base), "0.25") for i, a in enumerate(AXES)}
    runs = {1: ([("LADRC", stats(1.0)), ("INDI", stats(2.0))], {"LADRC": "tuned", "INDI": "tuned"}),
            2: ([("LADRC", stats(1.5)), ("INDI", stats(2.5))], {"LADRC": "defaults", "INDI": "scenario"}),
            3: ([("LADRC", stats(9.0)), ("INDI", None)], {"LADRC": "untunable", "INDI": "tuned"}),
            4: ([("LADRC", stats(4.0)), ("INDI", stats(5.0))], {})}
    return header, plan, runs


def write_tune_out(out, header, plan, runs):
    os.makedirs(os.path.join(out, "runs"), exist_ok=True)
    with open(os.path.join(out, "plan.csv"), "w") as f:
        f.write(",".join(header) + "\n" + "".join(",".join(row) + "\n" for row in plan))
    for r, (controllers, status) in runs.items():
        d = os.path.join(out, "runs", "%05d" % r)
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "metrics.csv"), "w") as f:
            f.write(tune_metrics_text("%05d" % r, controllers, status))


AXES = ("roll", "pitch", "yaw")


def test_merge_tune(work):
    out = os.path.join(work, "tune")
    write_tune_out(out, *tune_campaign())
    rc, so, se = run(["merge", out])
    check("merge_tune_succeeds", rc == 0, se)
    rows = read(os.path.join(out, "campaign.csv")).decode().splitlines() if rc == 0 else ["", "", "", "", ""]
    header = rows[0].split(",")
    check("merge_tune_columns", header.index("LADRC.tune") == header.index("LADRC.yaw.diverged") + 1 and
          header[-1] == "INDI.tune" and header.count("LADRC.tune") == 1 and len(header) == 3 + 2 * 16, rows[0])
    col = {name: [row.split(",")[i] for row in rows[1:]] for i, name in enumerate(header)}
    check("merge_tune_tokens", col["LADRC.tune"] == ["tuned", "defaults", "untunable", "-"] and
          col["INDI.tune"] == ["tuned", "scenario", "tuned", "-"], repr((col.get("LADRC.tune"), col.get("INDI.tune"))))
    check("merge_untunable_passes_through", col["LADRC.roll.rms_deg"][2] == "untunable" and
          col["LADRC.pitch.settling_s"][2] == "untunable" and col["LADRC.yaw.diverged"][2] == "untunable",
          repr([c[2] for c in col.values()]))
    check("merge_tune_diverged_still_read", col["INDI.roll.rms_deg"][2] == "diverged" and
          col["INDI.roll.diverged"][2] == "yes" and col["INDI.roll.rms_deg"][0] == "2")

    # Without any status row the table is as before: no .tune column (test_merge's bytes).
    plain = os.path.join(work, "tune_none")
    header, plan, runs = tune_campaign()
    write_tune_out(plain, header, plan, {r: (c, {}) for r, (c, _) in runs.items()})
    run(["merge", plain])
    check("merge_no_status_no_column", ".tune" not in read(os.path.join(plain, "campaign.csv")).decode())


def test_tunemap(work):
    out = os.path.join(work, "tune_map")
    write_tune_out(out, *tune_campaign())
    rc, _, se = run(["tunemap", out])
    check("tunemap_without_merge_exit_1", rc == 1 and "merge" in se, se)
    run(["merge", out])
    rc, so, se = run(["tunemap", out])
    check("tunemap_succeeds", rc == 0, se)
    path = os.path.join(out, "figures", "tunemap.png")
    size = png_size(path) if os.path.exists(path) else None
    print("tunemap.png: %s, %d bytes" % ("%dx%d" % size if size else "missing", os.path.getsize(path) if size else 0))
    check("tunemap_draws_png", size is not None and size[0] >= 600 and size[1] >= 300)
    lines = so.splitlines()
    head = lines[0].split() if lines else []
    ladrc = next((line.split() for line in lines if line.startswith("LADRC ")), [])
    indi = next((line.split() for line in lines if line.startswith("INDI ")), [])
    check("tunemap_table_header", head[:7] == ["controller", "tuned", "defaults", "scenario", "untunable",
                                                "diverged", "no"], so)
    check("tunemap_table_counts", ladrc[1:] == ["1", "1", "0", "1", "0", "1"] and
          indi[1:] == ["1", "0", "1", "0", "1", "1"], so)

    cols = campaign.read_campaign(out)[2]
    outcomes = [[campaign.run_outcome(cols, c, r) for r in range(4)] for c in ("LADRC", "INDI")]
    check("tunemap_outcomes", outcomes == [["tuned", "defaults", "untunable", "-"],
                                           ["tuned", "scenario", "diverged", "-"]], repr(outcomes))
    rows = campaign.tunemap_rows(["sensors.delay_ticks", "J"], cols, None)
    check("tunemap_rows_per_run", [lab for lab, _ in rows][0] == "run 1: delay_ticks=0, J=0.7" and len(rows) == 4,
          repr(rows))
    # Grouped by the delay: the cell's most frequent outcome, its median RMS, its share.
    rows = campaign.tunemap_rows(["sensors.delay_ticks", "J"], cols, ["sensors.delay_ticks"])
    check("tunemap_rows_grouped", rows == [("delay_ticks=0 (2 runs)", [0, 1]), ("delay_ticks=50 (2 runs)", [2, 3])],
          repr(rows))
    check("tunemap_cell_group", campaign.tunemap_cell(cols, "LADRC", [0, 1]) == ("tuned", "1.25 (1/2)") and
          campaign.tunemap_cell(cols, "INDI", [2]) == ("diverged", "div.") and
          campaign.tunemap_cell(cols, "LADRC", [2]) == ("untunable", "untun."),
          repr([campaign.tunemap_cell(cols, c, rr) for c, rr in (("LADRC", [0, 1]), ("INDI", [2]), ("LADRC", [2]))]))
    rc, _, se = run(["tunemap", out, "--by", "J"])
    check("tunemap_by", rc == 0, se)
    rc, _, se = run(["tunemap", out, "--by", "nonesuch"])
    check("tunemap_unknown_by_exit_1", rc == 1 and "--by nonesuch" in se, se)
    # plot and ratio read a table with untunable runs
    rc, _, se = run(["plot", out])
    check("plot_reads_untunable", rc == 0, se)
    rc, _, se = run(["ratio", out])
    check("ratio_reads_untunable", rc == 0, se)


def main():
    work = tempfile.mkdtemp(prefix="campaign_test.")
    try:
        test_merge(work)
        test_merge_errors(work)
        test_merge_tune(work)
        try:
            import matplotlib  # noqa: F401
            import numpy  # noqa: F401
            have_plot = True
        except ImportError:
            have_plot = False
            print("SKIPPED: the plot checks (matplotlib or numpy missing)")
        if have_plot:
            test_plot(work)
            test_ratio(work)
            test_tunemap(work)
    finally:
        shutil.rmtree(work)
    print("%d failed" % failures)
    if failures:
        return 1
    return 0 if have_plot else 77


if __name__ == "__main__":
    sys.exit(main())
