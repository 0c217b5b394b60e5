#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes a synthetic Betaflight blackbox log of a given size, for measuring
the decoder's speed and memory (docs/flight-logs.md, Betaflight section).

The log is one flight at 2 kHz: Betaflight 4.x's main fields and encodings
(I frames every 32, P frames between: the time on a straight line, gyro and
motors in one TAG8_8SVB group, axisI in TAG2_3S32, setpoint in TAG8_4S16),
a slow frame, and the log's end. The P frames repeat a few patterns of
small residuals, so the values wander but stay in range; a flight-mode
event every 10,000 frames.

Usage: tools/bbl_synth.py OUT.bbl MEGABYTES
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import whole_file  # noqa: E402

FIELDS = ("loopIteration,time,axisP[0],axisP[1],axisP[2],axisI[0],axisI[1],axisI[2],axisD[0],axisD[1],"
          "axisF[0],axisF[1],axisF[2],rcCommand[0],rcCommand[1],rcCommand[2],rcCommand[3],setpoint[0],"
          "setpoint[1],setpoint[2],setpoint[3],vbatLatest,gyroADC[0],gyroADC[1],gyroADC[2],"
          "motor[0],motor[1],motor[2],motor[3]")
I_SIGNED = "0,0,1,1,1,1,1,1,1,1,1,1,1,1,1,1,0,1,1,1,1,0,1,1,1,0,0,0,0"
I_PRED = "0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,9,0,0,0,11,5,5,5"
I_ENC = "1,1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,1,0,0,0,0,3,0,0,0,1,0,0,0"
P_PRED = "6,2,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,3,3,3,1,1,1,1"
P_ENC = "9,0,0,0,0,7,7,7,0,0,0,0,0,8,8,8,8,8,8,8,8,6,6,6,6,6,6,6,6"
I_INTERVAL = 32
DT_US = 500


def uvb(u):
    u &= 0xFFFFFFFF
    out = bytearray()
    while u >= 0x80:
        out.append((u & 0x7F) | 0x80)
        u >>= 7
    out.append(u)
    return bytes(out)


def svb(v):
    return uvb((v << 1) ^ (v >> 31))


def header():
    lines = [
        "Product:Blackbox flight data recorder by Nicholas Sherlock", "Data version:2",
        f"I interval:{I_INTERVAL}", "P interval:1/1", "Firmware type:Cleanflight",
        "Firmware revision:Betaflight 4.4.2 (synthetic) SYNTH", "minthrottle:1070", "motorOutput:158,2047",
        "vbatref:1650", "gyro_scale:0x3f800000", f"Field I name:{FIELDS}", f"Field I signed:{I_SIGNED}",
        f"Field I predictor:{I_PRED}", f"Field I encoding:{I_ENC}", f"Field P predictor:{P_PRED}",
        f"Field P encoding:{P_ENC}", "Field S name:flightModeFlags,stateFlags,failsafePhase",
        "Field S signed:0,0,0", "Field S predictor:0,0,0", "Field S encoding:1,1,1",
    ]
    return "".join(f"H {line}\n" for line in lines).encode()


def intra(k):
    """An I frame: every field from constants; the same values each time."""
    out = bytearray(b"I")
    out += uvb(k) + uvb(1_000_000 + k * DT_US)
    out += b"".join(svb(v) for v in (10, -12, 3, 40, -35, 6, 18, -20, 30, -25, 4))  # axisP..axisF
    out += svb(5) + svb(-7) + svb(2) + uvb(1400)  # rcCommand
    out += svb(12) + svb(-9) + svb(4) + svb(400)  # setpoint
    out += uvb(30)  # vbat: NEG_14BIT of vbatref - vbat
    out += svb(15) + svb(-11) + svb(6)  # gyro
    out += uvb(700) + svb(12) + svb(-8) + svb(3)  # motors
    return bytes(out)


def inter(first_after_intra, j):
    """A P frame: the time's residual (a constant period), small residuals that sum to zero over 4 frames."""
    s = (1, -1, 2, -2)[j % 4]
    out = bytearray(b"P")
    out += svb(DT_US if first_after_intra else 0)
    out += svb(s) + svb(-s) + svb(0)  # axisP
    out += bytes([0x40 | (s & 0xF), ((-s & 0xF) << 4) | 1 if j % 2 else 0x0F])  # axisI: TAG2_3S32 4-bit
    out += svb(0) + svb(s) + svb(0) + svb(-s) + svb(0)  # axisD, axisF
    out += bytes([0x15, ((s & 0xF) << 4) | (-s & 0xF), (s & 0xF) << 4])  # rcCommand: TAG8_4S16, 3 nibbles
    out += bytes([0x00])  # setpoint: all zero
    out += bytes([0b10011011]) + svb(s) + svb(-s) + svb(s) + svb(-s) + svb(s)  # vbat, gyro, motors: TAG8_8SVB
    return bytes(out)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    path, target = sys.argv[1], int(float(sys.argv[2]) * 1e6)
    with whole_file(path, "wb") as f:  # an interrupted run leaves no truncated log behind
        f.write(header())
        written, k = 0, 0
        block = []
        while written < target:
            frame = intra(k) if k % I_INTERVAL == 0 else inter(k % I_INTERVAL == 1, k)
            if k == 1:
                frame += b"S" + uvb(1) + uvb(0) + uvb(0)
            if k % 10000 == 5000:
                frame += b"E\x1e" + uvb(1) + uvb(0)  # a flight mode change
            block.append(frame)
            written += len(frame)
            k += 1
            if len(block) >= 100_000:
                f.write(b"".join(block))
                block = []
        f.write(b"".join(block))
        f.write(b"E\xffEnd of log\x00")


if __name__ == "__main__":
    main()
