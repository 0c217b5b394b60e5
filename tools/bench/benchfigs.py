# SPDX-License-Identifier: BSD-3-Clause
"""The figures of one benchmark measurement (tools/bench/measure.sh's data
file), read once for tools/bench/render.py and tools/bench/check.py.

Every figure is derived here from the records as the tools printed them, so
that the tables and the limits check read the same numbers.
"""
import re


def awk_num(x):
    """A number as awk's print shows it: integers whole, else %.6g."""
    if x == int(x) and abs(x) < 1e16:
        return str(int(x))
    return "%.6g" % x


class Figures:
    def __init__(self, path):
        self.path = path
        self.records = {}  # source -> list of lines (text after the source)
        with open(path, encoding="utf-8") as f:
            for line in f:
                line = line.rstrip("\n")
                if not line or line.startswith("#"):
                    continue
                source, _, text = line.partition(" ")
                self.records.setdefault(source, []).append(text)

    def lines(self, source):
        return self.records.get(source, [])

    def fields(self, source):
        """Each line of source split on whitespace, numbered as awk does ($1 = f[1])."""
        return [[""] + line.split() for line in self.lines(source)]

    def keyed(self, source, key):
        """The text after `key ` in the first record of source that starts with it."""
        for line in self.lines(source):
            k, _, rest = line.partition(" ")
            if k == key:
                return rest
        return ""

    # ---- Cortex-M4F benchmark ("BENCH key ...") --------------------------------
    def m4f(self, kind, *match):
        """Fields of the m4f lines whose $2 is kind and $3, $4... equal match."""
        out = []
        for f in self.fields("m4f"):
            if len(f) > 2 and f[2] == kind and all(len(f) > 3 + i and f[3 + i] == m for i, m in enumerate(match)):
                out.append(f)
        return out

    def _first(self, rows, col):
        vals = [r[col] for r in rows if len(r) > col]
        return "\n".join(vals)

    def insn(self, case, col):
        """Instructions per tick of case: col 1 one axis, 2 three axes + mixer."""
        return self._first(self.m4f("insn", case), 3 + col)

    def worst(self, case):
        return self._first(self.m4f("worst", case), 4)

    def size_of(self, type_name):
        return self._first(self.m4f("sizeof", type_name), 4)

    def module(self, name):
        return self._first(self.m4f("module", name), 4)

    def clock(self):
        """The text of the BENCH clock line."""
        return "\n".join(l[len("BENCH clock "):] for l in self.lines("m4f") if l.startswith("BENCH clock "))

    def clock_match(self, pattern):
        out = []
        for line in self.lines("m4f"):
            m = re.match(pattern, line)
            if m:
                out.append(m.group(1))
        return "\n".join(out)

    def instructions_per_count(self):
        return self.clock_match(r"^BENCH clock .*: ([0-9]*) instructions per count.*")

    def ticks_per_block(self):
        return self.clock_match(r"^BENCH clock .*; ([0-9]*) ticks per block.*$")

    def ticks_per_block_text(self):
        return self.clock_match(r"^BENCH clock .*; ([0-9]* ticks per block.*)$")

    # ---- library size, linked bytes, stack ----------------------------------------
    def size_totals(self):
        """(text, data, bss) of the archive."""
        for f in self.fields("size"):
            if "(TOTALS)" in f:
                return int(f[1]), int(f[2]), int(f[3])
        raise ValueError(f"{self.path}: no size totals")

    def size_objects(self):
        """(object, text + data) per object of the archive, in size's order."""
        out = []
        for line in self.lines("size"):
            if ".obj " not in line:
                continue
            f = line.split()
            obj = f[5]
            if obj.endswith(".obj"):
                obj = obj[: -len(".obj")]
            out.append((obj, int(f[0]) + int(f[1])))
        return out

    def linked_hp(self, source="linked"):
        """Library flash the HP firmware links; source "linked-lean": the lean HP build's."""
        return self._first([f for f in self.fields(source) if len(f) > 2 and f[2] == "total"], 3)

    # ---- the lean HP build (tools/bench/bench_lean.c: "BENCH lean ...") ---------------
    def lean(self, kind, *match):
        """Fields of the lean lines ("BENCH lean kind ..."): f[0] "lean", f[1] kind, f[2]..."""
        return [f[2:] for f in self.m4f("lean", kind, *match)]

    def lean_insn(self):
        return self._first(self.lean("insn", "HP-MLADRC"), 3)

    def lean_worst(self):
        return self._first(self.lean("worst", "HP-MLADRC"), 3)

    def lean_size_of(self, type_name):
        return self._first(self.lean("sizeof", type_name), 3)

    def stack(self):
        """(worst bytes, its root, its chain, external names) of the tick roots."""
        worst, root = 0.0, ""
        rows = [f for f in self.fields("stack") if len(f) > 1 and f[1] == "STACK"]
        for f in rows:
            if float(f[3]) > worst:
                worst, root = float(f[3]), f[2]
        chain = "\n".join(" ".join(f[4:]) for f in rows if f[2] == root)
        ext = "\n".join(" ".join(f[2:]) for f in self.fields("stack") if len(f) > 1 and f[1] == "EXTERNAL")
        return awk_num(worst), root, chain, ext

    def stack_roots(self):
        return " ".join(self.lines("stack-roots"))

    # ---- the figures the limits gate (tools/bench/limits.txt keys) -------------------
    CASES = ("PID", "LADRC", "LP-MLADRC", "HP-MLADRC", "HP-MLADRC-2tones", "HP-MLADRC-act", "CASCADED", "INDI",
             "LADRC-act", "RATE-ADRC", "HP-MLADRC-gyro")

    def quaternion_frame(self):
        """What the quaternion frame adds to LADRC's 3-axis attitude step (instructions per tick)."""
        quat = float(self.module("attitude_step_ladrc_quat"))
        euler = float(self.module("attitude_step_ladrc_euler"))
        return f"{quat - euler:.2f}"

    def gated(self):
        text, data, _bss = self.size_totals()
        out = {
            "flash.library": str(text + data),
            "stack.tick": self.stack()[0],
            "flash.linked_hp": self.linked_hp(),
            "sizeof.ladrc_attitude_t": self.size_of("ladrc_attitude_t"),
            "flash.linked_hp_lean": self.linked_hp("linked-lean"),
            "sizeof.ladrc_attitude_t.hp_lean": self.lean_size_of("ladrc_attitude_t"),
            "insn.3axes.HP-MLADRC-lean": self.lean_insn(),
            "insn.worst.HP-MLADRC-lean": self.lean_worst(),
        }
        out["insn.gyro_filter.rpm_4x3_3ch"] = self.module("gyro_filter_rpm_4x3_3ch")
        out["insn.frame.quaternion"] = self.quaternion_frame()
        for v in self.CASES:
            out["insn.axis." + v] = self.insn(v, 1)
            out["insn.3axes." + v] = self.insn(v, 2)
            out["insn.worst." + v] = self.worst(v)
        return out
