"""Blender data ↔ trispline data: axes, meshes, cameras, strokes.

Axes. Blender is Z-up, trispline (docs/commands.md, "The log format") Y-up; both right-handed, both in the meshes'
own units (Blender's metres are trispline's world units; volumes are millimetres, scaled by the operator).
    trispline (x, y, z) = Blender (x, z, -y)          Blender (x, y, z) = trispline (x, -z, y)
a rotation of -90° about X, the conversion glTF exporters make, so a log's scene.glb imports into Blender in place.

Shapes: V #V×3 float64 rows, F #F×3 int32 vertex indices (counter-clockwise seen from outside), as the module takes.
"""

import math

import bpy
import numpy as np


def active_mesh_in_object_mode(context):
    """The operators that act on the active mesh: Object Mode, an active object that is a mesh."""
    obj = context.active_object
    return context.mode == "OBJECT" and obj is not None and obj.type == "MESH"


def to_trispline(P):
    """#N×3 Blender points → trispline points (x, z, -y)."""
    P = np.asarray(P, dtype=np.float64).reshape(-1, 3)
    return np.column_stack((P[:, 0], P[:, 2], -P[:, 1]))


def to_blender(P):
    """#N×3 trispline points → Blender points (x, -z, y)."""
    P = np.asarray(P, dtype=np.float64).reshape(-1, 3)
    return np.column_stack((P[:, 0], -P[:, 2], P[:, 1]))


def matrix_np(M):
    return np.array([list(row) for row in M], dtype=np.float64)


def transform(M, P):
    """#N×3 points through a 4×4 matrix (mathutils or NumPy)."""
    M = matrix_np(M) if not isinstance(M, np.ndarray) else M
    return P @ M[:3, :3].T + M[:3, 3]


# ---- meshes ---------------------------------------------------------------------------------------------------------


def evaluated_mesh_arrays(obj, depsgraph, world=True):
    """The object's evaluated mesh (modifiers applied): V #V×3 Blender coordinates (world, or object space with
    world=False), F #T×3 int32 triangles (Blender's loop triangles of its polygons, vertex indices unchanged)."""
    ob_eval = obj.evaluated_get(depsgraph)
    me = ob_eval.to_mesh()
    try:
        V = np.empty(len(me.vertices) * 3, dtype=np.float64)
        me.vertices.foreach_get("co", V)
        V = V.reshape(-1, 3)
        me.calc_loop_triangles()
        F = np.empty(len(me.loop_triangles) * 3, dtype=np.int32)
        me.loop_triangles.foreach_get("vertices", F)
        F = F.reshape(-1, 3)
    finally:
        ob_eval.to_mesh_clear()
    if world:
        V = transform(obj.matrix_world, V)
    return V, F


def first_use_order(V, F):
    """V and F renumbered so that vertices come in the order the triangles first use them (unused ones dropped): the
    order the editor's mesh loader gives a file, so a mesh handed over here and the same mesh exported as OBJ and
    loaded by scene.load are one mesh, vertex for vertex. Results that depend on the vertex order (ddm.fill's
    auto_uv charts) then agree with `trispline replay` of the exported file."""
    flat = F.ravel()
    used, first = np.unique(flat, return_index=True)
    order = used[np.argsort(first)]
    remap = np.full(len(V), -1, dtype=np.int32)
    remap[order] = np.arange(len(order), dtype=np.int32)
    return V[order], remap[F]


def add_mesh(scene, name, V, F):
    """Put a mesh (trispline world coordinates) into a trispline Scene as object `name`: a primitive whose mesh is
    then replaced by `mesh.set` (docs/python.md, set_mesh), both through the scene's History. Positions are rounded
    to float32, Blender's own precision and what a mesh file of them (OBJ, glTF) read by scene.load holds, so a
    command gives here what `trispline replay` gives on the exported file (ddm.fill's automatic uvs can change
    with the last bits of a position)."""
    scene.run({"cmd": "scene.primitive", "kind": "box", "name": name})
    V32 = np.asarray(V, dtype=np.float32).astype(np.float64)
    scene.set_mesh(name, np.ascontiguousarray(V32), np.ascontiguousarray(F, dtype=np.int32))


