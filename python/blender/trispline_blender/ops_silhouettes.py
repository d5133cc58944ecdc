"""Object ▸ trispline ▸ Silhouettes from Volume: `volume.load` + `volume.silhouettes` (seed ch. 7) in Blender.

Loads a NIfTI file (or a DICOM series / .inv3 project) as a trivariate B-spline, extracts the silhouette curves of
its iso-surface for a camera (trispline.silhouettes: Newton on D = c, G·V = 0, traced), and makes one curve object
with one POLY spline per polyline. Volumes are millimetres, turned so the patient's superior axis is up (volume.load's
axes superior_up, Y-up in trispline, Z-up here); Scale says how many metres a millimetre is.
"""

import json
import os

import bpy
import numpy as np

from . import convert
from .module import module_or_report
from .ops_place import VIEWS

VOLUME = "volume"


def volume_box(stats):
    """The volume's bounding box (trispline world millimetres) from volume.load's report: dims, index_to_world."""
    dims = np.asarray(stats["dims"], dtype=np.float64)
    M = np.asarray(stats["index_to_world"], dtype=np.float64)
    corners = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], dtype=np.float64) * (dims - 1)
    W = corners @ M[:3, :3].T + M[:3, 3]
    return W.min(axis=0), W.max(axis=0)


class OBJECT_OT_trispline_silhouettes(bpy.types.Operator):
    """Silhouette curves of a CT/MRI volume's iso-surface (NIfTI, DICOM, .inv3), as a curve object (trispline
    volume.silhouettes)"""

    bl_idname = "object.trispline_silhouettes"
    bl_label = "Silhouettes from Volume"
    bl_options = {"REGISTER", "UNDO"}

    filepath: bpy.props.StringProperty(name="Volume file", subtype="FILE_PATH", default="",
                                       description="NIfTI (.nii, .nii.gz), a DICOM .dcm or an InVesalius .inv3")
    filter_glob: bpy.props.StringProperty(default="*.nii;*.nii.gz;*.dcm;*.inv3", options={"HIDDEN"})
    use_iso: bpy.props.BoolProperty(name="Set iso-level", default=False,
                                    description="Use Iso-level; off: 226 HU for CT, else Otsu's threshold")
    iso: bpy.props.FloatProperty(name="Iso-level", default=226.0,
                                 description="Iso-level in the volume's own units (HU for CT)")
    view: bpy.props.EnumProperty(
        name="View", default="AUTO",
        items=[v if v[0] != "TOP" else ("FRONT", "Front", "A camera in front of the volume (Blender -Y)")
               for v in VIEWS],
        description="The camera the silhouettes are seen from")
    scale: bpy.props.FloatProperty(name="Scale (m per mm)", default=0.001, min=1e-6, soft_max=1.0, precision=4,
                                   description="Metres per millimetre of the volume (0.001: true size)")
    at_cursor: bpy.props.BoolProperty(name="At 3D cursor", default=True,
                                      description="Centre the volume's box at the 3D cursor; off: the file's "
                                      "millimetres, scaled")
    hidden: bpy.props.EnumProperty(
        name="Hidden parts", default="REMOVE",
        items=[("REMOVE", "Remove", "Drop the parts hidden behind the iso-surface (the splines are cut there)"),
               ("SHOW", "Show", "Keep the hidden parts")])
    subdivision: bpy.props.IntProperty(name="Subdivision", default=1, min=1, max=4,
                                       description="Newton seeds per singleton axis")
    line_radius: bpy.props.FloatProperty(name="Line radius (mm)", default=0.6, min=0.0, soft_max=5.0,
                                         description="Bevel radius of the curves, in the volume's millimetres")

    @classmethod
    def poll(cls, context):
        return context.mode == "OBJECT"

    def invoke(self, context, event):
        if self.filepath:
            return self.execute(context)
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def _camera(self, context, lo, hi, to_mm):
        cam = None
        if self.view in ("AUTO", "VIEWPORT"):
            cam = convert.camera_from_viewport(context)
        if cam is None and self.view in ("AUTO", "CAMERA") and context.scene.camera is not None:
            cam = convert.camera_from_object(context.scene, context.scene.camera)
        if cam is None and self.view in ("VIEWPORT", "CAMERA"):
            return None
        if cam is not None:  # Blender metres (as trispline axes) → the volume's millimetres
            cam = dict(cam, eye=to_mm(cam["eye"]).tolist(), target=to_mm(cam["target"]).tolist())
            return cam
        c, r = 0.5 * (lo + hi), 0.5 * float(np.linalg.norm(hi - lo))
        fov = 30.0
        dist = r / np.sin(np.radians(fov / 2.0))
        return {"eye": [float(c[0]), float(c[1]), float(c[2] + dist)], "target": c.tolist(), "up": [0.0, 1.0, 0.0],
                "fov_deg": fov, "viewport": [1000, 1000]}

    def execute(self, context):
        mod = module_or_report(self, context)
        if mod is None:
            return {"CANCELLED"}
        path = bpy.path.abspath(self.filepath)
        if not path or not os.path.exists(path):
            self.report({"ERROR"}, f"Volume file: '{self.filepath}' does not exist")
            return {"CANCELLED"}
        scene = mod.Scene()
        load = {"cmd": "volume.load", "path": path, "name": VOLUME}
        if self.use_iso:
            load["iso"] = self.iso
        try:
            entry = scene.run(load)
            lo, hi = volume_box(entry["stats"])
            centre_b = convert.to_blender(0.5 * (lo + hi))[0]
            offset_b = (np.array(context.scene.cursor.location) - centre_b * self.scale) if self.at_cursor \
                else np.zeros(3)
            offset_t = convert.to_trispline(offset_b)[0]
            cam = self._camera(context, lo, hi, lambda q: (np.asarray(q) - offset_t) / self.scale)
            if cam is None:
                self.report({"ERROR"}, f"View '{self.view}': no perspective viewport or camera")
                return {"CANCELLED"}
            lines = [entry["command"],
                     scene.run(dict(cmd="camera.set", **cam))["command"],
                     scene.run({"cmd": "volume.silhouettes", "object": VOLUME, "hidden": self.hidden.lower(),
                                "subdivision": self.subdivision, "style": "plain"})["command"]]
            polylines = mod.silhouettes(scene, VOLUME, camera=cam, details=True)
        except (mod.CommandError, ValueError) as e:
            self.report({"ERROR"}, f"{e}")
            return {"CANCELLED"}

        name = os.path.basename(path).split(".")[0] + " silhouettes"
        curve = bpy.data.curves.new(name, "CURVE")
        curve.dimensions = "3D"
        curve.bevel_depth = self.line_radius * self.scale
        curve.bevel_resolution = 1
        points = 0
        for pl in polylines:
            P = convert.to_blender(pl["points"]) * self.scale + offset_b
            runs = [P]
            if self.hidden == "REMOVE":  # split at the hidden parts
                vis = np.asarray(pl["visible"], dtype=bool)
                edges = np.flatnonzero(np.diff(np.concatenate(([0], vis.astype(np.int8), [0]))))
                runs = [P[a:b] for a, b in zip(edges[::2], edges[1::2])]
            for run in runs:
                if len(run) < 2:
                    continue
                spline = curve.splines.new("POLY")
                spline.points.add(len(run) - 1)
                spline.points.foreach_set("co", np.column_stack((run, np.ones(len(run)))).astype(np.float32).ravel())
                points += len(run)
        obj = convert.link_object(context, name, curve)
        obj.data.materials.append(convert.material("trispline silhouettes", (0.02, 0.02, 0.025)))
        obj["trispline_log"] = json.dumps(lines)
        self.report({"INFO"}, f"Silhouettes: {len(curve.splines)} curves, {points} points")
        return {"FINISHED"}
