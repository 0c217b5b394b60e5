#!/usr/bin/env python3
"""Cut a short excerpt out of a flight log, keeping it a valid log of its format.

    log_excerpt.py info LOG                  what the log is: firmware, rates, duration
    log_excerpt.py cut LOG OUT [--start-s S] [--max-bytes N] [--log-index I] [--topics A,B]

Formats (told by their magic bytes, not by the file name):
  ULog (PX4, .ulg): the header and the definitions section (formats, info,
      parameters) are kept whole; in the data section every 'A' (add logged
      message), info, parameter and remove message is kept, and the data and
      log-text messages from --start-s (seconds of log time) until the byte
      budget is spent; with --topics, only those topics' data. The
      appended-data flag and offsets are cleared: what was appended lies past
      the cut.
  DataFlash (ArduPilot, .bin): every format/unit/multiplier/parameter/message
      /version message (FMT, FMTU, UNIT, MULT, PARM, MSG, VER and the like)
      is kept; the other messages (with --topics, only those named) from
      --start-s (TimeUS) until the budget.
  Betaflight blackbox (.bbl, .bfl, .txt): one log of the file (--log-index,
      0 the first): its header lines, then whole frames from the first intra
      ('I') frame at or after --start-s until the budget, ending after a
      complete frame. Frames are walked by their field encodings only (no
      values are predicted), so the cut never falls inside a frame.

Standard library only. Errors name the file and the byte offset.
"""

import argparse
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import refuse_inputs, write_whole  # noqa: E402

ULOG_MAGIC = b"ULog\x01\x12\x35"
DATAFLASH_HEAD = b"\xa3\x95"
DATAFLASH_FMT_ID = 128
BLACKBOX_MAGIC = b"H Product:Blackbox flight data recorder"


class LogError(Exception):
    """A log that cannot be cut: the message is 'file: offset N: what'."""


def fail(path, offset, message):
    raise LogError(f"{path}: offset {offset}: {message}")


def sniff(data):
    if data.startswith(ULOG_MAGIC):
        return "ulog"
    if data.startswith(BLACKBOX_MAGIC):
        return "blackbox"
    if data[:2] == DATAFLASH_HEAD and len(data) > 2 and data[2] == DATAFLASH_FMT_ID:
        return "dataflash"
    return None


# ---------------------------------------------------------------- ULog

ULOG_HEADER_BYTES = 16
ULOG_MSG_HEADER_BYTES = 3  # uint16 size, uint8 type
ULOG_INCOMPAT_APPENDED = 0x01
# messages of the data section kept whatever the budget: they are small and a
# reader needs them to make sense of the data it is given
ULOG_ALWAYS_KEPT = b"AIMPQRBF"
ULOG_TIMED = b"DLC"  # data, logged text, tagged logged text: cut by time and budget


def ulog_messages(path, data):
    """Yield (offset, type byte, payload) of every message after the header."""
    pos = ULOG_HEADER_BYTES
    while pos + ULOG_MSG_HEADER_BYTES <= len(data):
        size, kind = struct.unpack_from("<HB", data, pos)
        end = pos + ULOG_MSG_HEADER_BYTES + size
        if end > len(data):
            return  # a log cut mid-message (logger stopped): ends here
        yield pos, kind, data[pos + ULOG_MSG_HEADER_BYTES : end]
        pos = end


def ulog_timestamp_us(kind, payload):
    """Log time of a timed message: data messages start with uint16 msg_id then
    the topic's uint64 timestamp; 'L' has uint8 level then uint64 timestamp;
    'C' uint8 level, uint16 tag, uint64 timestamp."""
    if kind == ord("D") and len(payload) >= 10:
        return struct.unpack_from("<Q", payload, 2)[0]
    if kind == ord("L") and len(payload) >= 9:
        return struct.unpack_from("<Q", payload, 1)[0]
    if kind == ord("C") and len(payload) >= 11:
        return struct.unpack_from("<Q", payload, 3)[0]
    return None


