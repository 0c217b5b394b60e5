#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""A roll axis of the paper's vehicle in a 1 kHz loop, from Python: a 10 deg
step at 0.2 s, then a 4 rad/s^2 disturbance with a 3 rad/s tone of 3 rad/s^2 from 1.5 s,
for LADRC, HP-MLADRC and PID, motors limited to 0.05 N m. Writes a PNG (first argument, default
step_response.png).

Run with the package installed (python/README.md), or from the checkout with
the shared library built (-DBUILD_SHARED_LIBS=ON):
    LADRC_LIBRARY=build/libladrc.so PYTHONPATH=python python3 python/examples/step_response.py
"""
import math
import sys

try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as e:
    print(f"SKIPPED: {e.name} is not installed (Debian: python3-numpy, python3-matplotlib)")
    sys.exit(77)

import ladrc

DT, J, KT = 1e-3, 5.445e-3, 0.09    # step (s), roll inertia (kg m^2), rotor drag (N m s)
t = np.arange(0.0, 4.0, DT)
ref = np.where(t >= 0.2, math.radians(10.0), 0.0)
dist = np.where(t >= 1.5, 4.0 + 3.0 * np.sin(3.0 * (t - 1.5)), 0.0)   # rad/s^2


def fly(variant):
    axis = ladrc.Axis({"variant": variant, "dt_s": DT, "inertia_kg_m2": J,
                       "u_min_Nm": -0.05, "u_max_Nm": 0.05})
    angle, rate, out = 0.0, 0.0, np.empty_like(t)
    for k in range(t.size):
        u = axis.step(ref[k], angle, rate)
        axis.set_applied(u)
        rate += DT * ((u - KT * rate) / J + dist[k])  # airframe: J theta'' = u - kt theta' + J d
        angle += DT * rate
        out[k] = angle
    return out


fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
for variant in ("LADRC", "HP_MLADRC", "PID"):
    angle = fly(variant)
    ax1.plot(t, np.degrees(angle), label=variant)
    ax2.plot(t, np.degrees(ref - angle), label=variant)
ax1.plot(t, np.degrees(ref), "k--", lw=0.8, label="reference")
ax1.set_ylabel("roll (deg)")
ax2.set_ylabel("error (deg)")
ax2.set_xlabel("time (s); disturbance from 1.5 s")
ax1.legend()
ax1.grid(True)
ax2.grid(True)
out = sys.argv[1] if len(sys.argv) > 1 else "step_response.png"
fig.savefig(out, dpi=100)
print(f"wrote {out}")
