#!/usr/bin/env python3
"""Tests of the real-log tools on logs and runs built here:

- tools/log_excerpt.py cuts a ULog, a DataFlash log and a Betaflight blackbox log
  into valid logs (every message or frame whole, the definitions kept, the time
  window and byte budget kept) and refuses what it cannot cut, at its offset;
- tools/real_logs_report.py's verdict (the noise above 20 Hz from the two bands,
  the untunable's reason, a refused log);
- tools/real_logs.sh's discovery of logs (a PX4 topic set counted once, even
  when one set's prefix starts another's) and its exit status, with a stand-in
  ladrc_replay that writes a summary.
"""

import contextlib
import io
import os
import struct
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import log_excerpt as lx  # noqa: E402
import real_logs_report as rr  # noqa: E402


# ---------------------------------------------------------------- ULog builder


def ulog_msg(kind, payload):
    return struct.pack("<HB", len(payload), ord(kind)) + payload


def ulog_info(key, value):
    k = key.encode()
    return ulog_msg("I", bytes([len(k)]) + k + value)


def build_ulog(n_samples=100, period_us=10_000, appended=True):
    """Header, flag bits (appended flag set), two formats, info, a parameter;
    then subscriptions to two topics, their data interleaved, a logged text."""
    out = bytearray(lx.ULOG_MAGIC + b"\x01" + struct.pack("<Q", 0))
    flags = bytearray(40)
    if appended:
        flags[8] = lx.ULOG_INCOMPAT_APPENDED
        flags[16:24] = struct.pack("<Q", 123456)
    out += ulog_msg("B", bytes(flags))
    out += ulog_msg("F", b"gyro:uint64_t timestamp;float[3] xyz;")
    out += ulog_msg("F", b"cmd:uint64_t timestamp;float[3] xyz;")
    out += ulog_info("uint32_t ver_sw_release", struct.pack("<I", 0x010B02FF))
    out += ulog_msg("P", bytes([len(b"float MC_X")]) + b"float MC_X" + struct.pack("<f", 1.5))
    out += ulog_msg("A", struct.pack("<BH", 0, 0) + b"gyro")
    out += ulog_msg("A", struct.pack("<BH", 0, 1) + b"cmd")
    t0 = 1_000_000
    for k in range(n_samples):
        t = t0 + k * period_us
        out += ulog_msg("D", struct.pack("<HQfff", 0, t, k, 0, 0))
        out += ulog_msg("D", struct.pack("<HQfff", 1, t + 1, -k, 0, 0))
        if k == n_samples // 2:
            out += ulog_msg("L", bytes([6]) + struct.pack("<Q", t) + b"half way")
            out += ulog_msg("A", struct.pack("<BH", 1, 2) + b"gyro")  # a late subscription
    return bytes(out)


def ulog_walk(data):
    """(kind, payload) of every message; asserts the file ends on a message boundary."""
    msgs, pos = [], lx.ULOG_HEADER_BYTES
    while pos < len(data):
        size, kind = struct.unpack_from("<HB", data, pos)
        assert pos + 3 + size <= len(data), "a message runs past the end"
        msgs.append((chr(kind), data[pos + 3 : pos + 3 + size]))
        pos += 3 + size
    return msgs


# ---------------------------------------------------------------- DataFlash builder


def df_fmt(type_id, name, fmt, columns):
    length = 3 + sum(lx.DATAFLASH_TYPE_BYTES[c] for c in fmt)
    payload = struct.pack("<BB", type_id, length) + name.encode().ljust(4, b"\0")
    payload += fmt.encode().ljust(16, b"\0") + columns.encode().ljust(64, b"\0")
    return lx.DATAFLASH_HEAD + bytes([lx.DATAFLASH_FMT_ID]) + payload