def ulog_info_value(payload):
    """An 'I' message: uint8 key length, key 'type name', value bytes."""
    key_len = payload[0]
    key = payload[1 : 1 + key_len].decode("ascii", "replace")
    value = payload[1 + key_len :]
    typ, _, name = key.partition(" ")
    if typ.startswith("char["):
        return name, value.decode("ascii", "replace").rstrip("\x00")
    fmt = {"uint32_t": "<I", "int32_t": "<i", "uint64_t": "<Q", "int64_t": "<q",
           "uint8_t": "<B", "int8_t": "<b", "uint16_t": "<H", "int16_t": "<h",
           "float": "<f", "double": "<d", "bool": "<?"}.get(typ)
    if fmt and len(value) >= struct.calcsize(fmt):
        return name, struct.unpack_from(fmt, value)[0]
    return name, value.hex()


def ulog_release(value):
    """ver_sw_release 0xAABBCCTT: major, minor, patch, type (255 release)."""
    if not isinstance(value, int):
        return str(value)
    major, minor, patch, kind = (value >> 24) & 255, (value >> 16) & 255, (value >> 8) & 255, value & 255
    kinds = {0: "dev", 64: "alpha", 128: "beta", 192: "rc", 255: ""}
    suffix = kinds.get(kind, f"type{kind}")
    return f"v{major}.{minor}.{patch}" + (f" {suffix}" if suffix else "")


def ulog_info(path, data):
    info, subscriptions, counts, first, last = {}, {}, {}, {}, {}
    t_min, t_max = None, None
    for _, kind, payload in ulog_messages(path, data):
        if kind == ord("I"):
            name, value = ulog_info_value(payload)
            info[name] = value
        elif kind == ord("A"):
            multi_id, msg_id = struct.unpack_from("<BH", payload)
            name = payload[3:].decode("ascii", "replace")
            subscriptions[msg_id] = f"{name}" + (f"[{multi_id}]" if multi_id else "")
        elif kind == ord("D"):
            msg_id = struct.unpack_from("<H", payload)[0]
            t = ulog_timestamp_us(kind, payload)
            counts[msg_id] = counts.get(msg_id, 0) + 1
            first.setdefault(msg_id, t)
            last[msg_id] = t
            if t:
                t_min = t if t_min is None else min(t_min, t)
                t_max = t if t_max is None else max(t_max, t)
    lines = [
        "format: ULog",
        f"firmware: PX4 {ulog_release(info.get('ver_sw_release'))} (ver_sw {info.get('ver_sw', '?')}, "
        f"branch {info.get('ver_sw_branch', '?')})",
        f"hardware: {info.get('ver_hw', '?')}  vehicle: {info.get('sys_name', '?')} "
        f"airframe {info.get('sys_autostart_id', '?')}",
        f"duration: {((t_max or 0) - (t_min or 0)) / 1e6:.1f} s of data",
    ]
    for msg_id in sorted(counts, key=lambda m: subscriptions.get(m, "")):
        name = subscriptions.get(msg_id, f"id{msg_id}")
        span = (last[msg_id] - first[msg_id]) / 1e6 if counts[msg_id] > 1 else 0.0
        rate = (counts[msg_id] - 1) / span if span > 0 else 0.0
        lines.append(f"  {name}: {counts[msg_id]} messages, {rate:.1f} Hz")
    return "\n".join(lines)


