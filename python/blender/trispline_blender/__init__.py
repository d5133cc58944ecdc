"""trispline for Blender: sketch placement, pressing, tile fill and volume silhouettes as Object-menu operators.

The operators (docs/python.md, "Blender add-on") turn Blender meshes into a trispline scene through the `trispline`
Python module, run the very commands the editor's tools run (docs/commands.md), and write the results back as
ordinary meshes and curves with their materials. Each operator is one Blender undo step.

  Object ▸ trispline ▸ Place along Grease Pencil Stroke   place.sketch     (ops_place.py)
                      ▸ Press                              lattice.press    (ops_press.py, modal)
                      ▸ Tile Fill                          ddm.fill + bake  (ops_tiles.py)
                      ▸ Silhouettes from Volume            volume.load + silhouettes (ops_silhouettes.py)

Coordinates: Blender is Z-up, trispline Y-up, both right-handed; (x, y, z) in Blender is (x, z, -y) in trispline
(convert.py), as glTF exporters convert.
"""

bl_info = {
    "name": "trispline",
    "author": "trispline",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D ▸ Object ▸ trispline",
    "description": "Sketch placement, pressing, tile fill and volume silhouettes from trivariate B-splines",
    "doc_url": "https://github.com/trispline/trispline/blob/main/docs/python.md#blender-add-on",
    "category": "Object",
}

if "bpy" in locals():  # F8 / Reload Scripts: reload the submodules too
    import importlib

    for _m in (module, convert, ops_place, ops_press, ops_tiles, ops_silhouettes):  # noqa: F821
        importlib.reload(_m)
else:
    from . import module, convert, ops_place, ops_press, ops_tiles, ops_silhouettes  # noqa: F401

import bpy

_classes = (
    module.TrisplinePreferences,
    ops_press.TrisplinePathPoint,
    ops_place.OBJECT_OT_trispline_place,
    ops_press.OBJECT_OT_trispline_press,
    ops_tiles.OBJECT_OT_trispline_tile_fill,
    ops_silhouettes.OBJECT_OT_trispline_silhouettes,
)


class VIEW3D_MT_trispline(bpy.types.Menu):
    """The add-on's submenu of View3D ▸ Object."""

    bl_label = "trispline"
    bl_idname = "VIEW3D_MT_trispline"

    def draw(self, context):
        layout = self.layout
        layout.operator_context = "INVOKE_REGION_WIN"
        layout.operator(ops_place.OBJECT_OT_trispline_place.bl_idname, icon="GREASEPENCIL")
        layout.operator(ops_press.OBJECT_OT_trispline_press.bl_idname, icon="SPHERECURVE")
        layout.operator(ops_tiles.OBJECT_OT_trispline_tile_fill.bl_idname, icon="MOD_ARRAY")
        layout.operator(ops_silhouettes.OBJECT_OT_trispline_silhouettes.bl_idname, icon="OUTLINER_OB_VOLUME")


def _menu(self, context):
    self.layout.separator()
    self.layout.menu(VIEW3D_MT_trispline.bl_idname)


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.utils.register_class(VIEW3D_MT_trispline)
    bpy.types.VIEW3D_MT_object.append(_menu)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(_menu)
    bpy.utils.unregister_class(VIEW3D_MT_trispline)
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
