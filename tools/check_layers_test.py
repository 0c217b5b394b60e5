#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""tools/check_layers.py on tiny objects: two files calling each other must
fail naming the cycle, the same two with the call going one way must pass
with their layers. Usage: tools/check_layers_test.py [CC [NM]] (default cc, nm)."""

import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.join(HERE, "check_layers.py")


def build(cc, work, sources):
    """Compiles {name: text} into work/name.o; returns the objects."""
    objects = []
    for name, text in sources.items():
        src = os.path.join(work, name)
        with open(src, "w") as f:
            f.write(text)
        obj = src + ".o"
        subprocess.run([cc, "-c", src, "-o", obj], check=True)
        objects.append(obj)
    return objects


def check(nm, objects):
    run = subprocess.run([sys.executable, CHECK, "--nm", nm] + objects, capture_output=True, text=True)
    return run.returncode, run.stdout + run.stderr


def expect(what, cond, out):
    if not cond:
        print(f"check_layers_test: FAIL: {what}\n{out}", file=sys.stderr)
        sys.exit(1)
    print(f"check_layers_test: ok: {what}")


def main():
    cc = sys.argv[1] if len(sys.argv) > 1 else "cc"
    nm = sys.argv[2] if len(sys.argv) > 2 else "nm"
    with tempfile.TemporaryDirectory() as work:
        circle = build(cc, work, {
            "up.c": "int down(int x);\nint up(int x) { return x > 0 ? down(x - 1) : 0; }\n",
            "down.c": "int up(int x);\nint down(int x) { return up(x); }\n",
        })
        rc, out = check(nm, circle)
        expect("two files calling each other fail", rc == 1, out)
        expect("the cycle is named", "cycle: down.c -> up.c -> down.c" in out, out)

        layered = build(cc, work, {
            "top.c": "int bottom(int x);\nint top(int x) { return bottom(x) + 1; }\n",
            "bottom.c": "int bottom(int x) { return 2 * x; }\n",
        })
        rc, out = check(nm, layered)
        expect("a call one way passes", rc == 0, out)
        expect("the layers are printed", "layer 0: bottom.c\nlayer 1: top.c\n" in out, out)


if __name__ == "__main__":
    main()