def ulog_cut(path, data, start_s, max_bytes, topics=None):
    header = bytearray(data[:ULOG_HEADER_BYTES])
    kept_ids = set()  # msg_ids subscribed to a topic in `topics`
    out = [header]
    size = len(header)
    t_first = None
    in_data_section = False
    for offset, kind, payload in ulog_messages(path, data):
        raw = bytearray(data[offset : offset + ULOG_MSG_HEADER_BYTES + len(payload)])
        if kind == ord("B"):
            # flag bits: compat[8], incompat[8], appended offsets uint64[3]
            if len(payload) >= 40:
                raw[ULOG_MSG_HEADER_BYTES + 8] &= ~ULOG_INCOMPAT_APPENDED & 0xFF
                raw[ULOG_MSG_HEADER_BYTES + 16 : ULOG_MSG_HEADER_BYTES + 40] = bytes(24)
        if kind == ord("A"):
            in_data_section = True
            multi_id, msg_id = struct.unpack_from("<BH", payload)
            if topics is None or payload[3:].decode("ascii", "replace") in topics:
                kept_ids.add(msg_id)
        if not in_data_section or kind in ULOG_ALWAYS_KEPT:
            out.append(raw)
            size += len(raw)
            continue
        if kind not in ULOG_TIMED:
            continue  # sync and dropout markers: meaningless once messages are left out
        t = ulog_timestamp_us(kind, payload)
        if t is None:
            continue
        if kind == ord("D") and t_first is None and t > 0:
            t_first = t
        if t_first is None or t < t_first + start_s * 1e6:
            continue
        if kind == ord("D") and struct.unpack_from("<H", payload)[0] not in kept_ids:
            continue
        if size + len(raw) > max_bytes:
            break
        out.append(raw)
        size += len(raw)
    return b"".join(out)


# ---------------------------------------------------------------- DataFlash

DATAFLASH_TYPE_BYTES = {
    "a": 64, "b": 1, "B": 1, "h": 2, "H": 2, "i": 4, "I": 4, "f": 4, "d": 8,
    "n": 4, "N": 16, "Z": 64, "c": 2, "C": 2, "e": 4, "E": 4, "L": 4, "M": 1,
    "q": 8, "Q": 8,
}
DATAFLASH_FMT_BYTES = 89  # head 3, type 1, length 1, name 4, format 16, columns 64
# messages that describe the log rather than the flight: kept whatever the budget
DATAFLASH_METADATA = {"FMT", "FMTU", "UNIT", "MULT", "PARM", "MSG", "VER", "FILE"}


def dataflash_messages(path, data):
    """Yield (offset, name, payload, fields) of every message, learning the
    formats from the FMT messages as they come."""
    formats = {DATAFLASH_FMT_ID: ("FMT", DATAFLASH_FMT_BYTES, "BBnNZ", ["Type", "Length", "Name", "Format", "Columns"])}
    pos = 0
    while pos + 3 <= len(data):
        if data[pos : pos + 2] != DATAFLASH_HEAD:
            fail(path, pos, f"expected the message head A3 95, found {data[pos:pos + 2].hex()}")
        msg_id = data[pos + 2]
        if msg_id not in formats:
            fail(path, pos, f"message type {msg_id} has no FMT before it")
        name, length, fmt, columns = formats[msg_id]
        if pos + length > len(data):
            return  # the last message is cut (the logger stopped): ends here
        payload = data[pos + 3 : pos + length]
        if msg_id == DATAFLASH_FMT_ID:
            typ, ln = payload[0], payload[1]
            fname = payload[2:6].rstrip(b"\x00").decode("ascii", "replace")
            ffmt = payload[6:22].rstrip(b"\x00").decode("ascii", "replace")
            fcols = payload[22:86].rstrip(b"\x00").decode("ascii", "replace").split(",")
            if any(c not in DATAFLASH_TYPE_BYTES for c in ffmt):
                fail(path, pos, f"FMT of {fname}: format '{ffmt}' has a type letter this cutter does not know")
            # the message length is the FMT's: some firmware wrote formats that do not
            # add up to it (Copter 3.3's EKF5), and its messages are that long on disk
            need = 3 + sum(DATAFLASH_TYPE_BYTES[c] for c in ffmt)
            if need > ln:
                ffmt = ""  # fields cannot be read; the message is still skipped whole
            formats[typ] = (fname, ln, ffmt, fcols)
        yield pos, name, payload, (fmt, columns), length
        pos += length