def set_mesh_vertices(mesh, V_local):
    mesh.vertices.foreach_set("co", np.ascontiguousarray(V_local, dtype=np.float32).ravel())
    mesh.update()


def new_mesh(name, V, F, smooth=True):
    """A Blender mesh of V (#V×3, object space) and triangles F."""
    me = bpy.data.meshes.new(name)
    me.vertices.add(len(V))
    me.vertices.foreach_set("co", np.ascontiguousarray(V, dtype=np.float32).ravel())
    n = len(F)
    me.loops.add(3 * n)
    me.loops.foreach_set("vertex_index", np.ascontiguousarray(F, dtype=np.int32).ravel())
    me.polygons.add(n)
    me.polygons.foreach_set("loop_start", np.arange(0, 3 * n, 3, dtype=np.int32))
    me.polygons.foreach_set("loop_total", np.full(n, 3, dtype=np.int32))
    me.polygons.foreach_set("use_smooth", np.full(n, smooth, dtype=bool))
    me.update(calc_edges=True)
    return me


def link_object(context, name, data, location=(0.0, 0.0, 0.0)):
    """A new object in the active collection, selected and made active; the others deselected."""
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    context.collection.objects.link(obj)
    for o in context.selected_objects:
        o.select_set(False)
    obj.select_set(True)
    context.view_layer.objects.active = obj
    return obj


def bbox_centre(V):
    return 0.5 * (V.min(axis=0) + V.max(axis=0)) if len(V) else np.zeros(3)


def copy_materials(src, dst):
    """dst gets src's material slots (material and link), slot for slot; per-face indices are the mesh's."""
    if src is None:
        return
    while len(dst.material_slots) < len(src.material_slots):
        dst.data.materials.append(None)
    for i, slot in enumerate(src.material_slots):
        if slot.link == "OBJECT":
            dst.material_slots[i].link = "OBJECT"
        dst.material_slots[i].material = slot.material


def material(name, rgb):
    """The add-on's own material `name` (made once; linear RGB), for results without a source material."""
    mat = bpy.data.materials.get(name)
    if mat is None:
        mat = bpy.data.materials.new(name)
        mat.diffuse_color = (*rgb, 1.0)
        mat.use_nodes = True
        bsdf = mat.node_tree.nodes.get("Principled BSDF")
        if bsdf:
            bsdf.inputs["Base Color"].default_value = (*rgb, 1.0)
    return mat


# ---- cameras: trispline's camera.set dict (eye, target, up, fov_deg, viewport), trispline coordinates -----------


def camera_dict(eye_b, forward_b, up_b, fov_y_rad, width, height, distance=1.0):
    eye = to_trispline(eye_b)[0]
    f = to_trispline(forward_b)[0]
    f = f / np.linalg.norm(f)
    return {
        "eye": [float(x) for x in eye],
        "target": [float(x) for x in eye + f * distance],
        "up": [float(x) for x in to_trispline(up_b)[0]],
        "fov_deg": math.degrees(fov_y_rad),
        "viewport": [int(width), int(height)],
    }


def camera_from_viewport(context):
    """The 3D viewport's perspective view as a camera; None outside a 3D viewport or in an orthographic view.
    Camera view (Numpad 0) gives the scene camera (its frame is an off-centre part of the region)."""
    rv3d, region = context.region_data, context.region
    if rv3d is None or region is None or context.area is None or context.area.type != "VIEW_3D":
        return None
    if rv3d.view_perspective == "CAMERA" and context.scene.camera:
        return camera_from_object(context.scene, context.scene.camera)
    if not rv3d.is_perspective:
        return None
    inv = rv3d.view_matrix.inverted()
    fov_y = 2.0 * math.atan(1.0 / rv3d.window_matrix[1][1])
    return camera_dict(inv.translation, -inv.col[2].xyz, inv.col[1].xyz, fov_y, region.width, region.height,
                       rv3d.view_distance)


