# Runs inside Blender (blender -b --factory-startup --python blender_import.py -- FILE.glb OUT.json): imports FILE.glb
# with Blender's own glTF importer and writes what it made as JSON:
#   {"objects": [{"name", "vertices", "triangles", "materials": [names], "shape_keys"}],
#    "materials": {name: {"images": [image names], "alpha": blend_method}}, "images": {name: [width, height]}}
# Read by check_exports.py, which compares it with the GLB trispline wrote.
import json
import sys

import numpy

numpy.bool = bool  # Blender 3.4's glTF importer predates NumPy 1.24 (Debian 12 ships 1.24)

import bpy  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
source, out = args[0], args[1]

bpy.ops.wm.read_factory_settings(use_empty=True)
result = bpy.ops.import_scene.gltf(filepath=source)
if "FINISHED" not in result:
    raise SystemExit(f"Blender's glTF importer did not finish on {source}: {result}")

objects = []
for o in bpy.context.scene.objects:
    if o.type != "MESH":
        continue
    me = o.data
    objects.append({
        "name": o.name,
        "vertices": len(me.vertices),
        "triangles": sum(len(p.vertices) - 2 for p in me.polygons),
        "materials": [s.material.name for s in o.material_slots if s.material],
        "shape_keys": len(me.shape_keys.key_blocks) if me.shape_keys else 0,
    })

materials = {}
for m in bpy.data.materials:
    if not m.users or not m.use_nodes:
        continue
    images = sorted({n.image.name for n in m.node_tree.nodes if n.type == "TEX_IMAGE" and n.image})
    materials[m.name] = {"images": images, "alpha": m.blend_method}

images = {}
for im in bpy.data.images:
    if im.users and im.type == "IMAGE":
        images[im.name] = list(im.size)  # loads the pixels: [0, 0] when Blender could not decode the file

with open(out, "w") as f:
    json.dump({"objects": objects, "materials": materials, "images": images}, f, indent=1)