def dataflash_time_us(payload, fmt_cols):
    fmt, columns = fmt_cols
    if columns and columns[0] == "TimeUS" and fmt[:1] == "Q":
        return struct.unpack_from("<Q", payload)[0]
    if columns and columns[0] in ("TimeMS", "TimeUS") and fmt[:1] in "IiL":
        scale = 1000 if columns[0] == "TimeMS" else 1
        return struct.unpack_from("<I", payload)[0] * scale
    return None


DATAFLASH_STRUCT = {"b": "b", "B": "B", "h": "h", "H": "H", "i": "i", "I": "I", "f": "f", "d": "d",
                    "c": "h", "C": "H", "e": "i", "E": "I", "L": "i", "M": "B", "q": "q", "Q": "Q"}


def dataflash_fields(payload, fmt_cols):
    """A message's fields by column name (text fields as str, arrays skipped)."""
    fmt, columns = fmt_cols
    row, pos = {}, 0
    for code, column in zip(fmt, columns):
        size = DATAFLASH_TYPE_BYTES[code]
        if code in "nNZ":
            row[column] = payload[pos : pos + size].rstrip(b"\x00").decode("ascii", "replace")
        elif code in DATAFLASH_STRUCT:
            row[column] = struct.unpack_from("<" + DATAFLASH_STRUCT[code], payload, pos)[0]
        pos += size
    return row


def dataflash_info(path, data):
    counts, first, last, msgs, params = {}, {}, {}, [], {}
    t_min = t_max = None
    for _, name, payload, fmt_cols, _ in dataflash_messages(path, data):
        t = dataflash_time_us(payload, fmt_cols)
        if name == "MSG":
            text = payload[-64:].rstrip(b"\x00").decode("ascii", "replace")
            if len(msgs) < 6:
                msgs.append(text)
        if name == "PARM":
            row = dataflash_fields(payload, fmt_cols)
            if "Name" in row and "Value" in row:
                params[row["Name"]] = row["Value"]
        if name == "VER" and len(msgs) < 6:
            msgs.append("VER " + payload[-64:].rstrip(b"\x00").decode("ascii", "replace"))
        counts[name] = counts.get(name, 0) + 1
        if t is not None:
            first.setdefault(name, t)
            last[name] = t
            t_min = t if t_min is None else min(t_min, t)
            t_max = t if t_max is None else max(t_max, t)
    lines = ["format: DataFlash", "messages: " + " | ".join(msgs),
             f"duration: {((t_max or 0) - (t_min or 0)) / 1e6:.1f} s",
             "params: " + ", ".join(f"{k}={params[k]:g}" for k in
                                   ("SCHED_LOOP_RATE", "INS_GYRO_FILTER", "LOG_BITMASK", "FRAME_CLASS", "INS_FAST_SAMPLE")
                                   if k in params)]
    for name in sorted(counts):
        if name in first and counts[name] > 1 and last[name] > first[name]:
            rate = (counts[name] - 1) / ((last[name] - first[name]) / 1e6)
            lines.append(f"  {name}: {counts[name]} messages, {rate:.1f} Hz")
    return "\n".join(lines)


def dataflash_cut(path, data, start_s, max_bytes, topics=None):
    out, size, t_first = [], 0, None
    for offset, name, payload, fmt_cols, length in dataflash_messages(path, data):
        raw = data[offset : offset + length]
        if name in DATAFLASH_METADATA:
            out.append(raw)
            size += length
            continue
        t = dataflash_time_us(payload, fmt_cols)
        if t is None:
            continue
        if t_first is None and t > 0:
            t_first = t
        if t_first is None or t < t_first + start_s * 1e6:
            continue
        if topics is not None and name not in topics:
            continue
        if size + length > max_bytes:
            break
        out.append(raw)
        size += length
    return b"".join(out)


# ---------------------------------------------------------------- Betaflight blackbox

