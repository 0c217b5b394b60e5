#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Write the rate-loop parameters file apply.sh takes, from an airframe.

    params.py --inertia JX JY JZ --arm-m L --thrust-coeff KL --yaw-coeff B
              --w2-max W2 [--thrust-curve K --hover-command C] [--frame quadp|quadx]
              [--motor-idle 550] [--pidsum-limit 500 500 400]
              [--k-w 75 75 75] [--wo 300 300 300] [--motor-tau-s 0] [--delay-ticks 0]
              [-o FILE]

b0 in rad/s^2 per pidSum unit is kappa / J, kappa the torque (N m) one pidSum
unit makes (docs/betaflight-integration.md, "b0 in pidSum units"):

    one pidSum unit -> mix 1/1000 (PID_MIXER_SCALING) -> motor command
    R/1000 per motor with a mixer weight of 1, R = 1 - motor_idle/10000 (PWM
    endpoints 1000..2000 us, outputLow = 1000 + motor_idle/10) -> w^2 changes
    by dw2/dc = W2 (1 - K + 2 K C) (the simulator's w^2 = W2 ((1 - K) c + K c^2))
    -> torque: roll and pitch KL w^2 at the lever, yaw B w^2.

    QUADP: roll and pitch 2 motors at lever L:       kappa = 2 L KL dw2/dc R / 1000
    QUADX: roll and pitch 4 motors at lever L/sqrt2: kappa = 2 sqrt2 L KL dw2/dc R / 1000
    yaw (either): 4 motors:                          kappa = 4 B dw2/dc R / 1000

It holds while the mixer passes the sum through unscaled: AIRMODE on (without
it Betaflight scales the mix by 0.5 + throttle below half throttle) and no
motor at its end (the mixer's normalisation).
"""
import argparse
import math
import sys


def kappas(args):
    motor_range = 1.0 - args.motor_idle / 10000.0
    dw2_dc = args.w2_max * (1.0 - args.thrust_curve + 2.0 * args.thrust_curve * args.hover_command)
    per_unit = dw2_dc * motor_range / 1000.0  # w^2 (rad^2/s^2) per pidSum unit, one motor of weight 1
    if args.frame == "quadp":
        rp = 2.0 * args.arm_m * args.thrust_coeff * per_unit
    else:
        rp = 2.0 * math.sqrt(2.0) * args.arm_m * args.thrust_coeff * per_unit
    return [rp, rp, 4.0 * args.yaw_coeff * per_unit], motor_range, dw2_dc


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--inertia", type=float, nargs=3, required=True, metavar=("JX", "JY", "JZ"), help="kg m^2")
    ap.add_argument("--arm-m", type=float, required=True, help="rotor lever from the centre (m)")
    ap.add_argument("--thrust-coeff", type=float, required=True, help="KL: thrust per w^2 (N s^2)")
    ap.add_argument("--yaw-coeff", type=float, required=True, help="B: yaw torque per w^2 (N m s^2)")
    ap.add_argument("--w2-max", type=float, required=True, help="w^2 at full command (rad^2/s^2)")
    ap.add_argument("--thrust-curve", type=float, default=0.0, help="K of w^2 = W2 ((1 - K) c + K c^2)")
    ap.add_argument("--hover-command", type=float, default=0.0, help="C: the command c the slope is taken at")
    ap.add_argument("--frame", choices=("quadp", "quadx"), default="quadp", help="Betaflight's mixer")
    ap.add_argument("--motor-idle", type=float, default=550.0, help="Betaflight's motor_idle (percent x 100)")
    ap.add_argument("--pidsum-limit", type=float, nargs=3, default=[500.0, 500.0, 400.0])
    ap.add_argument("--k-w", type=float, nargs=3, default=[75.0, 75.0, 75.0], help="rate-loop crossover (1/s)")
    ap.add_argument("--wo", type=float, nargs=3, default=[300.0, 300.0, 300.0], help="observer bandwidth (rad/s)")
    ap.add_argument("--motor-tau-s", type=float, default=0.0)
    ap.add_argument("--delay-ticks", type=int, default=0, help="in PID loop ticks")
    ap.add_argument("-o", "--output", help="the file to write (default: stdout)")
    args = ap.parse_args()
    for name in ("arm_m", "thrust_coeff", "yaw_coeff", "w2_max"):
        if not getattr(args, name) > 0.0:
            ap.error(f"--{name.replace('_', '-')} must be > 0")
    if min(args.inertia) <= 0.0:
        ap.error("--inertia: each must be > 0")
    kappa, motor_range, dw2_dc = kappas(args)
    b0 = [k / j for k, j in zip(kappa, args.inertia)]
    text = [
        "# Rate-loop parameters for integrations/betaflight/apply.sh, written by params.py:",
        "#   " + " ".join(sys.argv[1:]),
        f"# motor range R = {motor_range:.6g}, dw2/dc = {dw2_dc:.6g} rad^2/s^2,"
        f" kappa = {kappa[0]:.6g} {kappa[1]:.6g} {kappa[2]:.6g} N m per pidSum unit",
        "k_w_per_s = " + " ".join(f"{v:.6g}" for v in args.k_w),
        "wo_rad_s = " + " ".join(f"{v:.6g}" for v in args.wo),
        "b0_rad_s2_per_pidsum = " + " ".join(f"{v:.6g}" for v in b0),
        "pidsum_limit = " + " ".join(f"{v:.6g}" for v in args.pidsum_limit),
        f"motor_tau_s = {args.motor_tau_s:.6g}",
        f"delay_ticks = {args.delay_ticks}",
    ]
    out = "\n".join(text) + "\n"
    if args.output:
        with open(args.output, "w") as f:
            f.write(out)
    else:
        sys.stdout.write(out)


if __name__ == "__main__":
    main()
