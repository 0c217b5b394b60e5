#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Bytes of one archive that a linked image carries, from the GNU ld map.

Usage: linked.py MAP ARCHIVE_NAME
Prints "LINKED <object> <flash> <ram>" per object of the archive and
"LINKED total <flash> <ram>": flash = .text + .rodata + .data input sections
kept by the link (the discarded ones are listed before the memory map and
skipped), ram = .data + .bss.
"""
import re
import sys

KEPT_FROM = "Linker script and memory map"
# An input section line: " .text.name 0xADDR 0xSIZE path/lib.a(obj.o)"; a long
# name puts the address, size and path on the next line.
ENTRY = re.compile(r"^\s*(\.\S+)?\s+0x[0-9a-f]+\s+0x([0-9a-f]+)\s+\S*?([^/\s]+)\(([^)]+)\)\s*$")
NAME_ONLY = re.compile(r"^\s(\.\S+)\s*$")


def main() -> int:
    map_path, archive = sys.argv[1], sys.argv[2]
    kept = False
    pending = None
    per_obj = {}
    for line in open(map_path, encoding="utf-8", errors="replace"):
        if not kept:
            kept = line.startswith(KEPT_FROM)
            continue
        m = NAME_ONLY.match(line)
        if m:
            pending = m.group(1)
            continue
        m = ENTRY.match(line)
        if m and m.group(3) == archive:
            section = m.group(1) or pending
            size = int(m.group(2), 16)
            flash, ram = per_obj.get(m.group(4), (0, 0))
            if section and section.startswith((".text", ".rodata", ".data")):
                flash += size
            if section and section.startswith((".data", ".bss")):
                ram += size
            per_obj[m.group(4)] = (flash, ram)
        pending = None
    for obj, (flash, ram) in sorted(per_obj.items()):
        print(f"LINKED {obj} {flash} {ram}")
    print(f"LINKED total {sum(f for f, _ in per_obj.values())} {sum(r for _, r in per_obj.values())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