BB_SIGNED_VB, BB_UNSIGNED_VB, BB_NEG_14BIT = 0, 1, 3
BB_TAG8_8SVB, BB_TAG2_3S32, BB_TAG8_4S16, BB_NULL = 6, 7, 8, 9
BB_FRAME_MARKERS = b"IPSGHE"
BB_EVENT_LOG_END = 255
BB_LOG_END_TEXT = b"End of log\x00"


def bb_split_logs(data):
    """Start offsets of every log in the file (each begins with the product line)."""
    starts, pos = [], 0
    while True:
        pos = data.find(BLACKBOX_MAGIC, pos)
        if pos < 0:
            return starts
        starts.append(pos)
        pos += len(BLACKBOX_MAGIC)


def bb_header(path, data, start, end):
    """Header lines 'H name:value' from start; returns (dict, offset of first frame)."""
    fields, pos = {}, start
    while pos < end and data[pos : pos + 2] == b"H ":
        eol = data.find(b"\n", pos, end)
        if eol < 0:
            fail(path, pos, "header line without its end of line")
        line = data[pos + 2 : eol].decode("ascii", "replace")
        name, _, value = line.partition(":")
        fields[name] = value
        pos = eol + 1
    return fields, pos


def bb_encodings(path, header, frame):
    value = header.get(f"Field {frame} encoding")
    if value is None:
        return None
    try:
        return [int(v) for v in value.split(",")]
    except ValueError:
        fail(path, 0, f"header 'Field {frame} encoding' is not a list of numbers: {value}")


def bb_read_uvb(data, pos, end):
    """Unsigned variable-length integer, 7 bits a byte, at most 5 bytes."""
    value = shift = 0
    for i in range(5):
        if pos + i >= end:
            raise IndexError
        b = data[pos + i]
        value |= (b & 0x7F) << shift
        if not b & 0x80:
            return value, pos + i + 1
        shift += 7
    raise ValueError("variable-length integer longer than 5 bytes")


def bb_skip_fields(data, pos, end, encodings):
    """Offset after one frame's fields, walked by encoding alone."""
    i, n = 0, len(encodings)
    while i < n:
        enc = encodings[i]
        if enc in (BB_SIGNED_VB, BB_UNSIGNED_VB, BB_NEG_14BIT):
            _, pos = bb_read_uvb(data, pos, end)
            i += 1
        elif enc == BB_NULL:
            i += 1
        elif enc == BB_TAG8_8SVB:
            group = 1
            while group < 8 and i + group < n and encodings[i + group] == BB_TAG8_8SVB:
                group += 1
            if group == 1:
                _, pos = bb_read_uvb(data, pos, end)  # a lone field is a plain signed VB
            else:
                if pos >= end:
                    raise IndexError
                present = data[pos]
                pos += 1
                for bit in range(group):
                    if present & (1 << bit):
                        _, pos = bb_read_uvb(data, pos, end)
            i += group
        elif enc == BB_TAG2_3S32:
            if pos >= end:
                raise IndexError
            lead = data[pos]
            selector = lead >> 6
            if selector == 0:  # three 2-bit fields in the lead byte
                pos += 1
            elif selector == 1:  # three 4-bit fields: lead's low nibble and one more byte
                pos += 2
            elif selector == 2:  # three 6-bit fields: lead's low 6 bits and two more bytes
                pos += 3
            else:  # each field 1, 2, 3 or 4 bytes, told by 2-bit tags in the lead
                pos += 1
                for k in range(3):
                    pos += ((lead >> (2 * k)) & 3) + 1
            i += 3
        elif enc == BB_TAG8_4S16:
            if pos >= end:
                raise IndexError
            selector = data[pos]
            nibbles = sum((0, 1, 2, 4)[(selector >> (2 * k)) & 3] for k in range(4))
            pos += 1 + (nibbles + 1) // 2
            i += 4
        else:
            raise ValueError(f"field encoding {enc} is not one Betaflight writes")
        if pos > end:
            raise IndexError
    return pos


