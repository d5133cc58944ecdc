#!/usr/bin/env python3
"""Deform a NumPy point cloud through an FFD lattice (seed Eq. 2.1), with exact normals (seed §4.3).

Usage: python3 ffd_numpy.py   (PYTHONPATH=build/python)
"""
import numpy as np
import trispline

rng = np.random.default_rng(7)
points = rng.normal(size=(200_000, 3))
normals = points / np.linalg.norm(points, axis=1, keepdims=True)
points = normals.copy()  # a unit sphere: its normals are its points

lo, hi = np.full(3, -1.2), np.full(3, 1.2)
lattice = trispline.Lattice.identity(bounds=(lo, hi), controls=(5, 5, 5), orders=(4, 4, 4))
P, N = trispline.ffd_evaluate(lattice, points, normals=normals)
print("identity lattice, max |P - points|:", np.abs(P - points).max())

cp = lattice.control_points  # #5×5×5×3 copy, world units
cp[:, 4, :, 1] += 0.8  # lift the top layer of control points (v = 1 is +y)
cp[2, :, 2, 0] *= 1.5  # and widen the middle column
stretched = lattice.with_control_points(cp)
P, N = trispline.ffd_evaluate(stretched, points, normals=normals)
print("stretched: y range", P[:, 1].min().round(3), "..", P[:, 1].max().round(3),
      "| normals unit:", np.allclose(np.linalg.norm(N, axis=1), 1.0))

ref, _ = trispline.ffd_evaluate(stretched, points, backend="cpu_ref")
print("cpu_fast vs cpu_ref, max error:", np.abs(P - ref).max())
print("certificate:", trispline.certify(stretched)["verdict"])

evaluator = trispline.FfdEvaluator(stretched, points)  # bind once, then evaluate per frame
for t in (0.0, 0.1, 0.2):
    P, _ = evaluator.evaluate(offset=(0.0, t, 0.0))
    print(f"offset v = {t}: mean y {P[:, 1].mean():.4f}")