def build_dataflash(n_samples=200, period_us=2_500):
    out = bytearray(df_fmt(lx.DATAFLASH_FMT_ID, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns"))
    out += df_fmt(130, "PARM", "QNf", "TimeUS,Name,Value")
    out += df_fmt(131, "GYR", "Qfff", "TimeUS,GyrX,GyrY,GyrZ")
    out += df_fmt(132, "MSG", "QZ", "TimeUS,Message")
    out += lx.DATAFLASH_HEAD + bytes([132]) + struct.pack("<Q", 1) + b"ArduCopter V4.5.7".ljust(64, b"\0")
    out += lx.DATAFLASH_HEAD + bytes([130]) + struct.pack("<Q", 2) + b"SCHED_LOOP_RATE".ljust(16, b"\0")
    out += struct.pack("<f", 400.0)
    for k in range(n_samples):
        out += lx.DATAFLASH_HEAD + bytes([131]) + struct.pack("<Qfff", 1_000_000 + k * period_us, k, 0, 0)
        if k == n_samples // 2:  # a parameter changed in flight: metadata, kept whatever the window
            out += lx.DATAFLASH_HEAD + bytes([130]) + struct.pack("<Q", 1_000_000 + k * period_us)
            out += b"ATC_RAT_RLL_P".ljust(16, b"\0") + struct.pack("<f", 0.135)
    return bytes(out)


# ---------------------------------------------------------------- blackbox builder


def uvb(v):
    out = bytearray()
    while v >= 0x80:
        out.append((v & 0x7F) | 0x80)
        v >>= 7
    out.append(v)
    return bytes(out)


def svb(v):
    """Zig-zag: 0, -1, 1, -2 ... as 0, 1, 2, 3 ..."""
    return uvb(v << 1 if v >= 0 else ((-v) << 1) - 1)


def tag8_8svb(values):
    present = 0
    body = bytearray()
    for i, v in enumerate(values):
        if v:
            present |= 1 << i
            body += svb(v)
    return bytes([present]) + bytes(body)


def tag2_3s32_wide(values):
    """Selector 3: each of three fields as 1-4 bytes, here 2 bytes each (tag 1)."""
    lead = (3 << 6) | (1 << 0) | (1 << 2) | (1 << 4)
    return bytes([lead]) + b"".join(struct.pack("<h", v) for v in values)


def tag8_4s16(values):
    """Field widths 0, 4-bit, 8-bit, 16-bit packed as nibbles, first field first."""
    nibbles, selector = [], 0
    for i, v in enumerate(values):
        if v == 0:
            kind = 0
        elif -8 <= v < 8:
            kind, nib = 1, [v & 0xF]
        elif -128 <= v < 128:
            kind, nib = 2, [(v >> 4) & 0xF, v & 0xF]
        else:
            kind, nib = 3, [(v >> 12) & 0xF, (v >> 8) & 0xF, (v >> 4) & 0xF, v & 0xF]
        selector |= kind << (2 * i)
        if kind:
            nibbles += nib
    if len(nibbles) % 2:
        nibbles.append(0)
    return bytes([selector]) + bytes((nibbles[i] << 4) | nibbles[i + 1] for i in range(0, len(nibbles), 2))


BB_HEADER = (
    "H Product:Blackbox flight data recorder by Nicholas Sherlock\n"
    "H Data version:2\n"
    "H Firmware revision:Betaflight 4.5.1 (test) STM32F7X2\n"
    "H looptime:125\nH pid_process_denom:2\nH I interval:32\nH P interval:1\n"
    "H Field I name:loopIteration,time,a,b,c,d,e,f,g,h,i,j,k,l\n"
    "H Field I encoding:1,1,0,0,0,0,0,0,0,0,0,0,0,0\n"
    "H Field P encoding:0,0,6,6,6,7,7,7,8,8,8,8,9,6\n"
    "H Field S name:flightModeFlags\nH Field S encoding:1\n"
)


def bb_log(n_frames=200, period_us=500, t0=5_000_000, end=True):
    out = bytearray(BB_HEADER.encode())
    for k in range(n_frames):
        if k % 32 == 0:
            out += b"I" + uvb(k) + uvb(t0 + k * period_us) + b"".join(svb(v) for v in range(-6, 6))
        else:
            out += b"P" + svb(1) + svb(period_us - 500) + tag8_8svb([k % 5, 0, -3])
            out += tag2_3s32_wide([k, -k, 300]) + tag8_4s16([0, 5, -100, 3000]) + svb(-(k % 3))
        if k == 50:
            out += b"S" + uvb(1)
            out += b"E" + bytes([30]) + uvb(1) + uvb(0)  # flight mode change
    if end:
        out += b"E" + bytes([lx.BB_EVENT_LOG_END]) + lx.BB_LOG_END_TEXT
    return bytes(out)


# ---------------------------------------------------------------- tests


class UlogCut(unittest.TestCase):
    def test_keeps_definitions_subscriptions_and_a_time_window(self):
        data = build_ulog()
        cut = lx.ulog_cut("t.ulg", data, start_s=0.2, max_bytes=10**9)
        msgs = ulog_walk(cut)
        kinds = "".join(k for k, _ in msgs)
        self.assertTrue(cut.startswith(lx.ULOG_MAGIC))
        self.assertEqual(kinds.count("F"), 2)
        self.assertEqual(kinds.count("A"), 3, "every subscription kept, the late one too")
        self.assertIn("P", kinds)
        times = [struct.unpack_from("<Q", p, 2)[0] for k, p in msgs if k == "D"]
        self.assertEqual(min(times), 1_000_000 + 200_000, "data from --start-s on, no earlier")
        self.assertEqual(len(times), 2 * 80)
        flags = next(p for k, p in msgs if k == "B")
        self.assertEqual(flags[8] & lx.ULOG_INCOMPAT_APPENDED, 0, "appended flag cleared")
        self.assertEqual(flags[16:40], bytes(24), "appended offsets cleared")

    def test_budget_and_topics(self):
        data = build_ulog()
        cut = lx.ulog_cut("t.ulg", data, 0.0, max_bytes=2000, topics={"cmd"})
        self.assertLessEqual(len(cut), 2000)
        msgs = ulog_walk(cut)
        ids = {struct.unpack_from("<H", p)[0] for k, p in msgs if k == "D"}
        self.assertEqual(ids, {1}, "only the cmd topic's data")

    def test_info_reads_the_release(self):
        self.assertIn("v1.11.2", lx.ulog_info("t.ulg", build_ulog()))

    def test_a_log_cut_mid_message_ends_at_the_last_whole_one(self):
        data = build_ulog()
        cut = lx.ulog_cut("t.ulg", data[:-5], 0.0, 10**9)
        ulog_walk(cut)  # asserts whole messages


class DataflashCut(unittest.TestCase):
    def test_keeps_metadata_and_a_window(self):
        data = build_dataflash()
        cut = lx.dataflash_cut("t.bin", data, start_s=0.25, max_bytes=10**9)
        names = [n for _, n, _, _, _ in lx.dataflash_messages("t.bin", cut)]
        self.assertEqual(names[:4], ["FMT"] * 4)
        self.assertEqual(names.count("PARM"), 2)
        self.assertIn("MSG", names)
        times = [lx.dataflash_time_us(p, fc) for _, n, p, fc, _ in lx.dataflash_messages("t.bin", cut) if n == "GYR"]
        self.assertEqual(min(times), 1_000_000 + 100 * 2_500)
        self.assertEqual(len(times), 100)

    def test_refuses_a_message_without_its_format_at_its_offset(self):
        data = build_dataflash()
        bad = data + lx.DATAFLASH_HEAD + bytes([200]) + bytes(8)
        with self.assertRaises(lx.LogError) as e:
            lx.dataflash_cut("t.bin", bad, 0.0, 10**9)
        self.assertIn(f"t.bin: offset {len(data)}: message type 200 has no FMT", str(e.exception))

    def test_info(self):
        info = lx.dataflash_info("t.bin", build_dataflash())
        self.assertIn("ArduCopter V4.5.7", info)
        self.assertIn("SCHED_LOOP_RATE=400", info)
        self.assertIn("GYR: 200 messages, 400.0 Hz", info)


class BlackboxCut(unittest.TestCase):
    def walk(self, data):
        header, first = lx.bb_header("t.bbl", data, 0, len(data))
        return header, list(lx.bb_frames("t.bbl", data, first, len(data), header))

    def test_every_frame_of_the_built_log_is_walked(self):
        data = bb_log()
        _, frames = self.walk(data)
        markers = "".join(m for _, m, _, _ in frames)
        self.assertEqual(markers.count("I"), 7)
        self.assertEqual(markers.count("P"), 193)
        self.assertEqual(markers.count("S") + markers.count("E"), 3)
        self.assertEqual(frames[-1][2], len(data), "the walk ends at the log-end event")

    def test_cut_starts_at_an_intra_frame_and_ends_after_a_whole_frame(self):
        data = bb_log() + bb_log(t0=9_000_000)  # two logs in one file
        for index in (0, 1):
            cut = lx.bb_cut("t.bbl", data, start_s=0.02, max_bytes=3000, index=index)
            self.assertLessEqual(len(cut), 3000)
            header, frames = self.walk(cut)
            self.assertEqual(header["Firmware revision"], "Betaflight 4.5.1 (test) STM32F7X2")
            self.assertEqual(frames[0][1], "I")
            t0 = (5_000_000, 9_000_000)[index]
            self.assertEqual(frames[0][3], t0 + 64 * 500, "the first intra frame at or after 0.02 s")
            self.assertEqual(frames[-1][2], len(cut), "no partial frame at the end")

    def test_a_corrupt_frame_ends_the_walk_before_it(self):
        data = bytearray(bb_log())
        _, whole = self.walk(bytes(data))
        corrupt_at = whole[100][0]
        data[corrupt_at] = ord("Z")
        _, frames = self.walk(bytes(data))
        # the frame before the corrupt byte is not trusted either: no marker follows it
        self.assertEqual(frames, whole[:99])

    def test_refuses_a_log_index_the_file_lacks(self):
        with self.assertRaises(lx.LogError) as e:
            lx.bb_cut("t.bbl", bb_log(), 0.0, 10**6, index=3)
        self.assertIn("log index 3 asked, the file holds 1 logs", str(e.exception))


SUMMARY_HEADER = (
    "source,axis,ticks,command_rms,command_std,noise_0_20hz,noise_20_100hz,noise_above_100hz,"
    "difference_rms,estimate_mean_rad_s2,estimate_std_rad_s2,fault_ticks,faults\n"
)


def summary_row(source, axis, mid, high):
    return f"{source},{axis},1000,0.1,0.1,0.01,{mid},{high},nan,nan,nan,0,0\n"


class Verdict(unittest.TestCase):
    def run_report(self, summary, status=0, stderr=""):
        with tempfile.TemporaryDirectory() as d:
            os.makedirs(os.path.join(d, "replay", "x"))
            if summary is not None:
                with open(os.path.join(d, "replay", "x", "replay_summary.csv"), "w") as f:
                    f.write(SUMMARY_HEADER + summary)
            for name, text in (("out", ""), ("err", stderr)):
                with open(os.path.join(d, name), "w") as f:
                    f.write(text)
            printed = io.StringIO()
            with contextlib.redirect_stdout(printed):
                return rr.main(["--log", "x.csv", "--status", str(status), "--out", d, "--stdout",
                                os.path.join(d, "out"), "--stderr", os.path.join(d, "err"), "--seconds", "1"])

    def rows(self, log=(0.003, 0.004), ladrc=(0.003, 0.004), hp=(0.01, 0.01)):
        s = ""
        for axis in rr.AXES:
            s += summary_row("LOG", axis, *log) + summary_row("LADRC", axis, *ladrc)
            s += summary_row("HP-MLADRC", axis, *hp) + summary_row("PID", axis, 1e-6, 1e-6)
        return s

    def test_the_quietest_of_the_family_at_or_below_the_log_passes(self):
        self.assertEqual(self.run_report(self.rows()), 0)

    def test_the_bands_add_in_power(self):
        # log sqrt(3^2+4^2) = 5e-3; LADRC 5.1e-3 from its bands: louder
        self.assertEqual(self.run_report(self.rows(ladrc=(0.0051, 0.0))), 1)
        self.assertEqual(self.run_report(self.rows(ladrc=(0.0049, 0.0))), 0)
        self.assertAlmostEqual(rr.noise_above_20hz({"noise_20_100hz": "3", "noise_above_100hz": "4"})[0], 5.0)
        self.assertEqual(rr.noise_above_20hz({"noise_above_20hz": "2", "noise_20_100hz": "3",
                                              "noise_above_100hz": "4"})[0], 2.0)

    def test_a_controller_outside_the_family_does_not_count(self):
        self.assertEqual(self.run_report(self.rows(ladrc=(1, 1), hp=(1, 1))), 1)

    def test_exit_status_and_refusals_fail(self):
        self.assertEqual(self.run_report(self.rows(), status=1), 1)
        self.assertEqual(self.run_report(None, status=2, stderr="x.csv:1:1: no column 'gyroADC[0]'\n"), 1)

    def test_status_one_is_explained(self):
        rows = {"LOG": {"roll": {"fault_ticks": "0"}}, "LADRC": {"roll": {"fault_ticks": "12"}},
                "PID": {"roll": {"fault_ticks": "0"}}}
        out = "warning: roll: b0's interval is wider than +-10 %\nwarning: yaw: R^2 < 0.5\n"
        self.assertEqual(rr.status_causes(out, rows), "2 identification warnings (roll, yaw); LADRC faulted (12 ticks)")
        self.assertEqual(rr.timings("x: 5 rows, identified in 1.31 s (4 passes)\n"
                                    "replayed 17022 ticks (17.02 s of flight) with 6 controllers in 0.79 s: 22x real time\n"),
                         ", identified in 1.31 s, replayed in 0.79 s (22x real time)")

    def test_reasons_from_the_status_column_and_stdout(self):
        status_rows = "".join("INDI," + a + ",untunable" * 12 + ',"untunable: INDI does not start: at 47 Hz"\n'
                              for a in rr.AXES)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "s.csv")
            with open(path, "w") as f:
                f.write(SUMMARY_HEADER.rstrip("\n") + ",noise_above_20hz,status\n" + status_rows)
            _, untunable, reasons = rr.read_summary(path)
        self.assertEqual((untunable, reasons), (["INDI"], {"INDI": "INDI does not start: at 47 Hz"}))
        self.assertEqual(rr.untunable_reasons("untunable LP-MLADRC, not replayed: it refuses 47 Hz\n", ["LP-MLADRC"]),
                         {"LP-MLADRC": "it refuses 47 Hz"})

    def test_noise_not_measured_fails(self):
        self.assertEqual(self.run_report(self.rows(log=("nan", "nan"))), 1)

    def test_untunable_needs_its_reason(self):
        rows = self.rows() + "".join("INDI," + a + ",untunable" * 11 + "\n" for a in rr.AXES)
        self.assertEqual(self.run_report(rows, stderr=""), 1)
        reason = "replay/x/airframe.ini:40:1: tune = margins: INDI is untunable: the rate is not logged\n"
        warning = "replay/x/airframe.ini:41:1: warning: tune = margins: LADRC missed its targets\n"
        self.assertEqual(self.run_report(rows, stderr=warning + reason), 0)
        self.assertEqual(rr.untunable_reasons(warning + reason, ["INDI", "LADRC"]),
                         {"INDI": "tune = margins: INDI is untunable: the rate is not logged"})


FAKE_REPLAY = """#!/usr/bin/env bash
# stands in for ladrc_replay: writes a summary whose LADRC is as loud as $FAKE_FACTOR x the log
log=$1
name=$(basename "$log"); name=${name%.*}
mkdir -p "replay/$name"
echo "$log" >> "$FAKE_CALLS"
[[ "$log" == *refused* ]] && { echo "$log:1:1: refused" >&2; exit 2; }
{
  echo "source,axis,ticks,command_rms,command_std,noise_0_20hz,noise_20_100hz,noise_above_100hz,difference_rms,estimate_mean_rad_s2,estimate_std_rad_s2,fault_ticks,faults"
  for a in roll pitch yaw; do
    echo "LOG,$a,10,1,1,1,0.01,0,nan,nan,nan,0,0"
    echo "LADRC,$a,10,1,1,1,0.009,0,1,0,0,0,0"
  done
} > "replay/$name/replay_summary.csv"
"""


class Runner(unittest.TestCase):
    def run_script(self, files):
        with tempfile.TemporaryDirectory() as d:
            logs = os.path.join(d, "logs")
            for f in files:
                p = os.path.join(logs, f)
                os.makedirs(os.path.dirname(p), exist_ok=True)
                open(p, "w").close()
            fake = os.path.join(d, "fake_replay")
            with open(fake, "w") as f:
                f.write(FAKE_REPLAY)
            os.chmod(fake, 0o755)
            calls = os.path.join(d, "calls")
            env = dict(os.environ, FAKE_CALLS=calls)
            p = subprocess.run(["bash", os.path.join(HERE, "real_logs.sh"), logs, "--replay", fake],
                               capture_output=True, text=True, env=env)
            ran = open(calls).read().split() if os.path.exists(calls) else []
            return p.returncode, sorted(os.path.relpath(r, logs) for r in ran), p.stdout

    def test_discovery_counts_a_px4_set_once(self):
        files = ["bf/a.bbl", "bf/B.BFL", "bf/a.01.csv", "bf/a.01.gps.csv", "ap/c.bin", "px4/d.ulg",
                 "px4/s_vehicle_attitude_0.csv", "px4/s_vehicle_angular_velocity_0.csv",
                 "px4/s_log_small_vehicle_attitude_0.csv", "px4/s_log_small_actuator_controls_0_0.csv",
                 "README.md"]
        rc, ran, out = self.run_script(files)
        self.assertEqual(rc, 0, out)
        self.assertEqual(ran, sorted(["ap/c.bin", "bf/B.BFL", "bf/a.01.csv", "bf/a.bbl", "px4/d.ulg",
                                      "px4/s_log_small_vehicle_attitude_0.csv", "px4/s_vehicle_attitude_0.csv"]))
        self.assertIn("real_logs: 7 of 7 logs pass, 0 fail", out)

    def test_one_refused_log_fails_the_run(self):
        rc, ran, out = self.run_script(["a.bbl", "refused.ulg"])
        self.assertEqual(rc, 1)
        self.assertEqual(len(ran), 2, "every log runs, after a failure too")
        self.assertIn("refused: ", out)

    def test_no_log_is_bad_usage(self):
        rc, _, _ = self.run_script(["README.md"])
        self.assertEqual(rc, 2)


if __name__ == "__main__":
    unittest.main()