def bb_skip_event(data, pos, end):
    """Offset after an event frame's payload (pos at the event type)."""
    kind = data[pos]
    pos += 1
    if kind == 0:  # sync beep: time
        _, pos = bb_read_uvb(data, pos, end)
    elif kind == 13:  # in-flight adjustment: function byte, then a float or a signed VB
        func = data[pos]
        pos += 1
        if func & 0x80:
            pos += 4
        else:
            _, pos = bb_read_uvb(data, pos, end)
    elif kind == 14:  # logging resumed: iteration, time
        _, pos = bb_read_uvb(data, pos, end)
        _, pos = bb_read_uvb(data, pos, end)
    elif kind == 15:  # disarm: reason
        _, pos = bb_read_uvb(data, pos, end)
    elif kind == 30:  # flight mode: new flags, old flags
        _, pos = bb_read_uvb(data, pos, end)
        _, pos = bb_read_uvb(data, pos, end)
    elif kind == 40:  # IMU failure: error code
        _, pos = bb_read_uvb(data, pos, end)
    elif kind == BB_EVENT_LOG_END:
        if data[pos : pos + len(BB_LOG_END_TEXT)] != BB_LOG_END_TEXT:
            raise ValueError("log-end event without its text")
        pos += len(BB_LOG_END_TEXT)
    else:
        raise ValueError(f"event type {kind} is not one this cutter knows")
    if pos > end:
        raise IndexError
    return pos, kind


def bb_frames(path, data, first, end, header):
    """Yield (offset, marker, end offset, I-frame time in us or None); stops at
    the log's end event, the end of the data, or a frame that does not parse
    (a corrupt stretch: the excerpt ends before it)."""
    enc = {m: bb_encodings(path, header, m) for m in "IPSGH"}
    if enc["I"] is None or enc["P"] is None:
        fail(path, first, "header has no 'Field I encoding' or 'Field P encoding'")
    names = header.get("Field I name", "").split(",")
    time_index = names.index("time") if "time" in names else None
    pos = first
    while pos < end:
        marker = chr(data[pos])
        try:
            if marker == "E":
                stop, kind = bb_skip_event(data, pos + 1, end)
                yield pos, marker, stop, None
                if kind == BB_EVENT_LOG_END:
                    return
                pos = stop
                continue
            if marker not in "IPSGH" or enc[marker] is None:
                return
            stop = bb_skip_fields(data, pos + 1, end, enc[marker])
            if stop < end and data[stop] not in BB_FRAME_MARKERS:
                return  # the next byte is no frame: this one was not what it seemed
            t = None
            if marker == "I" and time_index is not None:
                # an intra frame's first fields are unsigned VBs with no predictor
                q = pos + 1
                for _ in range(time_index + 1):
                    t, q = bb_read_uvb(data, q, end)
            yield pos, marker, stop, t
            pos = stop
        except (IndexError, ValueError):
            return


def bb_pick_log(path, data, index):
    starts = bb_split_logs(data)
    if not starts:
        fail(path, 0, "no blackbox header ('H Product:Blackbox flight data recorder')")
    if index >= len(starts):
        fail(path, 0, f"log index {index} asked, the file holds {len(starts)} logs")
    start = starts[index]
    end = starts[index + 1] if index + 1 < len(starts) else len(data)
    header, first = bb_header(path, data, start, end)
    return start, end, header, first, len(starts)


