#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Worst-case stack of the tick functions, from gcc's -fcallgraph-info=su files.

Usage: stack.py DIR ROOT...

Reads every *.ci file under DIR (one per library object), joins the call
graphs, and prints for each ROOT the deepest chain: the sum of the frames
along it. Calls to functions with no frame size in the graph (the C library,
e.g. sinf) are listed as external and counted as 0 bytes. Recursion or a
dynamic frame is an error, since neither has a static bound.
Output lines: "STACK <root> <bytes> <chain>" and "EXTERNAL <name>...".
"""
import os
import re
import sys

NODE = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
EDGE = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')
FRAME = re.compile(r'\\n(\d+) bytes \(([^)]*)\)')


def short(name):
    return name.rsplit(':', 1)[-1]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    frames, calls = {}, {}
    for base, _, files in os.walk(sys.argv[1]):
        for f in sorted(files):
            if not f.endswith('.ci'):
                continue
            with open(os.path.join(base, f), encoding='utf-8') as fh:
                for line in fh:
                    m = NODE.search(line)
                    if m:
                        fr = FRAME.search(m.group(2))
                        if fr:
                            if fr.group(2) != 'static':
                                sys.exit(f'stack.py: {short(m.group(1))}: {fr.group(2)} frame')
                            frames[m.group(1)] = int(fr.group(1))
                        continue
                    m = EDGE.search(line)
                    if m:
                        calls.setdefault(m.group(1), set()).add(m.group(2))
    external = set()
    memo = {}

    def worst(fn, path):
        if fn in path:
            sys.exit('stack.py: recursion: ' + ' -> '.join(short(p) for p in path + [fn]))
        if fn in memo:
            return memo[fn]
        if fn not in frames:
            external.add(short(fn))
            return 0, [short(fn) + '(ext)']
        best, chain = 0, []
        for callee in sorted(calls.get(fn, ())):
            depth, sub = worst(callee, path + [fn])
            if depth > best or not chain:
                best, chain = depth, sub
        memo[fn] = (frames[fn] + best, [f'{short(fn)}({frames[fn]})'] + chain)
        return memo[fn]

    for root in sys.argv[2:]:
        if root not in frames:
            sys.exit(f'stack.py: {root}: not in the call graph')
        depth, chain = worst(root, [])
        print(f'STACK {root} {depth} {" > ".join(chain)}')
    print('EXTERNAL ' + ' '.join(sorted(external)))


if __name__ == '__main__':
    main()
