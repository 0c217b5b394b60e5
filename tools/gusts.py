#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes broadband gusts into scenario files: a seeded sum of sines with a Dryden-like spectrum.

Usage: gusts.py [--check] FILE...

Each FILE holds, in its [disturbance] section, a block

    # gusts:begin seed=11 span_m=0.45 airspeed_m_s=6 band_rad_s=0.3:60 terms=10 rms_rad_s2=roll:8,pitch:8,yaw:0.8
    ...
    # gusts:end

whose lines this script rewrites from the parameters on the begin line: one signal per axis,
sum over k of a_k sin(w_k t + p_k) in rad/s^2. With --check it rewrites nothing and exits 1 when
a file's block differs from what the parameters give (the ctest check that the files are current).

Spectrum: the Dryden roll-gust form of MIL-F-8785C, Phi(w) ~ 1 / (1 + (4 b w / (pi V))^2), flat up
to the corner pi V / (4 b) (b the span, V the airspeed) and falling 20 dB/decade beyond: a rotor
pair sees the difference of the gust over the span, so the torque's spectrum has that shape.
The level is not Dryden's (it needs a turbulence intensity and the rotors' gust sensitivity, which
no file gives): each axis is scaled to the RMS given, as an angular acceleration.
Frequencies are drawn log-uniformly in the band, phases uniformly; a term's amplitude is
sqrt(2 Phi(w_k) dw_k), dw_k the width of its share of the band (midpoints in log w), so the
sum's spectrum follows Phi. Python's random (Mersenne Twister, seeded per axis) is the same on
every platform and version, so a seed gives the same file everywhere.
"""
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import write_whole  # noqa: E402

BEGIN, END = "# gusts:begin", "# gusts:end"
AXES = ("roll", "pitch", "yaw")


def parse_params(line):
    """{name: text} of the begin line's name=value words."""
    out = {}
    for word in line[len(BEGIN):].split():
        name, sep, value = word.partition("=")
        if not sep or not value:
            raise ValueError("expected name=value, got '%s'" % word)
        out[name] = value
    return out


def dryden_shape(w_rad_s, corner_rad_s):
    """Dryden's roll-gust spectrum up to its scale: flat, then -20 dB/decade past the corner."""
    return 1.0 / (1.0 + (w_rad_s / corner_rad_s) ** 2)


def terms(seed, axis_index, band, n, corner_rad_s, rms):
    """[(amplitude, frequency rad/s, phase rad)] of one axis, scaled to the RMS given."""
    rng = random.Random(seed * 1000 + axis_index)
    lo, hi = math.log(band[0]), math.log(band[1])
    logs = sorted(rng.uniform(lo, hi) for _ in range(n))
    phases = [rng.uniform(0.0, 2.0 * math.pi) for _ in range(n)]
    edges = [lo] + [(a + b) / 2.0 for a, b in zip(logs, logs[1:])] + [hi]
    raw = [math.sqrt(2.0 * dryden_shape(math.exp(x), corner_rad_s) * (math.exp(edges[k + 1]) - math.exp(edges[k])))
           for k, x in enumerate(logs)]
    scale = rms / math.sqrt(sum(a * a for a in raw) / 2.0)  # a sine of amplitude a has RMS a / sqrt(2)
    return [(a * scale, math.exp(x), p) for a, x, p in zip(raw, logs, phases)]


def block_lines(params):
    """The lines between the markers, from the begin line's parameters."""
    seed = int(params["seed"])
    span, speed = float(params["span_m"]), float(params["airspeed_m_s"])
    band = tuple(float(v) for v in params["band_rad_s"].split(":"))
    n = int(params["terms"])
    rms = {}
    for item in params["rms_rad_s2"].split(","):
        axis, _, value = item.partition(":")
        if axis not in AXES:
            raise ValueError("unknown axis '%s'" % axis)
        rms[axis] = float(value)
    if len(band) != 2 or not 0 < band[0] < band[1] or n < 1 or span <= 0 or speed <= 0:
        raise ValueError("need 0 < band low < band high, terms >= 1, span_m > 0, airspeed_m_s > 0")
    corner = math.pi * speed / (4.0 * span)
    lines = ["# Dryden corner pi V / (4 b) = %.3g rad/s; terms a sin(w t + p), a in rad/s^2" % corner]
    for i, axis in enumerate(AXES):
        if axis not in rms:
            continue
        parts = ["%.4g*sin(%.4g*t + %.4g)" % term for term in terms(seed, i, band, n, corner, rms[axis])]
        lines.append("%s = %s" % (axis, " + ".join(parts)))
    return lines


def process(path, check):
    """0 when the file is current (or was rewritten), 1 when --check finds it stale, 2 on an error."""
    with open(path) as f:
        text = f.read().split("\n")
    starts = [i for i, line in enumerate(text) if line.startswith(BEGIN)]
    ends = [i for i, line in enumerate(text) if line.startswith(END)]
    if len(starts) != 1 or len(ends) != 1 or ends[0] < starts[0]:
        print("gusts.py: %s: needs one '%s ...' line and one '%s' line after it" % (path, BEGIN, END), file=sys.stderr)
        return 2
    try:
        new = block_lines(parse_params(text[starts[0]]))
    except (KeyError, ValueError) as e:
        print("gusts.py: %s:%d: %s" % (path, starts[0] + 1, e), file=sys.stderr)
        return 2
    if text[starts[0] + 1:ends[0]] == new:
        return 0
    if check:
        print("gusts.py: %s: its gusts differ from what its parameters give; run tools/gusts.py %s"
              % (path, path), file=sys.stderr)
        return 1
    write_whole(path, "\n".join(text[:starts[0] + 1] + new + text[ends[0]:]))
    print("gusts.py: rewrote", path)
    return 0


def main(argv):
    check = "--check" in argv
    files = [a for a in argv if a != "--check"]
    if not files:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    return max(process(path, check) for path in files)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
