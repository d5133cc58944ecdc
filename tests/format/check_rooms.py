#!/usr/bin/env python3
"""The rooms of the source tree (docs/architecture.md) include each other without a cycle.

A room is the folder a tracked C++ file lives in (core/params, gpu/eval, editor/farm, ...). Room A depends on room B
when a file of A includes "B/x.h". The test fails, naming the cycle and one include of each step, when the rooms'
dependency graph has a cycle, and when a lower layer includes a higher one (core < gpu < ui < editor < bench < editor/cli;
tests and python may include anything). Never skips: without git it fails.
"""
import os
import re
import subprocess
import sys

# Each room's layer: the longest prefix listed decides (editor/cli, the command line, sits on the benchmarks).
LAYERS = ["core", "gpu", "ui", "editor", "bench", "editor/cli"]


def layer(path: str) -> int:
    best = -1
    for i, prefix in enumerate(LAYERS):
        if (path + "/").startswith(prefix + "/") and (best < 0 or len(prefix) > len(LAYERS[best])):
            best = i
    return best
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def main() -> int:
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    os.chdir(root)
    try:
        files = subprocess.check_output(["git", "ls-files", "*.cpp", "*.h"], text=True).split()
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"FAIL: cannot list the tracked files: {e}")
        return 1
    tracked = set(files)
    edges = {}  # (room, room) -> an example "file includes path"
    failures = []
    for f in files:
        if layer(f) < 0 or not os.path.isfile(f):
            continue
        room = os.path.dirname(f)
        with open(f, encoding="utf-8", errors="replace") as h:
            text = h.read()
        for inc in INCLUDE.findall(text):
            if inc not in tracked:
                continue  # generated headers, system-style includes of the build tree
            target = os.path.dirname(inc)
            if layer(inc) > layer(f):
                failures.append(f"{f} includes {inc}: {LAYERS[layer(f)]}/ must not depend on {LAYERS[layer(inc)]}/")
            if target != room:
                edges.setdefault((room, target), f"{f} includes {inc}")
    graph = {}
    for a, b in edges:
        graph.setdefault(a, set()).add(b)
    # Cycles: Tarjan's strongly connected components; any component of two or more rooms is a cycle.
    index, low, stack, on, comps = {}, {}, [], set(), []
    counter = [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            strong(v)
    for comp in comps:
        failures.append("rooms that include each other: " + ", ".join(comp))
        members = set(comp)
        for (a, b), why in sorted(edges.items()):
            if a in members and b in members:
                failures.append(f"    {a} -> {b}: {why}")
    if failures:
        print("FAIL: the rooms' includes go both ways or upwards (docs/architecture.md):")
        for line in failures:
            print("  " + line)
        return 1
    rooms = {r for e in edges for r in e}
    print(f"ok: {len(rooms)} rooms, {len(edges)} dependencies between them, no cycle, no upward include (core < gpu < ui < editor < bench < editor/cli)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
