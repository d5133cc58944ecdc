"""Object ▸ trispline ▸ Press: `lattice.press` (seed §2.4.1, Fig. 2.7), the spherical pressing tool, in Blender.

Presses an object placed by Place along Grease Pencil Stroke (it has the FFD lattice to press): its placement is run
again from its source and ground as they are now (ops_place.placed_scene), the recorded presses after it, then this
press; the object's vertices are written in place and the press is recorded on it. One drag is one press, one undo
step (as in the editor: a drag is one command).

Modal from the menu: drag with the left mouse button over the object (the sphere's centres follow the surface under
the cursor), release to press; wheel: radius; X: pull instead of press; Esc / right button: cancel. Executed with a
`path` (as scripts and tests do: bpy.ops.object.trispline_press(path=[{"name": "", "co": (x, y, z)}, ...])) it presses at once.
"""

import json

import bpy
import numpy as np
from bpy_extras import view3d_utils

from . import convert
from .module import module_or_report
from .ops_place import OBJECT, placed_scene, write_placed_vertices

FALLOFFS = [
    ("smooth", "Smooth", "3s² - 2s³, s = 1 - t"),
    ("sphere", "Sphere", "√(1 - t²)"),
    ("root", "Root", "√(1 - t)"),
    ("sharp", "Sharp", "(1 - t)²"),
    ("hat", "Linear", "1 - t (the seed's hat)"),
    ("gaussian", "Gaussian", "exp(-4.5 t²), the seed's"),
    ("box", "Box", "1 inside the sphere (the seed's box)"),
    ("constant", "Constant", "1 inside the sphere"),
]


class TrisplinePathPoint(bpy.types.PropertyGroup):
    co: bpy.props.FloatVectorProperty(name="Location (m)", size=3, subtype="TRANSLATION", unit="LENGTH",
                                      description="A sphere centre, world coordinates in metres")


