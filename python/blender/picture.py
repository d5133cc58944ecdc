"""docs/images/blender_addon.png: a scene made by the trispline add-on, rendered by Blender's Workbench (headless).

    blender -b --factory-startup --python python/blender/picture.py -- [--out docs/images/blender_addon.png]

The Stanford bunny placed along a Grease Pencil stroke over a terrain and pressed on its back, thorn tiles over a
mound, and the T1 MRI's silhouettes standing beside them: the four operators, run as the menu runs them.
"""

import math
import os
import sys

import bpy
import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
OUT = argv[argv.index("--out") + 1] if "--out" in argv else os.path.join(ROOT, "docs", "images", "blender_addon.png")

sys.path.insert(0, os.path.join(ROOT, "python", "blender"))  # the add-on from this checkout (module: build/python)
import addon_utils  # noqa: E402

addon_utils.enable("trispline_blender", default_set=True)


def mat(name, rgb):
    m = bpy.data.materials.new(name)
    m.diffuse_color = (*rgb, 1.0)
    return m


def select(objs, active):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    for o in objs:
        o.select_set(True)
    bpy.context.view_layer.objects.active = active


for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)

bpy.ops.mesh.primitive_grid_add(x_subdivisions=48, y_subdivisions=48, size=5.0)
terrain = bpy.context.active_object
terrain.name = "Terrain"
for v in terrain.data.vertices:
    v.co.z = 0.16 * math.sin(1.4 * v.co.x + 0.5) * math.cos(1.1 * v.co.y)
terrain.data.materials.append(mat("Ground", (0.42, 0.55, 0.33)))
bpy.ops.object.shade_smooth()

bpy.ops.wm.obj_import(filepath=os.path.join(ROOT, "assets", "data", "bunny.obj"))
bunny = bpy.context.selected_objects[0]
bunny.location = (0, 6, 0)
bunny.data.materials.append(mat("Bunny", (0.9, 0.55, 0.2)))
bpy.ops.object.shade_smooth()

gpd = bpy.data.grease_pencils.new("Sketch")
gp = bpy.data.objects.new("Sketch", gpd)
bpy.context.collection.objects.link(gp)
stroke = gpd.layers.new("Lines").frames.new(1).strokes.new()
xs = np.linspace(-1.9, -0.2, 30)
stroke.points.add(len(xs))
for p, x in zip(stroke.points, xs):
    p.co = (x, -0.3 + 0.35 * math.sin(1.8 * x), 0.4)
bpy.context.view_layer.update()
select([bunny, gp, terrain], terrain)
print(bpy.ops.object.trispline_place(view="TOP", width=0.45, height=0.8, volume="OFFSET"))
placed = bpy.data.objects[bunny.name + " placed"]
bunny.hide_render = bunny.hide_viewport = True
gp.hide_render = True
V = np.array([v.co[:] for v in placed.data.vertices]) + np.array(placed.location)
top = V[np.argmax(V[:, 2])]
select([placed], placed)
print(bpy.ops.object.trispline_press(path=[{"name": "", "co": tuple(top + np.array([d, 0, 0]))} for d in (-0.1, 0.1)],
                                     radius=0.3, strength=0.15))

bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8, radius=0.6, location=(0.9, 0.6, 0.0))
mound = bpy.context.active_object
mound.scale.z = 0.6
mound.data.materials.append(mat("Mound", (0.75, 0.72, 0.66)))
bpy.ops.object.shade_smooth()
select([mound], mound)
print(bpy.ops.object.trispline_tile_fill(tile="THORN", tile_size=0.16, height=0.12, layout="BRICK"))
bpy.data.materials["trispline tiles"].diffuse_color = (0.55, 0.25, 0.15, 1.0)

bpy.context.scene.cursor.location = (1.9, 0.2, 0.95)
select([], None)
print(bpy.ops.object.trispline_silhouettes(
    filepath=os.path.join(ROOT, "assets", "data", "KmeansTest_T1UCharRaw.nii.gz"), view="FRONT", scale=0.0068,
    hidden="REMOVE", line_radius=1.6))

cam_data = bpy.data.cameras.new("Camera")
cam = bpy.data.objects.new("Camera", cam_data)
bpy.context.collection.objects.link(cam)
cam.location = (0.1, -5.0, 2.6)
cam.rotation_euler = (math.radians(66), 0, 0)
cam_data.lens = 30
scene = bpy.context.scene
scene.camera = cam
scene.render.engine = "BLENDER_WORKBENCH"
scene.render.resolution_x, scene.render.resolution_y = 960, 540
scene.display.shading.light = "STUDIO"
scene.display.shading.color_type = "MATERIAL"
scene.display.shading.show_cavity = True
scene.display.shading.show_shadows = True
scene.render.film_transparent = False
scene.world = scene.world or bpy.data.worlds.new("World")
scene.view_settings.view_transform = "Standard"
scene.render.filepath = OUT
bpy.ops.render.render(write_still=True)
print("wrote", OUT)
