"""Object ▸ trispline ▸ Tile Fill: `ddm.fill` by tile size, then `ddm.bake` (seed ch. 5), in Blender.

Covers the active mesh with tiles: a tile object (the other selected mesh, or one named by Tile object) or one of
trispline's generated tiles. The tile object's local X and Y span a cell and its local Z points away from the surface
(ddm.fill makes a tile canonical by its bounding box); it is written to a temporary OBJ file, as ddm.fill reads tiles
from files. The surface goes in as world-space triangles (mesh.set), so tile size and height are metres. The tiles
become one new mesh object with the tile object's materials (a generated tile: the material "trispline tiles").
"""

import os
import tempfile

import bpy

from . import convert
from .module import module_or_report

SURFACE, LAYER, TILES = "surface", "tiles", "tiles"

TILES_ITEMS = [
    ("OBJECT", "Tile object", "The other selected mesh, or the one named in Tile object"),
    ("THORN", "Thorn", "trispline's generated thorn (626 vertices)"),
    ("FLOWER", "Flower", "trispline's generated flower (the thorn's topology)"),
    ("CHAIN", "Chain", "two interlocked links (1,152 vertices)"),
    ("HEX", "Hex", "a hexagonal slab, for the Hex layout"),
]


def write_obj(path, V, F):
    """A triangle mesh as OBJ (v and f lines only, 1-based), coordinates as they are."""
    with open(path, "w", encoding="utf-8") as f:
        f.write("# trispline Blender add-on: a tile object, local coordinates\n")
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V.tolist())
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F.tolist())


class OBJECT_OT_trispline_tile_fill(bpy.types.Operator):
    """Cover the active mesh with tiles of a given size (trispline ddm.fill), as a new mesh object"""

    bl_idname = "object.trispline_tile_fill"
    bl_label = "Tile Fill"
    bl_options = {"REGISTER", "UNDO"}

    tile: bpy.props.EnumProperty(name="Tile", items=TILES_ITEMS, default="OBJECT",
                                 description="The tile laid in every cell")
    tile_object: bpy.props.StringProperty(
        name="Tile object", default="",
        description="The mesh used as tile (local X, Y: the cell; local Z: away from the surface); empty: the "
        "selected mesh that is not active")
    tile_size: bpy.props.FloatProperty(name="Tile size (m)", default=0.25, min=1e-4, soft_max=10.0, unit="LENGTH",
                                       description="Tile width on the surface, in metres")
    height: bpy.props.FloatProperty(name="Height (m)", default=0.1, min=1e-5, soft_max=10.0, unit="LENGTH",
                                    description="Metres along the surface normal per tile unit of height")
    layout: bpy.props.EnumProperty(
        name="Layout", default="RECT",
        items=[("RECT", "Grid", "Rows and columns"), ("BRICK", "Brick", "Odd rows shifted by half a cell"),
               ("HEX", "Hex", "Rows 0.75 of a cell apart, odd rows shifted")])
    base: bpy.props.EnumProperty(
        name="Base", default="AUTO_UV",
        items=[("AUTO_UV", "Automatic UVs", "Automatic texture coordinates (LSCM charts): tiles of even size on "
                "any mesh"),
               ("LIMIT", "Limit surface", "The Loop limit surface, three charts per triangle (a coarse cage)")])
    rotation: bpy.props.FloatProperty(name="Rotation (°)", default=0.0, soft_min=-180.0, soft_max=180.0,
                                      description="Rotation of the tile in its cell, degrees counter-clockwise")

    @classmethod
    def poll(cls, context):
        return convert.active_mesh_in_object_mode(context)

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "tile")
        if self.tile == "OBJECT":
            layout.prop_search(self, "tile_object", bpy.data, "objects")
        for name in ("tile_size", "height", "layout", "base", "rotation"):
            layout.prop(self, name)

    def _tile_object(self, context, surface):
        if self.tile_object:
            obj = bpy.data.objects.get(self.tile_object)
            return obj if obj is not None and obj.type == "MESH" else None
        others = [o for o in context.selected_objects if o.type == "MESH" and o != surface]
        return others[0] if len(others) == 1 else None

    def execute(self, context):
        mod = module_or_report(self, context)
        if mod is None:
            return {"CANCELLED"}
        surface = context.active_object
        dg = context.evaluated_depsgraph_get()
        tile_obj = None
        if self.tile == "OBJECT":
            tile_obj = self._tile_object(context, surface)
            if tile_obj is None:
                self.report({"ERROR"}, "Tile object: select the tile mesh and then the surface (active), name a "
                            "mesh in Tile object, or choose a generated tile")
                return {"CANCELLED"}
        V, F = convert.first_use_order(*convert.evaluated_mesh_arrays(surface, dg))
        scene = mod.Scene()
        with tempfile.TemporaryDirectory(prefix="trispline_tile_") as tmp:
            tile = self.tile.lower()
            if tile_obj is not None:
                Vt, Ft = convert.evaluated_mesh_arrays(tile_obj, dg, world=False)
                Vt = Vt * tile_obj.matrix_world.to_scale()  # the tile as it looks, without its placement
                tile = os.path.join(tmp, "tile.obj")
                write_obj(tile, Vt, Ft)
            try:
                convert.add_mesh(scene, SURFACE, convert.to_trispline(V), F)
                fill = scene.run({"cmd": "ddm.fill", "object": SURFACE, "layer": LAYER, "tile": tile,
                                  "layout": self.layout.lower(), "tile_size": self.tile_size, "height": self.height,
                                  "base": self.base.lower(), "tile_rotate_deg": self.rotation})
                scene.run({"cmd": "ddm.bake", "object": SURFACE, "layer": LAYER, "name": TILES})
            except (mod.CommandError, ValueError) as e:
                self.report({"ERROR"}, f"{e}")
                return {"CANCELLED"}
        Vb = convert.to_blender(scene.vertices(TILES))
        centre = convert.bbox_centre(Vb)
        mesh = convert.new_mesh(f"{surface.name} tiles", Vb - centre, scene.faces(TILES))
        obj = convert.link_object(context, mesh.name, mesh, location=centre)
        if tile_obj is not None and len(tile_obj.material_slots):
            convert.copy_materials(tile_obj, obj)
        else:
            obj.data.materials.append(convert.material("trispline tiles", (0.55, 0.35, 0.2)))
        st = fill["stats"]
        self.report({"INFO"}, f"Tile Fill: {st.get('tiles')} tiles, {len(Vb)} vertices on '{surface.name}' "
                    f"({st.get('charts')} charts, {fill['ms']:.0f} ms)")
        return {"FINISHED"}
