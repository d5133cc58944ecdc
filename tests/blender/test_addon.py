"""The trispline Blender add-on (python/blender/trispline_blender) driven inside Blender, checked against the CLI.

    blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py -- \
        --source-dir . --module-dir build/python --trispline build/editor/trispline --work /tmp/x [--undo]

Installs the add-on from a zip (python/blender/make_zip.py) into a scripts folder under --work, enables it, builds a
terrain, an icosphere, a tile mesh and a Grease Pencil stroke, runs the four operators and checks each result's
vertex count and bounding box against the same commands run by `trispline replay` on the same meshes written as OBJ
(report.json's objects and scene.glb's positions). The silhouettes run on assets/data/KmeansTest_T1UCharRaw.nii.gz
and fail (never skip) without it. Every operator must be one undo step: in background mode (no window, so
ed.undo cannot run) that is its bl_options; with --undo (run under Xvfb, with a window) each operator is undone
for real and the scene checked to be as before. Any failure exits 1.
"""

import argparse
import json
import math
import os
import struct
import subprocess
import sys
import time
import traceback

import bpy
import numpy as np

FAILURES = []
T0 = time.time()


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        FAILURES.append(what)
    return cond


def args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser()
    ap.add_argument("--source-dir", required=True)
    ap.add_argument("--module-dir", required=True)
    ap.add_argument("--trispline", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--undo", action="store_true")
    return ap.parse_args(argv)


# ---- the test's own conversions (independent of the add-on's convert.py) ------------------------------------------


def mesh_world(obj):
    """Evaluated world-space vertices #V×3 (Blender) and loop triangles of a mesh object."""
    dg = bpy.context.evaluated_depsgraph_get()
    ob = obj.evaluated_get(dg)
    me = ob.to_mesh()
    me.calc_loop_triangles()
    M = np.array(obj.matrix_world)
    V = np.array([v.co[:] for v in me.vertices], dtype=np.float64)
    F = np.array([t.vertices[:] for t in me.loop_triangles], dtype=np.int64)
    ob.to_mesh_clear()
    return V @ M[:3, :3].T + M[:3, 3], F


def y_up(V):  # Blender Z-up → trispline Y-up: (x, y, z) → (x, z, -y)
    return np.column_stack((V[:, 0], V[:, 2], -V[:, 1]))


def write_obj(path, V, F):
    with open(path, "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V.tolist())
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F.tolist())


def bbox_blender(obj):
    """World bounding box of a mesh's vertices or a curve's points, in trispline axes (to compare with scene.glb)."""
    M = np.array(obj.matrix_world)
    if obj.type == "MESH":
        P = np.array([v.co[:] for v in obj.data.vertices])
    else:
        P = np.array([p.co[:3] for s in obj.data.splines for p in s.points])
    W = P @ M[:3, :3].T + M[:3, 3]
    T = y_up(W)
    return T.min(axis=0), T.max(axis=0), len(P)


def glb_positions(path):
    """{node name: #V×3 world positions} of a GLB's mesh nodes (node transforms applied)."""
    data = open(path, "rb").read()
    jlen = struct.unpack_from("<I", data, 12)[0]
    gltf = json.loads(data[20:20 + jlen])
    binary = data[20 + jlen + 8:]
    out = {}

    def matrix(node):
        if "matrix" in node:
            return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
        M = np.eye(4)
        x, y, z, w = node.get("rotation", [0, 0, 0, 1])
        R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                      [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                      [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
        M[:3, :3] = R * np.array(node.get("scale", [1, 1, 1]))
        M[:3, 3] = node.get("translation", [0, 0, 0])
        return M

    def visit(i, parent):
        node = gltf["nodes"][i]
        M = parent @ matrix(node)
        if "mesh" in node:
            P = []
            for prim in gltf["meshes"][node["mesh"]]["primitives"]:
                acc = gltf["accessors"][prim["attributes"]["POSITION"]]
                view = gltf["bufferViews"][acc["bufferView"]]
                stride = view.get("byteStride", 12)
                off = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
                raw = np.frombuffer(binary, dtype=np.uint8, count=stride * (acc["count"] - 1) + 12, offset=off)
                rows = np.lib.stride_tricks.as_strided(raw, shape=(acc["count"], 12), strides=(stride, 1))
                P.append(np.ascontiguousarray(rows).view("<f4").reshape(-1, 3).astype(np.float64))
            P = np.concatenate(P) if P else np.zeros((0, 3))
            out[node.get("name", str(i))] = P @ M[:3, :3].T + M[:3, 3]
        for c in node.get("children", []):
            visit(c, M)

    for s in gltf.get("scenes", [{"nodes": list(range(len(gltf["nodes"])))}]):
        for i in s["nodes"]:
            visit(i, np.eye(4))
    return out


def same_box(name, got, want, count_got, count_want):
    lo, hi, _ = got
    wlo, whi = want
    diag = float(np.linalg.norm(whi - wlo))
    tol = 2e-5 * diag + 1e-6  # float32 storage in Blender and in glTF
    err = float(max(np.max(np.abs(lo - wlo)), np.max(np.abs(hi - whi))))
    check(count_got == count_want, f"{name}: {count_got} vertices, trispline replay {count_want}")
    check(err <= tol, f"{name}: bounding box within {err:.2e} of trispline replay's (tolerance {tol:.1e})")


# ---- the scene ---------------------------------------------------------------------------------------------------


def clear_scene():
    for obj in list(bpy.data.objects):
        if obj.type != "CAMERA":
            bpy.data.objects.remove(obj)


def select(objs, active):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    for o in objs:
        o.select_set(True)
    bpy.context.view_layer.objects.active = active


def build_scene():
    clear_scene()
    cam = bpy.context.scene.camera
    cam.location = (0.3, -5.0, 4.5)
    cam.rotation_euler = (math.radians(48), 0.0, math.radians(3))
    cam.data.lens = 35
    r = bpy.context.scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = 960, 540, 100

    bpy.ops.mesh.primitive_grid_add(x_subdivisions=28, y_subdivisions=28, size=4.0, location=(0.2, -0.1, 0.05))
    terrain = bpy.context.active_object
    terrain.name = "Terrain"
    terrain.rotation_euler = (0.0, 0.0, math.radians(12))
    for v in terrain.data.vertices:
        x, y, _ = v.co
        v.co.z = 0.18 * math.sin(1.7 * x) * math.cos(1.3 * y)
    terrain.data.materials.append(bpy.data.materials.new("Ground"))

    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=0.3, location=(2.5, 2.5, 1.0))
    ico = bpy.context.active_object
    ico.name = "Ico"
    ico.scale = (1.6, 0.8, 0.8)
    ico.data.materials.append(bpy.data.materials.new("IcoMat"))

    bpy.ops.mesh.primitive_cone_add(vertices=8, radius1=0.5, depth=1.0, location=(-3.0, 2.5, 0.5))
    tile = bpy.context.active_object
    tile.name = "TileCone"
    tile.data.materials.append(bpy.data.materials.new("TileMat"))

    gpd = bpy.data.grease_pencils.new("Sketch")
    gp = bpy.data.objects.new("Sketch", gpd)
    bpy.context.collection.objects.link(gp)
    frame = gpd.layers.new("Lines").frames.new(1)
    stroke = frame.strokes.new()
    xs = np.linspace(-1.2, 1.0, 24)
    stroke.points.add(len(xs))
    for p, x in zip(stroke.points, xs):
        p.co = (x, 0.25 * math.sin(1.5 * x), 0.3)
    bpy.context.view_layer.update()
    return terrain, ico, tile, gp, np.array([p.co[:] for p in stroke.points])


# ---- install and enable --------------------------------------------------------------------------------------------


def install(a):
    import importlib.util

    spec = importlib.util.spec_from_file_location("make_zip", os.path.join(a.source_dir, "python", "blender",
                                                                            "make_zip.py"))
    make_zip = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make_zip)  # not through sys.path: the add-on must come from the installed copy

    scripts = os.path.join(a.work, "scripts")
    os.makedirs(os.path.join(scripts, "addons"), exist_ok=True)
    zpath = make_zip.make_zip(os.path.join(a.work, "trispline_blender.zip"), a.module_dir)
    bpy.context.preferences.filepaths.script_directory = scripts  # never the user's own scripts folder
    bpy.utils.refresh_script_paths()
    bpy.ops.preferences.addon_install(filepath=zpath, target="PREFS", overwrite=True)
    installed = os.path.join(scripts, "addons", "trispline_blender", "__init__.py")
    check(os.path.isfile(installed), f"add-on installed from the zip into {os.path.dirname(installed)}")
    bpy.ops.preferences.addon_enable(module="trispline_blender")
    check("trispline_blender" in bpy.context.preferences.addons, "add-on enabled")
    import trispline_blender

    check(os.path.realpath(trispline_blender.__file__) == os.path.realpath(installed), "the installed copy runs")
    check(hasattr(bpy.types, "VIEW3D_MT_trispline"), "Object ▸ trispline menu registered")
    for op in ("place", "press", "tile_fill", "silhouettes"):
        cls = bpy.types.Operator.bl_rna_get_subclass_py(f"OBJECT_OT_trispline_{op}")
        check(cls is not None and {"REGISTER", "UNDO"} <= set(cls.bl_options),
              f"object.trispline_{op}: bl_options REGISTER, UNDO (one undo step)")
    trispline = trispline_blender.module.import_trispline(bpy.context)
    check(os.path.realpath(os.path.dirname(os.path.dirname(trispline.__file__))) == os.path.realpath(a.module_dir),
          "trispline module found through the zip's module_path.txt")


# ---- the operators ---------------------------------------------------------------------------------------------------


def run_op(op, **kw):
    t = time.time()
    res = op(**kw)
    print(f"     {op.idname_py()} -> {res} in {time.time() - t:.2f} s", flush=True)
    return res


def main():
    a = args()
    a.source_dir, a.module_dir, a.work = (os.path.abspath(p) for p in (a.source_dir, a.module_dir, a.work))
    os.makedirs(a.work, exist_ok=True)
    nii = os.path.join(a.source_dir, "assets", "data", "KmeansTest_T1UCharRaw.nii.gz")
    if not check(os.path.isfile(nii), f"{nii} present (missing: run scripts/fetch_assets.sh)"):
        print("hint: scripts/fetch_assets.sh fetches assets/data/KmeansTest_T1UCharRaw.nii.gz", flush=True)
    install(a)
    terrain, ico, tile, gp, stroke = build_scene()
    ops = bpy.ops.object
    log = []

    # Ground, object and tile as the add-on would see them, written as OBJ for the CLI.
    Vg, Fg = mesh_world(terrain)
    Vi, Fi = mesh_world(ico)
    write_obj(os.path.join(a.work, "terrain.obj"), y_up(Vg), Fg)
    write_obj(os.path.join(a.work, "ico.obj"), y_up(Vi), Fi)
    me = tile.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
    me.calc_loop_triangles()
    write_obj(os.path.join(a.work, "tile.obj"), np.array([v.co[:] for v in me.vertices]),
              np.array([t.vertices[:] for t in me.loop_triangles]))
    tile.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh_clear()

    # 1. Place along the Grease Pencil stroke: the icosphere onto the terrain, seen by the scene camera.
    select([ico, gp, terrain], terrain)
    n_before = len(bpy.data.objects)
    res = run_op(ops.trispline_place, view="CAMERA", width=0.3, height=0.35, samples=(32, 8))
    check(res == {"FINISHED"}, "Place along Grease Pencil Stroke finished")
    placed = bpy.data.objects.get("Ico placed")
    check(placed is not None and len(bpy.data.objects) == n_before + 1, "one new object 'Ico placed'")
    check(placed.material_slots[0].material.name == "IcoMat", "the placed object keeps the source's material")
    placed_box = bbox_blender(placed)
    W = np.array(placed.matrix_world)
    Pw = np.array([v.co[:] for v in placed.data.vertices]) @ W[:3, :3].T + W[:3, 3]
    mid = Pw.mean(axis=0)
    check(stroke[:, 0].min() - 0.4 <= mid[0] <= stroke[:, 0].max() + 0.4 and abs(mid[1] - 0.25 * math.sin(1.5 *
          mid[0])) < 0.45, f"the placed object lies along the stroke (centre {mid.round(3).tolist()})")
    lines = json.loads(placed["trispline_log"])
    check(lines[0]["cmd"] == "place.sketch" and len(lines[0]["stroke"]) == 32, "placement recorded (place.sketch)")
    log_place = [{"cmd": "scene.load", "path": "terrain.obj", "name": "ground"},
                 {"cmd": "scene.load", "path": "ico.obj", "name": "object"}, lines[0]]

    # 2. Press the placed object: a sphere swept over its top, executed with a path (the modal's result).
    top = Pw[np.argmax(Pw[:, 2])]
    path = [{"name": "", "co": tuple(top + np.array([dx, 0.0, 0.05]))} for dx in (-0.2, 0.0, 0.2)]
    select([placed], placed)
    V_before = np.array([v.co[:] for v in placed.data.vertices])
    res = run_op(ops.trispline_press, path=path, radius=0.35, strength=0.12, falloff="smooth")
    check(res == {"FINISHED"}, "Press finished")
    V_after = np.array([v.co[:] for v in placed.data.vertices])
    check(len(V_after) == len(V_before) and np.max(np.abs(V_after - V_before)) > 1e-3,
          f"Press moved the object's vertices in place (at most {np.max(np.abs(V_after - V_before)):.3f} m)")
    lines = json.loads(placed["trispline_log"])
    check([ln["cmd"] for ln in lines] == ["place.sketch", "lattice.press"], "press recorded after the placement")
    log_press = log_place + [lines[1]]

    # 3. Tile Fill: the cone as tile over the terrain, 0.45 m tiles.
    select([tile, terrain], terrain)
    res = run_op(ops.trispline_tile_fill, tile="OBJECT", tile_size=0.45, height=0.2, layout="RECT", base="AUTO_UV")
    check(res == {"FINISHED"}, "Tile Fill finished")
    tiles = bpy.data.objects.get("Terrain tiles")
    check(tiles is not None and tiles.material_slots[0].material.name == "TileMat",
          "one new object 'Terrain tiles' with the tile's material")
    log_tiles = [{"cmd": "scene.load", "path": "terrain.obj", "name": "surface"},
                 {"cmd": "ddm.fill", "object": "surface", "layer": "tiles", "tile": "tile.obj", "layout": "rect",
                  "tile_size": 0.45, "height": 0.2, "base": "auto_uv"},
                 {"cmd": "ddm.bake", "object": "surface", "layer": "tiles", "name": "tiles"}]

    # 4. Silhouettes from the T1 MRI, seen from the front, hidden parts kept (comparable with report.json).
    select([], None)
    res = run_op(ops.trispline_silhouettes, filepath=nii, view="FRONT", hidden="SHOW", scale=0.005)
    sil = bpy.data.objects.get("KmeansTest_T1UCharRaw silhouettes")
    n_points = sum(len(s.points) for s in sil.data.splines) if sil else 0
    check(res == {"FINISHED"} and sil is not None and sil.type == "CURVE" and n_points > 0,
          f"Silhouettes: a curve object of {len(sil.data.splines) if sil else 0} POLY splines, {n_points} points")
    check(sil is not None and all(s.type == "POLY" for s in sil.data.splines) and len(sil.material_slots) == 1,
          "silhouette splines are POLY, with a material")
    sl = json.loads(sil["trispline_log"])
    log_sil = [dict(sl[0], path=nii), sl[1], sl[2]]

    # trispline replay of the same commands
    def replay(name, lines):
        path = os.path.join(a.work, name + ".jsonl")
        with open(path, "w") as f:
            f.writelines(json.dumps(ln) + "\n" for ln in lines)
        out = os.path.join(a.work, name)
        t = time.time()
        p = subprocess.run([a.trispline, "replay", path, "--out", out, "--no-render"], capture_output=True,
                           text=True)
        check(p.returncode == 0, f"trispline replay {name}.jsonl ({time.time() - t:.2f} s) {p.stderr.strip()[-300:]}")
        report = json.load(open(os.path.join(out, "report.json")))
        return report, glb_positions(os.path.join(out, "scene.glb"))

    def compare(name, box, report, glb, obj_id):
        count = {o["name"]: o["vertices"] for o in report["objects"]}.get(obj_id, -1)
        P = glb.get(obj_id, np.zeros((0, 3)))
        same_box(name, box, (P.min(axis=0), P.max(axis=0)) if len(P) else (np.zeros(3), np.zeros(3)), box[2], count)

    report, glb = replay("place", log_place)
    compare("Place", placed_box, report, glb, "object")
    report, glb = replay("press", log_press)
    compare("Press", bbox_blender(placed), report, glb, "object")
    report, glb = replay("tiles", log_tiles)
    compare("Tile Fill", bbox_blender(tiles), report, glb, "tiles")
    report, _ = replay("silhouettes", log_sil)
    st = report["commands"][-1]["stats"]
    check(st["points"] == n_points and st["polylines"] == len(sil.data.splines),
          f"Silhouettes: {n_points} points in {len(sil.data.splines)} splines, trispline replay "
          f"{st['points']} in {st['polylines']}")

    if a.undo:
        undo_checks(terrain, ico, tile, gp, nii)


def undo_checks(terrain, ico, tile, gp, nii):
    """With a window: each operator is one undo step (ed.undo brings back the scene as it was before it). The calls
    pass undo=True (bpy.ops' second argument), which pushes the undo step a menu or key press pushes; a script's
    plain call pushes none."""
    win = bpy.context.window_manager.windows[0]
    ops = bpy.ops.object

    def undo():
        with bpy.context.temp_override(window=win):
            bpy.ops.ed.undo()

    def names():
        return sorted(o.name for o in bpy.data.objects)

    for label, setup, call in (
        ("Place", lambda: select([bpy.data.objects["Ico"], bpy.data.objects["Sketch"], bpy.data.objects["Terrain"]],
                                 bpy.data.objects["Terrain"]),
         lambda: ops.trispline_place("EXEC_DEFAULT", True, view="CAMERA", width=0.3, height=0.35)),
        ("Tile Fill", lambda: select([bpy.data.objects["TileCone"], bpy.data.objects["Terrain"]],
                                     bpy.data.objects["Terrain"]),
         lambda: ops.trispline_tile_fill("EXEC_DEFAULT", True, tile="OBJECT", tile_size=0.45, height=0.2)),
        ("Silhouettes", lambda: select([], None),
         lambda: ops.trispline_silhouettes("EXEC_DEFAULT", True, filepath=nii, view="FRONT", scale=0.005)),
    ):
        setup()
        bpy.ops.ed.undo_push(message=f"before {label}")
        before = names()
        check(call() == {"FINISHED"}, f"undo: {label} ran")
        after = names()
        undo()
        check(after != before and names() == before, f"undo: one ed.undo removes what {label} made")
    placed = bpy.data.objects["Ico placed"]
    select([placed], placed)
    bpy.ops.ed.undo_push(message="before Press")
    placed = bpy.data.objects["Ico placed"]
    V0 = np.array([v.co[:] for v in placed.data.vertices])
    top = V0[np.argmax(V0[:, 2])] + np.array(placed.matrix_world.translation)
    check(ops.trispline_press("EXEC_DEFAULT", True, path=[{"name": "", "co": tuple(top)}], radius=0.4, strength=0.15) == {"FINISHED"}, "undo: Press ran")
    placed = bpy.data.objects["Ico placed"]
    V1 = np.array([v.co[:] for v in placed.data.vertices])
    log1 = placed["trispline_log"]
    undo()
    placed = bpy.data.objects["Ico placed"]
    V2 = np.array([v.co[:] for v in placed.data.vertices])
    check(np.max(np.abs(V1 - V0)) > 1e-3 and np.array_equal(V2, V0) and placed["trispline_log"] != log1,
          "undo: one ed.undo restores the pressed vertices and the recorded presses")


def finish():
    try:
        main()
    except Exception:
        traceback.print_exc()
        FAILURES.append("exception")
    print(f"{'FAILED: ' + str(len(FAILURES)) + ' check(s)' if FAILURES else 'all checks passed'} "
          f"({time.time() - T0:.1f} s)", flush=True)
    if bpy.app.background:
        sys.exit(1 if FAILURES else 0)
    os._exit(1 if FAILURES else 0)  # with a window (--undo under Xvfb): leave without saving quit.blend


if __name__ == "__main__":  # (test_press_drag.py imports the helpers above)
    if bpy.app.background:
        finish()
    else:  # a window: run once the event loop is up, so that ed.undo has a screen
        bpy.app.timers.register(lambda: finish() or None, first_interval=0.5)
