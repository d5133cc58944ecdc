#!/usr/bin/env python3
"""FFD throughput from Python beside `trispline bench ffd`'s cpu_fast figure, like for like (docs/python.md).

Both sides deform the same 1 M vertices (a UV sphere of --rows × --cols vertices written to a binary PLY, which
`bench ffd --mesh FILE --subdiv 0` loads) through L×L×L lattices (L = 4, 8) of orders 3 and 4, randomly perturbed by
15 % of a cell, positions only and positions + normals, on all threads (oneTBB default: every core). Columns:
  bench      `trispline bench ffd --cpu-only --json`, cpu_fast, all threads, "kernel" (evaluate() on bound vertices)
  evaluator  trispline.FfdEvaluator.evaluate(): the same kernel plus the results written into new NumPy arrays
  out=       FfdEvaluator.evaluate(out=(P, N)): the same into arrays the caller keeps (an animation loop)
  bench e2e  the bench's cpu_fast "end_to_end": world points embedded, a fresh evaluator bound (sort by cell),
             evaluated, float64 results written — in C++
  one-shot   trispline.ffd_evaluate(lattice, points): the same work from Python; its ratio is to bench e2e
Median of --runs runs each, in M vertices / s. Usage:
  PYTHONPATH=build/python python3 python/bench_ffd.py [--trispline build/editor/trispline] [--runs 5]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

# This script's folder holds the package's sources (python/trispline without the compiled module): import the built
# package from PYTHONPATH instead.
sys.path[:] = [p for p in sys.path if os.path.abspath(p or ".") != os.path.dirname(os.path.abspath(__file__))]
import trispline  # noqa: E402


def sphere(rows, cols):
    """A UV sphere of rows × cols vertices (radius 1) and its triangles, unit normals = positions."""
    th = np.linspace(0.02, np.pi - 0.02, rows)
    ph = np.linspace(0.0, 2 * np.pi, cols, endpoint=False)
    t, p = np.meshgrid(th, ph, indexing="ij")
    V = np.stack([np.sin(t) * np.cos(p), np.cos(t), np.sin(t) * np.sin(p)], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(rows - 1), np.arange(cols), indexing="ij")
    a = i * cols + j
    b = i * cols + (j + 1) % cols
    c, d = a + cols, b + cols
    F = np.concatenate([np.stack([a, c, b], -1).reshape(-1, 3), np.stack([b, c, d], -1).reshape(-1, 3)])
    return V, F.astype(np.int32)


def write_ply(path, V, F):
    with open(path, "wb") as f:
        f.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {len(V)}\nproperty double x\n"
                f"property double y\nproperty double z\nelement face {len(F)}\n"
                "property list uchar int vertex_indices\nend_header\n".encode())
        f.write(V.astype("<f8").tobytes())
        faces = np.empty(len(F), dtype=[("n", "u1"), ("i", "<i4", 3)])
        faces["n"] = 3
        faces["i"] = F
        f.write(faces.tobytes())


def perturbed(lo, hi, controls, order, rng, perturbation=0.15):
    L = trispline.Lattice.identity(bounds=(lo, hi), controls=(controls,) * 3, orders=(order,) * 3)
    cp = L.control_points
    cp += rng.uniform(-1, 1, cp.shape) * (perturbation / (controls - 1)) * (hi - lo)
    return L.with_control_points(cp)


def median_ms(runs, fn):
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t0) * 1e3)
    return float(np.median(times))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--trispline", default="build/editor/trispline", help="the trispline executable")
    ap.add_argument("--rows", type=int, default=1000)
    ap.add_argument("--cols", type=int, default=1000)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    a = ap.parse_args()
    V, F = sphere(a.rows, a.cols)
    with tempfile.TemporaryDirectory() as tmp:
        ply = os.path.join(tmp, "sphere.ply")
        write_ply(ply, V, F)
        out = subprocess.run([a.trispline, "bench", "ffd", "--cpu-only", "--json", "--mesh", ply, "--subdiv", "0",
                              "--runs", str(a.runs)], check=True, capture_output=True, text=True).stdout
    bench = json.loads(out[out.index("{"):])
    rng = np.random.default_rng(1)
    lo, hi = V.min(axis=0), V.max(axis=0)
    rows = []
    e2e = {(c["lattice"][0], c["order"][0], c["normals"]): c for c in bench["cases"]
           if c["backend"] == "cpu_fast" and c["threads"] == bench["threads_all"] and c["timing"] == "end_to_end"}
    for c in bench["cases"]:
        if c["backend"] != "cpu_fast" or c["threads"] != bench["threads_all"] or c["timing"] != "kernel":
            continue
        L = perturbed(lo, hi, c["lattice"][0], c["order"][0], rng)
        N = V if c["normals"] else None  # the sphere's unit normals
        ev = trispline.FfdEvaluator(L, V, normals=N)
        ev.evaluate()  # warm-up (first binning), as the bench's evaluator is bound before timing
        ev_ms = median_ms(a.runs, ev.evaluate)
        out = (np.empty((len(V), 3)), np.empty((len(V), 3)) if c["normals"] else None)
        ev.evaluate(out=out)  # the out= arrays' pages touched once, as an animation loop's are
        out_ms = median_ms(a.runs, lambda: ev.evaluate(out=out))
        one_ms = median_ms(a.runs, lambda: trispline.ffd_evaluate(L, V, normals=N))
        mv = len(V) / 1e3
        e = e2e[(c["lattice"][0], c["order"][0], c["normals"])]
        rows.append({"lattice": c["lattice"][0], "order": c["order"][0], "normals": c["normals"],
                     "vertices": len(V), "bench_mverts_s": c["mverts_per_s"], "evaluator_mverts_s": mv / ev_ms,
                     "one_shot_mverts_s": mv / one_ms, "bench_ms": c["median_ms"], "evaluator_ms": ev_ms,
                     "bench_e2e_ms": e["median_ms"], "one_shot_ms": one_ms, "out_ms": out_ms})
    result = {"cpu": bench["cpu"], "simd": bench["simd"], "threads": bench["threads_all"],
              "bench_vertices": bench["mesh"]["vertices"], "runs": a.runs, "cases": rows}
    if a.json:
        print(json.dumps(result, indent=2))
        return 0
    print(f"{result['cpu']}, {result['threads']} threads, {result['simd']}; {len(V):,} vertices "
          f"(bench: {result['bench_vertices']:,}); median of {a.runs} runs; M vertices/s (ms)")
    print(f"{'lattice':>8} {'order':>6} {'normals':>8} {'bench':>16} {'evaluator':>16} {'ratio':>6} "
          f"{'out=':>8} {'ratio':>6} {'bench e2e':>10} {'one-shot':>16} {'ratio':>6}")
    for r in rows:
        print(f"{r['lattice']:>6}^3 {r['order']:>6} {str(r['normals']):>8} "
              f"{r['bench_mverts_s']:>8.1f} ({r['bench_ms']:5.1f}) {r['evaluator_mverts_s']:>8.1f} "
              f"({r['evaluator_ms']:5.1f}) {r['evaluator_ms'] / r['bench_ms']:>6.2f} "
              f"{r['out_ms']:>8.1f} {r['out_ms'] / r['bench_ms']:>6.2f} "
              f"{r['bench_e2e_ms']:>10.1f} "
              f"{r['one_shot_mverts_s']:>8.1f} ({r['one_shot_ms']:5.1f}) {r['one_shot_ms'] / r['bench_e2e_ms']:>6.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
