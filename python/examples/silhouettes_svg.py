#!/usr/bin/env python3
"""Silhouettes of an analytic volume's iso-surface (seed §7.3.3) for two views, written as SVG polylines.

Usage: python3 silhouettes_svg.py [OUT_DIR]   (PYTHONPATH=build/python)
"""
import os
import sys

import numpy as np
import trispline

out = sys.argv[1] if len(sys.argv) > 1 else "."
scene = trispline.Scene()
scene.run({"cmd": "volume.load", "analytic": "torus", "name": "torus", "iso": 0.0})
for name, eye in (("front", (0, 0, 250)), ("oblique", (150, 120, 150))):
    camera = {"eye": eye, "target": (0, 0, 0), "up": (0, 1, 0)}
    curves = trispline.silhouettes(scene, "torus", camera)  # list of #K×3 polylines, millimetres
    forward = -np.asarray(eye, float) / np.linalg.norm(eye)
    right = np.cross(forward, (0, 1, 0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    paths = []
    for c in curves:
        x, y = 250 + 3 * (c @ right), 250 - 3 * (c @ up)
        paths.append("<polyline fill='none' stroke='black' points='" +
                     " ".join(f"{a:.1f},{b:.1f}" for a, b in zip(x, y)) + "'/>")
    path = os.path.join(out, f"torus_{name}.svg")
    with open(path, "w") as f:
        f.write("<svg xmlns='http://www.w3.org/2000/svg' width='500' height='500'>" + "".join(paths) + "</svg>\n")
    print(f"{name}: {len(curves)} curves, {sum(len(c) for c in curves)} points -> {path}")
