#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Checks that the files of a library form layers, not a circle.

Usage: tools/check_layers.py [--nm NM] [--quiet] ARCHIVE_OR_OBJECT...

Reads the global symbols of each object (nm -A -P -g; an archive stands for
its members): file A depends on file B when A references a symbol B defines.
Exit status 0 and the layering on stdout (layer 0 depends on nothing of the
library, layer k on layers below k) when the graph has no cycle; 1 naming
every cycle (a -> b -> a) otherwise; 2 on bad usage or when nm fails.
"""

import argparse
import os
import re
import subprocess
import sys

# nm -P classes: lower case is local (ignored by -g) except the weak ones.
UNDEFINED = {"U", "w", "v"}
# "lib.a[member.o]: sym T ..." (an archive member) or "file.o: sym T ...".
LINE = re.compile(r"^(?:.*\[(?P<member>[^\]]+)\]|(?P<object>[^:]+)):\s+(?P<sym>\S+)\s+(?P<cls>\S)")


def file_name(obj):
    """axis.c.o -> axis.c: the source file an object came from."""
    base = os.path.basename(obj)
    return base[:-2] if base.endswith(".o") else base


def read_symbols(nm, paths):
    """{file: (defined set, undefined set)} over the objects of paths."""
    files = {}
    for path in paths:
        try:
            out = subprocess.run([nm, "-A", "-P", "-g", path], check=True, capture_output=True, text=True).stdout
        except (OSError, subprocess.CalledProcessError) as err:
            sys.exit(f"check_layers: {nm} failed on {path}: {err}")
        for line in out.splitlines():
            m = LINE.match(line)
            if not m:
                continue
            name = file_name(m.group("member") or m.group("object"))
            defined, undefined = files.setdefault(name, (set(), set()))
            (undefined if m.group("cls") in UNDEFINED else defined).add(m.group("sym"))
    return files


def file_graph(files):
    """{file: set of files it depends on}, within the given files only."""
    owner = {}
    for name, (defined, _) in files.items():
        for sym in defined:
            owner.setdefault(sym, name)
    return {name: {owner[s] for s in undefined if s in owner and owner[s] != name}
            for name, (_, undefined) in files.items()}


def circles(graph):
    """The strongly connected components of more than one file (Tarjan):
    each file of one is on a cycle with each other."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found



def one_cycle(graph, comp):
    """A shortest path from comp[0] back to itself inside comp (breadth first)."""
    start, members = comp[0], set(comp)
    prev, queue = {start: None}, [start]
    while queue:
        v = queue.pop(0)
        if start in graph[v]:
            path = [v]
            while prev[path[-1]] is not None:
                path.append(prev[path[-1]])
            return path[::-1] + [start]
        for w in sorted(graph[v] & members):
            if w not in prev:
                prev[w] = v
                queue.append(w)
    return comp + [start]  # not reached: comp is strongly connected


def layers(graph):
    """{file: layer}: 0 without dependencies, else 1 + the highest below."""
    layer = {}

    def depth(v):
        if v not in layer:
            layer[v] = 1 + max((depth(w) for w in graph[v]), default=-1)
        return layer[v]

    for v in graph:
        depth(v)
    return layer


def main(argv):
    parser = argparse.ArgumentParser(description="Fails on a dependency cycle between the files of a library.")
    parser.add_argument("--nm", default="nm", help="nm of the objects' target (default: nm)")
    parser.add_argument("--quiet", action="store_true", help="no layering on stdout")
    parser.add_argument("paths", nargs="+", metavar="ARCHIVE_OR_OBJECT")
    args = parser.parse_args(argv)
    graph = file_graph(read_symbols(args.nm, args.paths))
    if not graph:
        sys.exit("check_layers: no objects in " + " ".join(args.paths))
    found = circles(graph)
    if found:
        for comp in found:
            cycle = one_cycle(graph, comp)
            print("check_layers: cycle: " + " -> ".join(cycle), file=sys.stderr)
            if len(comp) > len(cycle) - 1:
                print("  in a circle of " + " ".join(comp), file=sys.stderr)
        return 1
    if not args.quiet:
        layer = layers(graph)
        for k in range(max(layer.values()) + 1):
            print(f"layer {k}: " + " ".join(sorted(v for v in layer if layer[v] == k)))
    print(f"check_layers: {len(graph)} files, no cycle")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
