#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes the seed corpus of tests/fuzz/fuzz_gyro_filter.c (tests/fuzz/corpus/gyro_filter/):
configs at 1, 4 and 8 kHz, and sequences of the adversarial kinds the target decodes (random
speeds every tick, alternating speeds, sawtooth sweeps, speeds at the range's ends and beyond,
samples at every scale, bad samples and speeds, resets), in the byte layout the target reads.
The corpus's found_* inputs are kept as the fuzzer found them, not written here.

Usage: tests/fuzz/make_gyro_filter_corpus.py [OUT_DIR]"""
import math
import os
import struct
import sys

RATES = {1000: 0, 2000: 1, 4000: 2, 8000: 3, 500: 4, 3200: 5}


def log_byte(fraction, lo, hi):
    """The byte that log_between(lo, hi) decodes to fraction (of Nyquist, or a Q)."""
    return max(0, min(254, round(254.0 * math.log(fraction / lo) / math.log(hi / lo))))


def config(rate_hz, channels, lpf_order=0, lpf_hz=100.0, notches=(), notch_q=5.0, rotors=0, harmonics=1,
           rpm_q=5.0, rpm_min_hz=100.0, fade_hz=50.0):
    nyq = rate_hz / 2.0
    out = [RATES[rate_hz], channels - 1, lpf_order, log_byte(lpf_hz / nyq, 0.02, 1.0), len(notches)]
    for i in range(4):
        out.append(log_byte((notches[i] if i < len(notches) else 100.0) / nyq, 0.02, 0.95))
    out += [log_byte(notch_q, 0.5, 10.0), rotors, harmonics - 1, log_byte(rpm_q, 0.5, 10.0),
            log_byte(rpm_min_hz / nyq, 0.02, 0.95)]
    out += [0] if fade_hz == 0.0 else [1, log_byte(fade_hz / nyq, 0.001, 0.5)]
    return bytes(out)


def speed_byte(hz, rate_hz):
    """A speed as decode_speed reads it: over [0, 1.1 x 0.45 x the rate]."""
    return max(0, min(254, round(254.0 * hz / (1.1 * 0.45 * rate_hz))))


def tail(rate_hz, rotor_hz, samples, scale_index=0):
    top = 1.1 * 0.45 * rate_hz
    return bytes([scale_index] + [round(255.0 * hz / top) for hz in rotor_hz] + list(samples))


def run(kind, ticks, seed=1, lo=0, hi=0, period=2, scale_index=0):
    """An op of kind 2 (random speeds), 3 (alternating lo / hi) or 4 (sawtooth), ticks = 1 + 4 n."""
    return bytes([(2 + kind) | (scale_index << 4), (ticks - 1) // 4, seed >> 8, seed & 255, lo, hi, period - 2])


def tick(samples, speeds=None, scale_index=0):
    op = (1 if speeds is not None else 0) | (scale_index << 4)
    return bytes([op] + (list(speeds) if speeds is not None else []) + list(samples))


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "corpus", "gyro_filter")
    os.makedirs(out_dir, exist_ok=True)
    seeds = {}
    # a second of random speeds on 2 rotors (F14's latch), then steady
    c = config(1000, 1, rotors=2, harmonics=1, rpm_min_hz=20.0, fade_hz=10.0)
    seeds["random_speeds_1s"] = c + tail(1000, (150.0, 160.0), [200]) + run(0, 1001, seed=7)
    # 100 / 200 Hz alternating on 4 rotors x 3 harmonics with 4 fixed notches and a low-pass, 3 channels
    c = config(1000, 3, lpf_order=2, lpf_hz=150.0, notches=(60.0, 130.0, 200.0, 270.0), rotors=4, harmonics=3,
               rpm_min_hz=50.0, fade_hz=20.0)
    seeds["alternating_4x3_4_notches"] = c + tail(1000, (100.0, 110.0, 120.0, 130.0), [150, 100, 127]) + run(
        1, 1001, lo=speed_byte(100.0, 1000), hi=speed_byte(200.0, 1000))
    # a sawtooth over the whole range every 3 ticks, at 4 kHz, 8 rotors x 4 harmonics
    c = config(4000, 3, lpf_order=1, lpf_hz=300.0, rotors=8, harmonics=4, rpm_min_hz=80.0, fade_hz=40.0)
    seeds["sawtooth_3_ticks_4khz"] = c + tail(4000, [120.0 + 10 * r for r in range(8)], [10, 128, 240]) + run(
        2, 1001, period=3)
    # speeds at the range's ends, past them and bad (255 and an edge index), at 8 kHz
    c = config(8000, 2, lpf_order=2, lpf_hz=500.0, notches=(300.0,), rotors=4, harmonics=2, rpm_min_hz=100.0)
    ends = b"".join(tick([100, 160], speeds=[0, 254, 255, 9, 255, 5]) + tick([90, 170], speeds=[255, 0, 255, 3, 254, 1])
                    for _ in range(20))
    seeds["speeds_at_the_ends_8khz"] = c + tail(8000, (200.0, 300.0, 400.0, 500.0), [127, 127]) + ends
    # huge samples (the largest the filter takes) under random speeds, then bad samples of every kind
    c = config(1000, 2, lpf_order=2, lpf_hz=100.0, notches=(80.0,), rotors=4, harmonics=3, rpm_min_hz=50.0)
    bad = b"".join(tick([255, e, 255, (e + 8) % 16], scale_index=1) for e in range(16))
    seeds["huge_and_bad_samples"] = (c + tail(1000, (120.0, 130.0, 140.0, 150.0), [0, 254], scale_index=1)
                                     + run(0, 401, seed=99, scale_index=3) + bad + run(0, 101, seed=5))
    # resets, on good values and on bad ones (the channel rests on its latest output)
    c = config(2000, 3, lpf_order=1, lpf_hz=200.0, rotors=2, harmonics=2, rpm_min_hz=60.0)
    resets = bytes([5 | (1 << 4), 10, 255, 0, 200]) + tick([1, 2, 3]) + bytes([5, 255, 1, 255, 2, 127])
    seeds["resets"] = c + tail(2000, (100.0, 200.0), [127, 127, 127]) + run(0, 201) + resets + run(1, 101, lo=10,
                                                                                                     hi=200)
    # configs the filter refuses: a NaN step, 7 channels, lpf order 3
    seeds["refused_nan_dt"] = bytes([7]) + struct.pack("<f", float("nan")) + bytes(16)
    seeds["refused_7_channels"] = bytes([0, 255]) + bytes(16)
    seeds["refused_lpf_order_3"] = bytes([0, 0, 255]) + bytes(16)
    for name, data in seeds.items():
        with open(os.path.join(out_dir, name), "wb") as f:
            f.write(data)
    print("%d seeds in %s" % (len(seeds), out_dir))


if __name__ == "__main__":
    main()
