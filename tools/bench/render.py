#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The rendering part of tools/bench.sh: Markdown tables of one measurement
(tools/bench/measure.sh --all), each budget figure marked against its budget
("meets" / "over"), then where the instructions of the HP-MLADRC tick go.

Usage: render.py FIGURES              print the tables
       render.py FIGURES --page MD    also put them between MD's
                                      <!-- performance:start --> and
                                      <!-- performance:end --> markers
                                      (tools/bench.sh --docs: docs/performance.md)
"""
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree

from benchfigs import Figures, awk_num

START, END = "<!-- performance:start -->", "<!-- performance:end -->"
# The lean HP build (tools/bench/bench_lean.c), as the rows name it.
LEAN = "lean HP build (HP + Levant only, known frequency, one tone, no online search)"
# What HP-MLADRC on the gyro may cost a flight controller: its 3-axis tick at
# most 1.3 times CASCADED's, its 3-axis state at most 1.5 KB.
GYRO_PER_CASCADED = 1.3
GYRO_STATE_B = 1536


def num(text):
    return float(text)


def mark(x, op, lim):
    x, lim = num(x), num(lim)
    ok = x <= lim if op == "<=" else x < lim if op == "<" else x >= lim
    return "meets" if ok else "over"


def label(v):
    return "HP-MLADRC (two tones)" if v == "HP-MLADRC-2tones" else v


def render(fig):
    out = []

    def row(*cells):
        out.append("| %s | %s | %s | %s |" % cells)

    def echo(text=""):
        out.append(text)

    cases = Figures.CASES
    insn = fig.insn
    text, data, bss = fig.size_totals()
    flash, ram = text + data, data + bss
    stack_worst, _root, stack_chain, stack_ext = fig.stack()
    linked_hp = fig.linked_hp()
    ipc = fig.instructions_per_count()

    # the simulator's runs: the scenario's [run] controllers, duration_s each
    duration = fig.keyed("sim", "duration_s")
    controllers = fig.keyed("sim", "controllers").split()
    runs = len(controllers)
    batch = int(fig.keyed("sim", "batch"))
    simulated = awk_num(num(duration) * runs)
    wall = {}
    for line in fig.lines("wall"):
        name, _, secs = line.partition(" ")
        wall[name] = secs

    def rate(w, s=None):
        return "%.0f" % (num(s if s is not None else simulated) / num(w))

    def ratio(a, b):
        return "%.2f" % (num(a) / num(b))

    host = fig.fields("host")

    def host_ns(v, c):
        return "\n".join(f[3 + c] for f in host if len(f) > 3 + c and f[2] == "host" and f[3] == v)

    cg = {}
    for line in fig.lines("callgrind"):
        name, _, ir = line.partition(" ")
        cg[name] = ir
    cg_ticks = cg["ticks"]

    def host_insn(c, v):
        return "%.1f" % ((num(cg[f"{c}:{v}"]) - num(cg["empty"])) / num(cg_ticks))

    hp3 = insn("HP-MLADRC", 2)
    att_size = fig.size_of("ladrc_attitude_t")

    echo("| measure | value | budget | status |")
    echo("|---|---:|---:|---|")
    for v in cases:
        row(f"{label(v)}, one axis (ladrc_axis_step with a rate), instructions/tick", insn(v, 1), "", "")
    for v in ("PID", "LADRC", "LP-MLADRC"):
        row(f"{v}, 3 axes + mixer, instructions/tick", insn(v, 2), "", "")
    row("HP-MLADRC, 3 axes + mixer, instructions/tick", hp3, "<= 1500", mark(hp3, "<=", 1500))
    row("HP-MLADRC (two tones), 3 axes + mixer, instructions/tick", insn("HP-MLADRC-2tones", 2), "", "")
    lean3 = fig.lean_insn()
    row(f"HP-MLADRC, {LEAN}, 3 axes + mixer, instructions/tick", lean3, "<= 1500", mark(lean3, "<=", 1500))
    row("ratio HP-MLADRC / PID, 3 axes + mixer", ratio(hp3, insn("PID", 2)), "", "")
    for v in ("HP-MLADRC-act", "CASCADED", "INDI", "LADRC-act", "RATE-ADRC", "HP-MLADRC-gyro"):
        row(f"{v}, 3 axes + mixer, instructions/tick", insn(v, 2), "", "")
    # Against the cascaded P / PID baseline a flight stack would otherwise fly.
    for v, budget in (("HP-MLADRC-gyro", 1.3), ("RATE-ADRC", 1.0)):
        r = ratio(insn(v, 2), insn("CASCADED", 2))
        row(f"ratio {v} / CASCADED, 3 axes + mixer", r, f"<= {budget}", mark(r, "<=", budget))
    # The same target in instructions: what a flight controller pays for CASCADED, plus 30 %.
    gyro3 = insn("HP-MLADRC-gyro", 2)
    gyro_budget = "%.0f" % (GYRO_PER_CASCADED * num(insn("CASCADED", 2)))
    row(f"HP-MLADRC-gyro, 3 axes + mixer, instructions/tick, against {GYRO_PER_CASCADED} x CASCADED's", gyro3,
        f"<= {gyro_budget}", mark(gyro3, "<=", gyro_budget))
    # The actuator model's own cost (LADRC-act against LADRC) and HP-MLADRC's
    # with its command advanced over the modelled actuator, per axis.
    for v, base, what in (("LADRC-act", "LADRC", "LADRC"),
                          ("HP-MLADRC-act", "HP-MLADRC", "HP-MLADRC (with its advanced command)")):
        extra = "%.1f" % (num(insn(v, 1)) - num(insn(base, 1)))
        row(f"actuator model (30 ms lag, 2 ticks), extra instructions/tick per axis: {what}", extra, "< 60",
            mark(extra, "<", 60))
    for v in cases:
        row(f"{label(v)}, 3 axes + mixer, dearest single tick, instructions (+-{ipc})", fig.worst(v), "", "")
    row(f"HP-MLADRC, {LEAN}, 3 axes + mixer, dearest single tick, instructions (+-{ipc})", fig.lean_worst(), "", "")
    for c in (1, 2):
        for v in cases:
            row(f"{label(v)}, {'one axis' if c == 1 else '3 axes + mixer'}, host, ns/tick", host_ns(v, c), "", "")
    for c in ("axis", "attitude"):
        for v in cases:
            row(f"{label(v)}, {'one axis' if c == 'axis' else '3 axes + mixer'}, host, instructions/tick (callgrind)",
                host_insn(c, v), "", "")
    row("3-axis state, sizeof(ladrc_attitude_t), B", att_size, "<= 512", mark(att_size, "<=", 512))
    row("3-axis state, sizeof(ladrc_attitude_t), against the HP-MLADRC-gyro target of 1.5 KB, B", att_size,
        f"<= {GYRO_STATE_B}", mark(att_size, "<=", GYRO_STATE_B))
    lean_size = fig.lean_size_of("ladrc_attitude_t")
    row(f"3-axis state, {LEAN}, sizeof(ladrc_attitude_t), B", lean_size, "<= 512", mark(lean_size, "<=", 512))
    for t in ("ladrc_axis_t", "ladrc_hp_estimator_t", "ladrc_rls_t"):
        row(f"sizeof({t}), {LEAN}, B", fig.lean_size_of(t), "", "")
    row("mixer state, sizeof(ladrc_mixer_t), B", fig.size_of("ladrc_mixer_t"), "", "")
    for t in ("ladrc_attitude_config_t", "ladrc_axis_t", "ladrc_axis_config_t", "ladrc_mixer_config_t", "ladrc_pid_t",
              "ladrc_cascaded_t", "ladrc_leso_t", "ladrc_td_t", "ladrc_levant_t", "ladrc_lp_estimator_t",
              "ladrc_hp_estimator_t", "ladrc_rls_t", "ladrc_indi_t", "ladrc_reso_t", "ladrc_gyro_filter_t"):
        row(f"sizeof({t}), B", fig.size_of(t), "", "")
    row("library flash (text + data), B", flash, "<= 8192", mark(flash, "<=", 8192))
    for obj, obj_flash in fig.size_objects():
        row(f"flash of {obj}, B", obj_flash, "", "")
    row("library RAM (data + bss), B", ram, "", "")
    row("library flash an HP-MLADRC firmware links (tools/bench/fw_hp.c, --gc-sections), B", linked_hp, "", "")
    lean_flash = fig.linked_hp("linked-lean")
    row(f"library flash the HP-MLADRC firmware links, {LEAN} (tools/bench/fw_hp.c, --gc-sections), B", lean_flash,
        "<= 8192", mark(lean_flash, "<=", 8192))
    row("worst-case stack of one tick, B", stack_worst, "<= 256", mark(stack_worst, "<=", 256))
    for c in controllers:
        row(f"simulator, paper, {c} alone, no CSV, --jobs 1, x real time", rate(wall[f"ctrl_nocsv:{c}"], duration),
            "", "")
        row(f"simulator, paper, {c} alone, full CSV, --jobs 1, x real time", rate(wall[f"ctrl_csv:{c}"], duration),
            "", "")
    r_nocsv, r_csv = rate(wall["nocsv1"]), rate(wall["csv1"])
    row("simulator, paper, no CSV, --jobs 1, x real time", r_nocsv, ">= 2000", mark(r_nocsv, ">=", 2000))
    row("simulator, paper, full CSV, --jobs 1, x real time", r_csv, ">= 300", mark(r_csv, ">=", 300))
    row(f"simulator, paper x{batch} ({runs * batch} runs), no CSV, --jobs 2, x real time",
        rate(wall["batch2"], awk_num(num(simulated) * batch)), "", "")
    row(f"simulator, paper ({runs} runs), no CSV, speed-up --jobs 1 -> 2", ratio(wall["nocsv1"], wall["nocsv2"]), "",
        "")
    row(f"simulator, paper ({runs} runs), full CSV, speed-up --jobs 1 -> 2", ratio(wall["csv1"], wall["csv2"]), "", "")
    speedup_batch = ratio(wall["batch1"], wall["batch2"])
    row(f"simulator, paper x{batch} ({runs * batch} runs), no CSV, speed-up --jobs 1 -> 2", speedup_batch, ">= 1.8",
        mark(speedup_batch, ">=", 1.8))

    echo()
    echo(f"{fig.clock()}; the empty loop (same inputs, no call) is subtracted; two runs gave identical counts.")

    def engaged(c, k):
        return "\n".join(f"weight {f[6]} from tick {f[11]}, {f[8]} tone(s)" for f in fig.m4f("engaged", c, k))

    def saturated(c):
        return "\n".join(f[4] for f in fig.m4f("saturated", c))

    echo("Mixer in LADRC_MIXER_SATURATE (rotor limits 1e4..2e5 rad^2/s^2), thrust from ladrc_mixer_thrust_from_tilt. "
         "Inputs: the paper references from t = 12 s and the angles and rates of the closed loop the HP-MLADRC "
         "controller itself flies from reset (rigid body with the paper's inertia, drag 0.09 N m s and gyroscopic "
         "coupling; achieved torques applied) under the Table 2 disturbance 20 -+ 120 sin(3 t) rad/s^2 on roll and "
         "pitch, a quarter of it on yaw, or for the two-tone case the same plus 30 sin(8 t) (yaw: a quarter); so the "
         "timed HP-MLADRC cases repeat that closed loop and their estimators run engaged over the measured ticks "
         f"(checked: one tone, 3 axes: {engaged('HP-MLADRC', 'attitude')}, one axis: {engaged('HP-MLADRC', 'axis')}; "
         f"two tones, 3 axes: {engaged('HP-MLADRC-2tones', 'attitude')}, one axis: "
         f"{engaged('HP-MLADRC-2tones', 'axis')}). The warm-up is long enough for that. The other variants see the "
         "same angles in open loop. HP-MLADRC-gyro (on the observer loop's angles its 3-axis fit does not engage) "
         "flies its own closed loop from reset the same way, with its actuator model in the plant (each torque acts "
         "2 ticks late through a 30 ms first-order lag); checked: 3 axes: "
         f"{engaged('HP-MLADRC-gyro', 'attitude')}, one axis: {engaged('HP-MLADRC-gyro', 'axis')}. "
         "The disturbance's peaks ask for more roll and pitch torque than the rotor limits "
         "leave at hover thrust, so in the HP-MLADRC 3-axis cases the mixer cuts thrust or yaw back on "
         f"{saturated('HP-MLADRC')} (one tone), {saturated('HP-MLADRC-2tones')} (two tones) and "
         f"{saturated('HP-MLADRC-gyro')} (gyro) of the "
         f"{fig.ticks_per_block()} measured ticks, and ladrc_mixer_step takes its saturating path.")
    host_clock = "\n".join(l[len("BENCH host clock "):] for l in fig.lines("host") if l.startswith("BENCH host clock "))
    echo(f"Host: {fig.keyed('env', 'cpu')}, gcc Release (-O3) build {fig.keyed('env', 'bench-host')}; ns/tick: "
         f"{host_clock}. Instructions/tick: x86-64 instructions counted by valgrind --tool=callgrind "
         f"--toggle-collect=bench_collect (only the {cg_ticks} measured ticks, after the same warm-up), minus the "
         f"same count for the empty loop, divided by {cg_ticks}; deterministic, not comparable with the Cortex-M4F "
         "counts.")
    echo(f"Stack: deepest of {fig.stack_roots()}; chain: {stack_chain}; not counted (C library): {stack_ext}.")
    echo(f"Simulator: {runs} runs of {duration} s ({simulated} s simulated), best wall time of 5; x real time = "
         f"simulated s / wall s on {fig.keyed('env', 'nproc')} cores; one controller alone: --controllers NAME, "
         f"{duration} s simulated.")

    # ---- where the instructions go --------------------------------------------------
    mod = fig.module

    def calc(x):
        return "%.2f" % x

    fd = "\n".join(f[3] for f in fig.fields("m4f") if len(f) > 3 and f[2] == "hp_fit_decimation")
    fit_decimation = num(fd)
    leso, levant, hp = num(mod("ladrc_leso_step")), num(mod("ladrc_levant_step")), num(mod("ladrc_hp_step"))
    twin, hp2 = num(mod("ladrc_leso_step_twin")), num(mod("ladrc_hp_step_2tones"))
    rls3, rls5 = num(mod("ladrc_rls_update_3")), num(mod("ladrc_rls_update_5"))
    lone = mod("lone_hp_axes_x3")
    thrust, mixer = mod("ladrc_mixer_thrust_from_tilt"), mod("ladrc_mixer_step")
    hp_own = calc(hp - rls3 / fit_decimation)
    hp2_own = calc(hp2 - rls5 / fit_decimation)
    axis_rest = calc(num(lone) / 3 - leso - twin - levant - hp)
    att_rest = calc(num(hp3) - num(lone) - num(thrust) - num(mixer))

    def brow(module, per_call, calls):  # calls per tick 0: not part of the tick, no share
        if calls in ("0", 0):
            echo(f"| {module} | {per_call} | 0 |  |")
        else:
            echo(f"| {module} | {per_call} | {calls} | {calc(100 * num(per_call) * num(calls) / num(hp3))} % |")

    echo()
    echo("Where the instructions of the HP-MLADRC 3-axis + mixer tick go (Cortex-M4F, same build and method):")
    echo()
    echo("| module | instructions/call | calls per HP 3-axis tick | share of the HP 3-axis tick |")
    echo("|---|---:|---:|---:|")
    brow("ladrc_leso_step (each axis's observer)", mod("ladrc_leso_step"), 3)
    brow("ladrc_leso_step_twin (each HP axis's shadow observer)", mod("ladrc_leso_step_twin"), 3)
    brow("ladrc_levant_step (implicit, the HP axis default)", mod("ladrc_levant_step"), 3)
    brow("ladrc_hp_step without its RLS update (gate, tones, online frequencies, model), one tone", hp_own, 3)
    brow(f"ladrc_rls_update, 3 params (HP fit of bias and one tone, every {fd} ticks)", mod("ladrc_rls_update_3"),
         calc(3 / fit_decimation))
    brow("rest of ladrc_axis_step with a rate (checks, hand-over, control law) and the feed setters: a lone HP axis "
         "minus the rows above", axis_rest, 3)
    brow("ladrc_mixer_thrust_from_tilt", thrust, 1)
    brow("ladrc_mixer_step (allocate, saturate)", mixer, 1)
    brow("rest of the 3-axis tick (coupling feed, known part): the tick minus 3 lone axes and the mixer rows",
         att_rest, 1)
    brow("HP-MLADRC 3 axes + mixer, measured", hp3, 1)
    brow("not in this tick: ladrc_hp_step without its RLS update, two tones", hp2_own, 0)
    brow("not in this tick: ladrc_rls_update, 5 params (HP fit of bias and two tones)", mod("ladrc_rls_update_5"), 0)
    brow("not in this tick: HP-MLADRC (two tones) 3 axes + mixer, measured", insn("HP-MLADRC-2tones", 2), 0)
    brow("not in this tick: ladrc_td_step (LADRC's shaper)", mod("ladrc_td_step"), 0)
    brow("not in this tick: ladrc_lp_step (LP-MLADRC, with its 1-param RLS)", mod("ladrc_lp_step"), 0)
    brow("not in this tick: ladrc_pid_step (PID)", mod("ladrc_pid_step"), 0)
    hp_state = "; ".join(f"{f[3]}: weight {f[5]}, {f[7]} tone(s)" for f in fig.fields("m4f")
                         if len(f) > 7 and f[2] == "hp_state" and f[3].startswith("ladrc_hp_step"))
    echo()
    echo(f"Each module is timed alone like the ticks ({fig.ticks_per_block_text()}), configured as the axis defaults "
         "configure it, on the inputs it sees in the HP 3-axis case (replayed): its torques, thrust, applied torques, "
         "d_hat, fed rates and known parts, the references and angles; ladrc_hp_step on roll's recorded HP sample "
         "(z3 - z3 of the shadow), one tone and two tones, engaged over the measured ticks like the axes "
         f"({hp_state}); the RLS on the regressors of the fit (bias, the phasors at 3 and 8 rad/s at the fit samples' "
         "times) and the disturbance, at the engaged fit's forgetting. Lone axes: the three HP-MLADRC axes "
         "configured as the attitude configures them, each tick given the recorded fed rate, known part and applied "
         f"torque, stepped side by side, no attitude layer, no mixer ({lone} instructions per tick for the three). The "
         "two \"rest\" rows make the shares add up to the measured tick, so they also carry any difference between "
         "the modules alone and inside the tick.")

    # ---- where the instructions of the gyro tick go -----------------------------------
    gyro3 = insn("HP-MLADRC-gyro", 2)
    cas3 = insn("CASCADED", 2)
    lp_act, lead = num(mod("ladrc_lp_step_act")), num(mod("ladrc_lp_step_lead"))
    hpg = num(mod("ladrc_hp_step_gyro"))
    lone_g = mod("lone_hp_gyro_axes_x3")
    hpg_own = calc(hpg - rls3 / fit_decimation)
    gaxis_rest = calc(num(lone_g) / 3 - leso - levant - lp_act - lead - hpg)
    gatt_rest = calc(num(gyro3) - num(lone_g) - num(thrust) - num(mixer))

    def grow(module, per_call, calls):
        if calls in ("0", 0):
            echo(f"| {module} | {per_call} | 0 |  |")
        else:
            echo(f"| {module} | {per_call} | {calls} | {calc(100 * num(per_call) * num(calls) / num(gyro3))} % |")

    echo()
    echo("Where the instructions of the HP-MLADRC-gyro 3-axis + mixer tick go (Cortex-M4F, same build and method), "
         f"against CASCADED's {cas3} (ratio {ratio(gyro3, cas3)}):")
    echo()
    echo("| module | instructions/call | calls per HP-gyro 3-axis tick | share of the HP-gyro 3-axis tick |")
    echo("|---|---:|---:|---:|")
    grow("ladrc_leso_step (each axis's observer)", mod("ladrc_leso_step"), 3)
    grow("ladrc_levant_step (implicit, the HP axis default)", mod("ladrc_levant_step"), 3)
    grow("ladrc_lp_step with the actuator model (the LP estimator on the rate, its 1-param RLS)",
         mod("ladrc_lp_step_act"), 3)
    grow("ladrc_lp_step_lead (LP's command advanced over the actuator)", mod("ladrc_lp_step_lead"), 3)
    grow("ladrc_hp_step on the gyro sample without its RLS update (block mean, gate, tones, online frequencies, "
         "model, command)", hpg_own, 3)
    grow(f"ladrc_rls_update, 3 params (HP fit of bias and one tone, every {fd} ticks)", mod("ladrc_rls_update_3"),
         calc(3 / fit_decimation))
    grow("rest of ladrc_axis_step with a rate (checks, actuator model, hand-over, control law) and the feed "
         "setters: a lone HP-gyro axis minus the rows above", gaxis_rest, 3)
    grow("ladrc_mixer_thrust_from_tilt", thrust, 1)
    grow("ladrc_mixer_step (allocate, saturate)", mixer, 1)
    grow("rest of the 3-axis tick (coupling feed, known part): the tick minus 3 lone axes and the mixer rows",
         gatt_rest, 1)
    grow("HP-MLADRC-gyro 3 axes + mixer, measured", gyro3, 1)
    grow("not in this tick: CASCADED 3 axes + mixer, measured", cas3, 0)
    grow("not in this tick: ladrc_leso_step_twin (the observer HP's shadow)", mod("ladrc_leso_step_twin"), 0)
    gyro_state = "; ".join(f"{f[3]}: weight {f[5]}, {f[7]} tone(s)" for f in fig.fields("m4f")
                           if len(f) > 7 and f[2] == "hp_state" and f[3] in ("ladrc_hp_step_gyro", "lone_hp_gyro_axis"))
    echo()
    echo("Timed as above, on the inputs of the HP-MLADRC-gyro 3-axis case (replayed): ladrc_lp_step configured as the "
         "gyro axis configures its LP estimator (30 ms lag, 2 ticks), on roll's measured rate and its known input "
         "(b0 times the acting torque plus the fit's estimate), ladrc_lp_step_lead on that estimator, ladrc_hp_step "
         "configured as the gyro axis configures its fit (block means, the sample's age, the command advanced over "
         "the actuator) on roll's recorded sample (LP's sample plus the fit's estimate); lone axes: the three "
         f"HP-MLADRC-gyro axes ({lone_g} instructions per tick for the three). Engaged: {gyro_state}.")
    gyro_filter_table(echo, fig, calc)
    frame_table(echo, fig, calc)
    return "\n".join(out)


def gyro_filter_table(echo, fig, calc):
    """The gyro filter stage: per notch and channel, and the RPM bank against the HP-MLADRC estimators."""
    mod = fig.module
    notch, lpf2 = num(mod("ladrc_gyro_filter_step_notch_1ch")), num(mod("ladrc_gyro_filter_step_lpf2_1ch"))
    centres, rpm3 = num(mod("ladrc_gyro_filter_set_rotor_hz_4x3")), num(mod("gyro_filter_rpm_4x3_3ch"))
    full3 = num(mod("gyro_filter_rpm_4x3_lpf2_3ch"))
    # The HP-MLADRC tick's own estimator: ladrc_hp_step (its RLS fit included) and the shadow observer, per axis.
    hp_est = 3 * (num(mod("ladrc_hp_step")) + num(mod("ladrc_leso_step_twin")))
    per_section = (rpm3 - centres) / (12 * 3)
    echo()
    echo("The gyro filter stage (Cortex-M4F, same build and method):")
    echo()
    echo("| stage | instructions/call | per notch and channel |")
    echo("|---|---:|---:|")
    echo(f"| one fixed notch on one channel (call included) | {calc(notch)} |  |")
    echo(f"| second-order low-pass on one channel (call included) | {calc(lpf2)} |  |")
    echo(f"| ladrc_gyro_filter_set_rotor_hz: 12 RPM centres moved (4 rotors x 3 harmonics) | {calc(centres)} | "
         f"{calc(centres / 12)} per centre |")
    echo(f"| RPM bank 4 x 3 on 3 axes: centres moved, then 36 notch steps | {calc(rpm3)} | {calc(per_section)} |")
    echo(f"| the same with a second-order low-pass after it | {calc(full3)} |  |")
    echo(f"| HP-MLADRC's own estimators, 3 axes: 3 x (ladrc_hp_step with its RLS + ladrc_leso_step_twin) | "
         f"{calc(hp_est)} |  |")
    echo()
    echo(f"The 4 x 3 RPM bank on 3 axes costs {calc(rpm3 / hp_est)}x HP-MLADRC's own estimators (target: at most 2x). "
         "The bank's centres move every tick (each rotor wandering +-10 % about 120 Hz, all 12 centres on); the gyro "
         "samples are the HP 3-axis case's measured rates. sizeof(ladrc_gyro_filter_t) "
         f"{fig.size_of('ladrc_gyro_filter_t')} B (6 channels, 4 fixed notches, 8 rotors x 4 harmonics and a low-pass "
         "at most).")


def frame_table(echo, fig, calc):
    """The quaternion frame's front end: LADRC's 3-axis attitude step in both frames."""
    euler, quat = num(fig.module("attitude_step_ladrc_euler")), num(fig.module("attitude_step_ladrc_quat"))
    echo()
    echo("The attitude frames (Cortex-M4F, same build and method; LADRC's 3 axes, ladrc_attitude_step or "
         "ladrc_attitude_step_quat, no mixer, on the HP 3-axis case's attitudes as quaternions):")
    echo()
    echo("| attitude step | instructions/tick |")
    echo("|---|---:|")
    echo(f"| Euler frame (per angle) | {calc(euler)} |")
    echo(f"| quaternion frame (tilt priority, yaw weight 0.4) | {calc(quat)} |")
    echo(f"| the quaternion front end | {calc(quat - euler)} |")


def main() -> int:
    args = sys.argv[1:]
    if len(args) not in (1, 3) or (len(args) == 3 and args[1] != "--page"):
        print("usage: render.py FIGURES [--page MARKDOWN]", file=sys.stderr)
        return 2
    table = render(Figures(args[0]))
    print(table)
    if len(args) == 3:
        path = args[2]
        text = open(path, encoding="utf-8").read()
        i, j = text.index(START) + len(START), text.index(END)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text[:i] + "\n" + table + "\n" + text[j:])
    return 0


if __name__ == "__main__":
    sys.exit(main())
