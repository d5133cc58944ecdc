"""Object ▸ trispline ▸ Place along Grease Pencil Stroke: `place.sketch` (seed §2.3.1) in Blender.

The selected mesh is placed onto the active object under the last Grease Pencil stroke (a selected Grease Pencil
object's, else the scene's annotation). place.sketch takes its stroke in viewport pixels with the camera it was drawn
in, so the stroke's 3D points are projected with a camera (the View property): the 3D viewport's view, the scene
camera, or one looking straight down. The result is a new mesh object (the source's topology, uvs and materials,
placed vertices); it remembers its source, its ground and the commands run, for Press (ops_press.py).
"""

import json

import bpy
import numpy as np

from . import convert
from .module import module_or_report

AXES = [("X", "X", "Blender's X axis"), ("Y", "Y", "Blender's Y axis"), ("Z", "Z", "Blender's Z axis")]
TRISPLINE_AXIS = {"X": "x", "Y": "z", "Z": "y"}  # Blender axis → trispline axis (x, y, z)_b = (x, -z, y)_t
AXIS_INDEX = {"X": 0, "Y": 1, "Z": 2}

VIEWS = [
    ("AUTO", "Automatic", "The 3D viewport's view when run from one, else the scene camera, else Top"),
    ("VIEWPORT", "Viewport", "The 3D viewport's perspective view the operator is run from"),
    ("CAMERA", "Scene camera", "The scene's perspective camera at the render resolution"),
    ("TOP", "Top", "A camera looking straight down (-Z) at the stroke"),
]

# Ids of the objects in the trispline scene the operators build (object names may be anything in Blender).
GROUND, OBJECT = "ground", "object"


def view_camera(op, context, view, stroke_b, ground_b):
    """The camera dict for `view`, or None after reporting why."""
    cam = None
    if view in ("AUTO", "VIEWPORT"):
        cam = convert.camera_from_viewport(context)
        if cam is None and view == "VIEWPORT":
            op.report({"ERROR"}, "View: Viewport needs a 3D viewport in a perspective view (Numpad 5)")
            return None
    if cam is None and view in ("AUTO", "CAMERA") and context.scene.camera is not None:
        cam = convert.camera_from_object(context.scene, context.scene.camera)
        if cam is None and view == "CAMERA":
            op.report({"ERROR"}, "View: Scene camera needs a perspective camera")
            return None
    if cam is None and view == "CAMERA":
        op.report({"ERROR"}, "View: Scene camera, but the scene has no camera")
        return None
    if cam is None:
        lo, hi = ground_b.min(axis=0), ground_b.max(axis=0)
        cam = convert.camera_top(stroke_b, above_b=(lo, hi))
    return cam


def placed_scene(mod, context, obj):
    """A trispline Scene holding `obj`'s placement again: its source and ground as they are now (evaluated, world
    space) and the commands it recorded (place.sketch, then every press). (scene, None) or (None, why)."""
    src, ground = obj.get("trispline_source"), obj.get("trispline_ground")
    log = obj.get("trispline_log")
    if not log or src is None or ground is None:
        return None, f"'{obj.name}' was not placed by Place along Grease Pencil Stroke (nothing to press)"
    if not isinstance(src, bpy.types.Object) or src.type != "MESH" or not isinstance(ground, bpy.types.Object):
        return None, f"the source or the ground of '{obj.name}' is gone"
    dg = context.evaluated_depsgraph_get()
    scene = mod.Scene()
    for name, ob in ((GROUND, ground), (OBJECT, src)):
        V, F = convert.evaluated_mesh_arrays(ob, dg)
        convert.add_mesh(scene, name, convert.to_trispline(V), F)
    for line in json.loads(log):
        scene.run(line)
    return scene, None


def write_placed_vertices(obj, V_t):
    """The object's mesh vertices from trispline world points (its own matrix undone)."""
    V_b = convert.to_blender(V_t)
    M_inv = np.linalg.inv(convert.matrix_np(obj.matrix_world))
    convert.set_mesh_vertices(obj.data, convert.transform(M_inv, V_b))


