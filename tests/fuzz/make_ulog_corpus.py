#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes the seed corpus of fuzz_ulog (tests/fuzz/corpus/ulog/): small ULogs built here
from the format's documentation, each exercising one part of the decoder (docs/fuzzing.md).
Usage: tests/fuzz/make_ulog_corpus.py [DIR]"""
import os
import struct
import sys

SYNC = bytes([0x2F, 0x73, 0x13, 0x20, 0x25, 0x0C, 0xBB, 0x12])
GYRO = b"vehicle_angular_velocity:uint64_t timestamp;uint64_t timestamp_sample;float[3] xyz;"


def msg(kind, payload):
    return struct.pack("<HB", len(payload), ord(kind)) + payload


def header():
    return b"ULog\x01\x12\x35\x01" + struct.pack("<Q", 1000)


def flags(incompat=0, appended=0):
    return msg("B", bytes(8) + bytes([incompat & 0xFF, incompat >> 8]) + bytes(6) + struct.pack("<3Q", appended, 0, 0))


def add(multi_id, msg_id, name):
    return msg("A", struct.pack("<BH", multi_id, msg_id) + name)


def data(msg_id, payload):
    return msg("D", struct.pack("<H", msg_id) + payload)


def gyro(msg_id, t_us, x, y, z):
    return data(msg_id, struct.pack("<QQ3f", t_us, t_us - 50, x, y, z))


def gyro_log(rows=4):
    out = header() + flags() + msg("F", GYRO) + add(0, 0, b"vehicle_angular_velocity")
    for k in range(rows):
        out += gyro(0, 1000 * (k + 1), 0.1 * k, -0.2, 1e-30)
    return out


def kinds():
    out = header() + flags()
    out += msg("F", b"a:uint64_t timestamp;int8_t i8;uint8_t u8;int16_t i16;uint16_t u16;int32_t i32;uint32_t u32;"
                    b"int64_t i64;double d;bool ok;char c;char[5] name;uint8_t[3] _padding0;s[2] s;")
    out += msg("F", b"s:float v;uint8_t[4] _padding0;")
    out += msg("I", b"\x0fchar[3] sys_namePX4")
    out += msg("P", b"\x0cint32_t PARAMx\x01\x00\x00\x00")
    out += add(0, 0, b"a") + add(1, 1, b"a")
    for msg_id in (0, 1):
        out += data(msg_id, struct.pack("<QbBhHiIqd??5s3sfIfI", 5 + msg_id, -1, 255, -3, 4, -5, 6, -7, 0.25, True,
                                         b"x", b"ab,\n\x00", b"pad", float("nan"), 0, float("inf"), 0))
    return out


def px4():
    out = header() + flags() + msg("F", GYRO)
    out += msg("F", b"vehicle_attitude:uint64_t timestamp;float[4] q;")
    out += msg("F", b"actuator_controls_0:uint64_t timestamp;uint64_t timestamp_sample;float[8] control;")
    out += msg("F", b"actuator_outputs:uint64_t timestamp;uint32_t noutputs;float[16] output;uint8_t[4] _padding0;")
    for i, name in enumerate((b"vehicle_angular_velocity", b"vehicle_attitude", b"actuator_controls_0",
                              b"actuator_outputs")):
        out += add(0, i, name)
    for k in range(3):
        t = 2000 + 1000 * k
        out += gyro(0, t, 0.5, 0.25, -1.0)
        out += data(1, struct.pack("<Q4f", t, 1.0, 0.0, 0.0, 0.0))
        out += data(2, struct.pack("<QQ8f", t, t, *([0.1] * 8)))
        out += data(3, struct.pack("<QI16f", t, 4, *([1500.0] * 16)))
    return out


def appended():
    body = msg("F", GYRO) + add(0, 0, b"vehicle_angular_velocity") + gyro(0, 1000, 1, 2, 3)
    cut = gyro(0, 2000, 4, 5, 6)[:9]
    offset = 16 + 43 + len(body) + len(cut)
    return header() + flags(1, offset) + body + cut + gyro(0, 3000, 7, 8, 9)


def counted():
    out = gyro_log(2)
    out += msg("O", struct.pack("<H", 20)) + msg("Z", b"future") + msg("L", b"6" + bytes(8) + b"text")
    out += msg("C", b"6\x01\x00" + bytes(8) + b"tagged") + msg("S", SYNC)
    out += data(0, bytes(10)) + data(7, bytes(28)) + gyro(0, 500, 0, 0, 0)
    out += msg("R", struct.pack("<H", 0)) + gyro(0, 9000, 0, 0, 0)
    return out


def corrupt(with_sync):
    out = gyro_log(2) + bytes(3) + b"\x07" * 5
    return out + (msg("S", SYNC) if with_sync else b"") + gyro(0, 8000, 1, 1, 1)


def narrow():
    out = header() + msg("F", b"n:uint16_t timestamp;float v;uint8_t[2] _padding0;") + add(0, 0, b"n")
    for t in (65000, 65535, 3, 70):
        out += data(0, struct.pack("<Hf", t, 1.5))
    out += msg("F", b"m:uint8_t timestamp;float v;") + add(0, 1, b"m")
    for t in (250, 255, 1):
        out += data(1, struct.pack("<Bf", t, 2.5))
    return out


SEEDS = {
    "gyro.ulg": gyro_log(),
    "kinds.ulg": kinds(),
    "px4_before_v1_13.ulg": px4(),
    "appended.ulg": appended(),
    "counted.ulg": counted(),
    "corrupt_sync.ulg": corrupt(True),
    "corrupt_end.ulg": corrupt(False),
    "cut.ulg": gyro_log()[:-7],
    "narrow_timestamps.ulg": narrow(),
    "error_incompat.ulg": header() + flags(0x0102),
    "error_short_add.ulg": gyro_log(1) + msg("A", b"\x00\x01"),
    "error_no_format.ulg": gyro_log(1) + add(0, 1, b"a"),
    "error_circular.ulg": header() + msg("F", b"a:uint64_t timestamp;a a;") + add(0, 0, b"a"),
    "error_magic.ulg": b"ULog\x01\x12\x36\x01" + bytes(8),
}


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "corpus", "ulog")
    os.makedirs(folder, exist_ok=True)
    for name, content in SEEDS.items():
        with open(os.path.join(folder, name), "wb") as f:
            f.write(content)
    print(f"{len(SEEDS)} seeds in {folder}")


if __name__ == "__main__":
    main()
