// DDM commands (seed ch. 5, deformation displacement maps): layers of geometric tiles over an object's surface.
//
// `ddm.fill` — a whole-surface layer (the painting tool's fill click):
//   {"cmd":"ddm.fill","object":"ID","layer":"NAME","tile":"PATH|thorn|chain|hex|flower","layout":"rect|hex|brick",
//    "counts":[n,m] | "tile_size":s,"height":h}
//   optional (DdmLayerSpec): "base":"limit|teapot_body|uv|auto_uv" (default: the object's, ddm_default_base — what
//   the Tile Paint panel starts from), "tiles":[more tiles …] with
//   "choice":"pattern|random" and "seed":s, "map_resolution":[Ru,Rv] (or one number), "tile_scale":[sx,sy] (or one
//   number), "tile_rotate_deg":r, "tile_shift":[dx,dy].
//   tile    a generated tile (ddm_tile.h) or a mesh file (OBJ/PLY/glTF, relative to the log's folder; logged absolute,
//           relative again in saved logs, like scene.load's path), made canonical by its bounding box, its materials
//           and uvs kept (texture-mapped tiles, seed Fig. 5.12: ddm_tile_materials); "tiles" adds
//           more (same rules): cell k of a chart gets tile (k + row) mod #tiles ("pattern", seed Fig. 5.12) or one
//           drawn by a mt19937 seeded with `seed` ("random");
//   base    limit: the Loop limit surface of the object's rest mesh (OpenSubdiv Bfr), three charts per triangle;
//           teapot_body: the teapot primitive's 8 Bézier body patches as one chart, periodic around the pot;
//           uv: the rest mesh rasterised in its texture coordinates (one chart; tiles wholly outside the UV islands
//           are pruned); auto_uv: the same in automatic texture coordinates (ddm_auto_uv; tiles whose centre lies
//           between its charts are pruned too);
//   layout, counts: cells per chart (ddm_layout_cells): n × m, n ≥ 1 (≥ 2 for hex / brick), m ≥ 1;
//   tile_size  world units (object space), instead of counts: every chart gets ddm_counts_for_size of its world size
//           (ddm_fill_chart_counts), so tiles are of even size across charts; with counts an error ("tile_size");
//   height  world units (object space) per tile unit of w, along the base normal, > 0;
//   map_resolution  P/N map samples per chart edge (DdmMaps), default [9,9] (limit), [513,257] (teapot_body),
//           [1025,1025] (uv); tile_* the layer's DdmTileTransform (scale > 0, degrees, cell units).
//   The layer is sampled into P/N maps and evaluated over them on the CPU reference (ddm_layer_mesh: what the GPU
//   draws) and stored on the object (SceneObject::ddm_layers); a layer of the same name is replaced. The layer is laid
//   on the object's rest surface and carried by whatever deforms the object — FFD, DFFD rig, glTF clip, incision,
//   morph — after the DDM (core/scene/ddm_follow.h; the layer keeps the rest mesh as its host_mesh). At most
//   max_vertices tile vertices (default and at most 10,000,000), refused with the count before anything is built.
//   report.json: base (the one used), charts, tiles, tile_vertices, vertices, map_samples, ms; auto_uv adds uv_charts
//   and uv_area_distortion_p95 (DdmAutoUvStats).
// Errors: see ddm_layer_spec.h.
#pragma once

#include <optional>
#include <string>

#include "core/commands/ddm_layer_spec.h"
#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct DdmFillParams {
  std::string object;
  std::string layer;
  DdmLayerSpec spec;
};

class DdmFillCommand : public ObjectSnapshotCommand<DdmFillCommand, DdmFillParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<DdmFillParams>& schema();
  std::string label() const override;
  bool preparable() const override { return true; }  // the editor builds a fill on a worker thread

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
  std::string failure_field() const override { return "tile"; }
};

}  // namespace trispline::core