class OBJECT_OT_trispline_press(bpy.types.Operator):
    """Press the active placed object with a sphere swept along a drag (trispline lattice.press)"""

    bl_idname = "object.trispline_press"
    bl_label = "Press"
    bl_options = {"REGISTER", "UNDO"}

    # SKIP_SAVE: a drag's path is not remembered for the next call from the menu (which would press at once there).
    path: bpy.props.CollectionProperty(type=TrisplinePathPoint, name="Path", options={"SKIP_SAVE"},
                                       description="Sphere centres along the sweep, world coordinates in metres")
    radius: bpy.props.FloatProperty(name="Radius (m)", default=0.2, min=1e-4, soft_max=10.0, unit="LENGTH",
                                    description="Sphere radius in metres")
    strength: bpy.props.FloatProperty(
        name="Strength (m)", default=0.1, soft_min=-2.0, soft_max=2.0, unit="LENGTH",
        description="How far, in metres, the lattice points under the centre move along their columns; < 0 pulls")
    falloff: bpy.props.EnumProperty(name="Falloff", items=FALLOFFS, default="smooth",
                                    description="Weight over the distance t from the path (radius units)")
    keep_fold_free: bpy.props.BoolProperty(
        name="Keep fold-free", default=False,
        description="Limit the strength so that the pressed lattice stays certified fold-free (det J > 0)")

    @classmethod
    def poll(cls, context):
        return convert.active_mesh_in_object_mode(context)

    # ---- one press -------------------------------------------------------------------------------------------------

    def execute(self, context):
        mod = module_or_report(self, context)
        if mod is None:
            return {"CANCELLED"}
        obj = context.active_object
        if len(self.path) == 0:
            self.report({"ERROR"}, "Press needs a path: drag over the object, or give path=[{'name': '', 'co': (x, y, z)}]")
            return {"CANCELLED"}
        scene, why = placed_scene(mod, context, obj)
        if scene is None:
            self.report({"ERROR"}, why)
            return {"CANCELLED"}
        if len(scene.vertices(OBJECT)) != len(obj.data.vertices):
            self.report({"ERROR"}, f"'{obj.name}' no longer has its source's vertices (edited after placing)")
            return {"CANCELLED"}
        path = convert.to_trispline(np.array([p.co[:] for p in self.path], dtype=np.float64))
        line = {"cmd": "lattice.press", "object": OBJECT, "path": path.tolist(), "radius": self.radius,
                "strength": self.strength, "falloff": self.falloff, "keep_fold_free": self.keep_fold_free}
        try:
            entry = scene.run(line)
        except (mod.CommandError, ValueError) as e:
            self.report({"ERROR"}, f"lattice.press: {e}")
            return {"CANCELLED"}
        write_placed_vertices(obj, scene.vertices(OBJECT))
        obj["trispline_log"] = json.dumps(json.loads(obj["trispline_log"]) + [entry["command"]])
        st = entry["stats"]
        self.report({"INFO"}, f"Pressed '{obj.name}': {st.get('moved')} control points moved, at most "
                    f"{st.get('max_displacement', 0.0):.3g} m")
        return {"FINISHED"}

    # ---- the modal drag --------------------------------------------------------------------------------------------

    def invoke(self, context, event):
        if len(self.path) or context.area is None or context.area.type != "VIEW_3D":
            return self.execute(context)
        if module_or_report(self, context) is None:
            return {"CANCELLED"}
        if not context.active_object.get("trispline_log"):
            self.report({"ERROR"}, f"'{context.active_object.name}' was not placed by Place along Grease Pencil "
                        "Stroke (nothing to press)")
            return {"CANCELLED"}
        self.path.clear()
        self._dragging = False
        self._handle = None
        try:
            import gpu
            from gpu_extras.batch import batch_for_shader  # noqa: F401

            self._handle = bpy.types.SpaceView3D.draw_handler_add(self._draw, (), "WINDOW", "POST_VIEW")
        except Exception:  # drawing is a help, not a need
            self._handle = None
        self._header(context)
        context.window_manager.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def _header(self, context):
        mode = "pull" if self.strength < 0 else "press"
        context.area.header_text_set(
            f"Press: drag over the object with LMB ({mode}, radius {self.radius:.3g} m, strength "
            f"{abs(self.strength):.3g} m) · wheel: radius · X: press/pull · Esc: cancel")

    def _finish(self, context):
        if self._handle is not None:
            bpy.types.SpaceView3D.draw_handler_remove(self._handle, "WINDOW")
        context.area.header_text_set(None)
        context.area.tag_redraw()

    def _hit(self, context, event):
        region, rv3d = context.region, context.region_data
        xy = (event.mouse_region_x, event.mouse_region_y)
        origin = view3d_utils.region_2d_to_origin_3d(region, rv3d, xy)
        direction = view3d_utils.region_2d_to_vector_3d(region, rv3d, xy)
        obj = context.active_object
        M_inv = obj.matrix_world.inverted()
        o_local = M_inv @ origin
        d_local = (M_inv.to_3x3() @ direction).normalized()
        ok, loc, _, _ = obj.evaluated_get(context.evaluated_depsgraph_get()).ray_cast(o_local, d_local)
        return obj.matrix_world @ loc if ok else None

    def modal(self, context, event):
        context.area.tag_redraw()
        if event.type in {"ESC", "RIGHTMOUSE"} and event.value == "PRESS":
            self._finish(context)
            return {"CANCELLED"}
        if event.type == "WHEELUPMOUSE":
            self.radius *= 1.1
        elif event.type == "WHEELDOWNMOUSE":
            self.radius /= 1.1
        elif event.type == "X" and event.value == "PRESS":
            self.strength = -self.strength
        elif event.type == "LEFTMOUSE" and event.value == "PRESS":
            self._dragging = True
        elif event.type == "LEFTMOUSE" and event.value == "RELEASE" and self._dragging:
            self._finish(context)
            return self.execute(context) if len(self.path) else {"CANCELLED"}
        if self._dragging and event.type in {"MOUSEMOVE", "LEFTMOUSE", "INBETWEEN_MOUSEMOVE"}:
            p = self._hit(context, event)
            if p is not None and (not len(self.path) or (p - self.path[-1].co.copy()).length > 0.2 * self.radius):
                self.path.add().co = p
        self._header(context)
        return {"RUNNING_MODAL"}

    def _draw(self):
        import gpu
        from gpu_extras.batch import batch_for_shader

        if not len(self.path):
            return
        try:
            shader = gpu.shader.from_builtin("3D_UNIFORM_COLOR")
        except ValueError:
            shader = gpu.shader.from_builtin("UNIFORM_COLOR")
        pts = [tuple(p.co) for p in self.path]
        batch = batch_for_shader(shader, "LINE_STRIP" if len(pts) > 1 else "POINTS", {"pos": pts})
        shader.bind()
        shader.uniform_float("color", (1.0, 0.5, 0.1, 1.0))
        gpu.state.line_width_set(3.0)
        gpu.state.point_size_set(8.0)
        batch.draw(shader)
