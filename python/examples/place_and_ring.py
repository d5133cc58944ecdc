#!/usr/bin/env python3
"""Build a scene with commands (as log lines), bend a sphere around a ring lattice, undo/redo, save the log.

Usage: python3 place_and_ring.py [OUT_DIR]   (PYTHONPATH=build/python)
"""
import os
import sys

import numpy as np
import trispline

out = sys.argv[1] if len(sys.argv) > 1 else "."
scene = trispline.Scene()
scene.run({"cmd": "scene.primitive", "kind": "teapot", "name": "pot", "scale": 0.6})
scene.run({"cmd": "scene.primitive", "kind": "sphere", "name": "ball", "translate": [0, 1.5, 0]})
entry = scene.run({"cmd": "lattice.ring", "object": "ball", "center": [0, 0, 0], "radius": 1.4, "phase": 0.0})
print("lattice.ring:", entry["ms"], "ms", entry["stats"])

try:
    scene.run({"cmd": "lattice.ring", "object": "nothing", "center": [0, 0, 0], "radius": 1.4})
except trispline.CommandError as e:
    print("refused, field", repr(e.field), "-", e.message)

bent = scene.vertices("ball")  # read-only #V×3 view of the deformed mesh, world units
scene.undo()
print("undo moved the ball back:", not np.array_equal(bent, scene.vertices("ball")))
scene.redo()
print("lattice:", scene.lattice("ball"), "fold-free:", trispline.certify(scene.lattice("ball"))["verdict"])

log = os.path.join(out, "ring.jsonl")
scene.save(log)
again = trispline.Scene.open(log)
print("saved", log, "- reopened:", again.objects, "same vertices:", np.array_equal(again.vertices("ball"), bent))