def bb_info(path, data, index):
    start, end, header, first, n_logs = bb_pick_log(path, data, index)
    frames = {}
    t_first = t_last = None
    for _, marker, _, t in bb_frames(path, data, first, end, header):
        frames[marker] = frames.get(marker, 0) + 1
        if t is not None:
            t_first = t if t_first is None else t_first
            t_last = t
    looptime = int(header.get("looptime", "0") or 0)
    denom = int(header.get("pid_process_denom", "1") or 1)
    p_interval = header.get("P interval", "?")
    p_ratio = header.get("P ratio", "")
    lines = [
        "format: Betaflight blackbox",
        f"logs in file: {n_logs} (this: {index})",
        f"firmware: {header.get('Firmware revision', '?')} ({header.get('Firmware date', '?')})",
        f"board: {header.get('Board information', '?')}  craft: {header.get('Craft name', '?')}",
        f"looptime: {looptime} us gyro, pid_process_denom {denom} -> PID loop "
        f"{1e6 / (looptime * denom) if looptime else 0:.0f} Hz; I interval {header.get('I interval', '?')}, "
        f"P interval {p_interval} {p_ratio}",
        f"debug_mode: {header.get('debug_mode', '?')}",
        f"frames: {frames}",
        f"duration: {((t_last or 0) - (t_first or 0)) / 1e6:.1f} s (I frames {t_first} .. {t_last} us)",
    ]
    n_main = frames.get("I", 0) + frames.get("P", 0)
    if t_first is not None and t_last and t_last > t_first:
        lines.append(f"log rate: {n_main / ((t_last - t_first) / 1e6):.0f} Hz (I+P frames)")
    return "\n".join(lines)


def bb_cut(path, data, start_s, max_bytes, index):
    start, end, header, first, _ = bb_pick_log(path, data, index)
    head = data[start:first]
    out_end = None
    begin = None
    t0 = None
    for offset, marker, stop, t in bb_frames(path, data, first, end, header):
        if t is not None and t0 is None:
            t0 = t
        if begin is None:
            if marker == "I" and t is not None and t >= t0 + start_s * 1e6:
                begin = offset
            else:
                continue
        if len(head) + (stop - begin) > max_bytes:
            break
        out_end = stop
    if begin is None or out_end is None:
        fail(path, first, f"no intra frame at or after {start_s} s fits the budget of {max_bytes} bytes")
    return head + data[begin:out_end]


# ---------------------------------------------------------------- command line


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p_info = sub.add_parser("info", help="what the log is")
    p_info.add_argument("log")
    p_info.add_argument("--log-index", type=int, default=0, help="blackbox: which log of the file")
    p_cut = sub.add_parser("cut", help="write a valid excerpt")
    p_cut.add_argument("log")
    p_cut.add_argument("out")
    p_cut.add_argument("--start-s", type=float, default=0.0, help="log time to start at (s from the first data)")
    p_cut.add_argument("--max-bytes", type=int, default=150_000, help="size budget of the excerpt (bytes)")
    p_cut.add_argument("--log-index", type=int, default=0, help="blackbox: which log of the file")
    p_cut.add_argument("--topics", help="ULog topics / DataFlash messages whose data to keep (comma separated; default all)")
    args = parser.parse_args(argv)
    if args.command == "cut":
        refuse_inputs("log_excerpt.py", {"OUT": args.out}, [args.log])

    with open(args.log, "rb") as f:
        data = f.read()
    kind = sniff(data)
    try:
        if kind is None:
            fail(args.log, 0, "not a ULog, DataFlash or Betaflight blackbox log (magic bytes)")
        if args.command == "info":
            if kind == "ulog":
                print(ulog_info(args.log, data))
            elif kind == "dataflash":
                print(dataflash_info(args.log, data))
            else:
                print(bb_info(args.log, data, args.log_index))
            return 0
        topics = set(args.topics.split(",")) if args.topics else None
        if topics is not None and kind == "blackbox":
            fail(args.log, 0, "--topics is for ULog and DataFlash logs: a blackbox frame holds every field")
        if kind == "ulog":
            cut = ulog_cut(args.log, data, args.start_s, args.max_bytes, topics)
        elif kind == "dataflash":
            cut = dataflash_cut(args.log, data, args.start_s, args.max_bytes, topics)
        else:
            cut = bb_cut(args.log, data, args.start_s, args.max_bytes, args.log_index)
    except LogError as e:
        print(e, file=sys.stderr)
        return 2
    write_whole(args.out, cut)
    print(f"{args.out}: {len(cut)} bytes ({kind}) from {args.log}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