class OBJECT_OT_trispline_place(bpy.types.Operator):
    """Place the selected mesh onto the active object under the last Grease Pencil stroke (trispline place.sketch)"""

    bl_idname = "object.trispline_place"
    bl_label = "Place along Grease Pencil Stroke"
    bl_options = {"REGISTER", "UNDO"}

    view: bpy.props.EnumProperty(name="View", items=VIEWS, default="AUTO",
                                 description="The camera the stroke is seen through (place.sketch's camera)")
    width: bpy.props.FloatProperty(
        name="Half-width (m)", default=0.0, min=0.0, soft_max=10.0, unit="LENGTH",
        description="d: half-width of the band around the stroke, in metres; 0: half the object's extent across "
        "the stroke")
    height: bpy.props.FloatProperty(
        name="Height (m)", default=0.0, min=0.0, soft_max=10.0, unit="LENGTH",
        description="h: height of the deformation volume above the contact surface, in metres; 0: the object's "
        "own height along Up axis")
    volume: bpy.props.EnumProperty(
        name="Volume", default="EXTRUDE",
        items=[("EXTRUDE", "Extrude", "F1: the contact surface extruded towards the viewer (seed Eq. 2.3)"),
               ("OFFSET", "Offset", "F2: the contact surface offset along its normals (seed Eq. 2.4)")])
    fit: bpy.props.EnumProperty(
        name="Fit", default="KEEP",
        items=[("KEEP", "Keep proportions", "The object keeps its length : height along the stroke"),
               ("STRETCH", "Stretch", "The object covers the whole stroke (the seed's placement)")])
    extent: bpy.props.FloatProperty(name="Extent", default=1.0, min=0.01, max=1.0, subtype="FACTOR",
                                    description="Fraction of the stroke the object covers (stretch) or at most "
                                    "covers (keep)")
    length_axis: bpy.props.EnumProperty(name="Length axis", items=AXES, default="X",
                                        description="The object's world axis laid along the stroke")
    up_axis: bpy.props.EnumProperty(name="Up axis", items=AXES, default="Z",
                                    description="The object's world axis that points away from the surface")
    samples: bpy.props.IntVectorProperty(name="Rays", size=2, default=(32, 8), min=4, max=4096,
                                         description="Contact rays along × across the stroke")
    stroke_points: bpy.props.IntProperty(name="Stroke points", default=32, min=2, max=1024,
                                         description="The stroke resampled to this many points by arc length")

    @classmethod
    def poll(cls, context):
        return context.mode == "OBJECT" and context.active_object is not None

    def execute(self, context):
        mod = module_or_report(self, context)
        if mod is None:
            return {"CANCELLED"}
        ground = context.active_object
        sources = [o for o in context.selected_objects if o.type == "MESH" and o != ground]
        if ground.type != "MESH" or len(sources) != 1:
            self.report({"ERROR"}, "Select the mesh to place, then the ground mesh last (active)")
            return {"CANCELLED"}
        if self.length_axis == self.up_axis:
            self.report({"ERROR"}, "Length axis and Up axis must differ")
            return {"CANCELLED"}
        src = sources[0]
        stroke_b, where = convert.grease_pencil_stroke(context)
        if stroke_b is None:
            self.report({"ERROR"}, where)
            return {"CANCELLED"}

        dg = context.evaluated_depsgraph_get()
        Vg, Fg = convert.evaluated_mesh_arrays(ground, dg)
        Vs, Fs = convert.evaluated_mesh_arrays(src, dg)
        cam = view_camera(self, context, self.view, stroke_b, Vg)
        if cam is None:
            return {"CANCELLED"}
        px, depth = convert.project(cam, convert.to_trispline(convert.resample_polyline(stroke_b,
                                                                                          self.stroke_points)))
        if np.any(depth <= 0.0):
            self.report({"ERROR"}, f"The {where} stroke is partly behind the camera of View '{self.view}'")
            return {"CANCELLED"}

        ext = Vs.max(axis=0) - Vs.min(axis=0)
        up, length = AXIS_INDEX[self.up_axis], AXIS_INDEX[self.length_axis]
        across = 3 - up - length
        line = {
            "cmd": "place.sketch", "object": OBJECT, "stroke": np.round(px, 3).tolist(),
            "width": self.width or max(0.5 * float(ext[across]), 1e-3),
            "height": self.height or max(float(ext[up]), 1e-3),
            "samples": list(self.samples), "volume": self.volume.lower(), "fit": self.fit.lower(),
            "extent": self.extent, "length_axis": TRISPLINE_AXIS[self.length_axis],
            "up_axis": TRISPLINE_AXIS[self.up_axis], "camera": cam,
        }
        scene = mod.Scene()
        try:
            convert.add_mesh(scene, GROUND, convert.to_trispline(Vg), Fg)
            convert.add_mesh(scene, OBJECT, convert.to_trispline(Vs), Fs)
            entry = scene.run(line)
        except (mod.CommandError, ValueError) as e:
            self.report({"ERROR"}, f"place.sketch: {e}")
            return {"CANCELLED"}

        V_b = convert.to_blender(scene.vertices(OBJECT))
        mesh = bpy.data.meshes.new_from_object(src.evaluated_get(dg))  # topology, uvs, face materials kept
        mesh.name = f"{src.name} placed"
        if len(mesh.vertices) != len(V_b):  # cannot happen: mesh.set kept the evaluated mesh's vertices
            bpy.data.meshes.remove(mesh)
            self.report({"ERROR"}, "the placed mesh lost its vertex order")
            return {"CANCELLED"}
        centre = convert.bbox_centre(V_b)
        convert.set_mesh_vertices(mesh, V_b - centre)
        obj = convert.link_object(context, mesh.name, mesh, location=centre)
        convert.copy_materials(src, obj)
        obj["trispline_source"] = src
        obj["trispline_ground"] = ground
        obj["trispline_log"] = json.dumps([entry["command"]])
        st = entry["stats"]
        self.report({"INFO"}, f"Placed '{src.name}' on '{ground.name}' along the {where} stroke: "
                    f"{st.get('rays_hit')} of {st.get('rays_total')} rays hit, {entry['ms']:.0f} ms")
        return {"FINISHED"}