def camera_from_object(scene, cam_obj):
    """A perspective Blender camera at the scene's render resolution; None for other camera types."""
    cam = cam_obj.data
    if cam.type != "PERSP":
        return None
    r = scene.render
    w = max(1, round(r.resolution_x * r.resolution_percentage / 100))
    h = max(1, round(r.resolution_y * r.resolution_percentage / 100))
    fit = cam.sensor_fit if cam.sensor_fit != "AUTO" else ("HORIZONTAL" if w >= h else "VERTICAL")
    if fit == "HORIZONTAL":
        fov_y = 2.0 * math.atan(cam.sensor_width / (2.0 * cam.lens) * h / w)
    else:
        fov_y = 2.0 * math.atan(cam.sensor_height / (2.0 * cam.lens))
    M = cam_obj.matrix_world.normalized()
    return camera_dict(M.translation, -M.col[2].xyz, M.col[1].xyz, fov_y, w, h)


def camera_top(points_b, above_b=(), fov_deg=30.0, size=1000):
    """A camera looking straight down (Blender -Z) at points_b (#N×3), framing them in 80 % of a size² image,
    higher than every point of above_b (the ground's bounding box)."""
    P = np.asarray(points_b, dtype=np.float64).reshape(-1, 3)
    lo, hi = P.min(axis=0), P.max(axis=0)
    c = 0.5 * (lo + hi)
    half = max(0.5 * float(np.max(hi[:2] - lo[:2])), 1e-3) / 0.8
    top = max([hi[2]] + [float(q[2]) for q in above_b])
    dist = half / math.tan(math.radians(fov_deg) / 2.0)
    eye = np.array([c[0], c[1], max(c[2] + dist, top + 0.25 * dist)])
    return camera_dict(eye, (0.0, 0.0, -1.0), (0.0, 1.0, 0.0), math.radians(fov_deg), size, size,
                       float(eye[2] - c[2]))


def project(camera, P_t):
    """trispline points #N×3 → viewport pixels #N×2 ((0,0) top-left, y down) and view depths #N, as
    core/scene/camera.cpp projects (glm::lookAt, glm::perspective with the vertical fov)."""
    eye, target, up = (np.asarray(camera[k], dtype=np.float64) for k in ("eye", "target", "up"))
    w, h = camera["viewport"]
    f = target - eye
    f /= np.linalg.norm(f)
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    d = P_t - eye
    x, y, z = d @ s, d @ u, d @ f
    t = math.tan(math.radians(camera["fov_deg"]) / 2.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ndc_x = x / (z * t * (w / h))
        ndc_y = y / (z * t)
    return np.column_stack(((ndc_x + 1.0) * 0.5 * w, (1.0 - ndc_y) * 0.5 * h)), z


# ---- grease pencil strokes --------------------------------------------------------------------------------------------


def _last_stroke(gpd):
    layer = gpd.layers.active or (gpd.layers[-1] if len(gpd.layers) else None)
    if layer is None:
        return None
    frame = layer.active_frame or (layer.frames[-1] if len(layer.frames) else None)
    if frame is None or not len(frame.strokes):
        return None
    return frame.strokes[-1]


def grease_pencil_stroke(context):
    """World points (#N×3, Blender) of the stroke to place along and where it came from: the last stroke of the
    active layer's current frame of a selected Grease Pencil object, else of the scene's annotations (the Annotate
    tool). (None, why) when there is none."""
    for obj in context.selected_objects:
        if obj.type == "GPENCIL":
            stroke = _last_stroke(obj.data)
            if stroke is not None and len(stroke.points) >= 2:
                P = np.array([p.co[:] for p in stroke.points], dtype=np.float64)
                return transform(obj.matrix_world, P), f"Grease Pencil '{obj.name}'"
    gpd = context.scene.grease_pencil  # annotations: points already in world space
    stroke = _last_stroke(gpd) if gpd else None
    if stroke is not None and len(stroke.points) >= 2:
        return np.array([p.co[:] for p in stroke.points], dtype=np.float64), "annotation"
    return None, "no stroke: draw one with a selected Grease Pencil object or the Annotate tool"


def resample_polyline(P, n):
    """n points evenly spaced by arc length along polyline P (#N×D), ends kept."""
    seg = np.linalg.norm(np.diff(P, axis=0), axis=1)
    s = np.concatenate(([0.0], np.cumsum(seg)))
    if s[-1] <= 0.0:
        return P[:1]
    t = np.linspace(0.0, s[-1], n)
    return np.column_stack([np.interp(t, s, P[:, k]) for k in range(P.shape[1])])
