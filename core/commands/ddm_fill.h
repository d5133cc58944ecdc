// `ddm.fill` — a whole-surface layer of geometric tiles over an object (seed ch. 5, deformation displacement maps;
// the Tile Paint tool's Fill). Its fields are declared once in ddm_layer_spec.cpp / ddm_fill.cpp (ParamSchema) and
// listed in docs/commands.md; what the declaration cannot say:
//   tiles   a generated tile (ddm_tile.h) or a mesh file made canonical by its bounding box, its materials and uvs
//           kept (texture-mapped tiles, seed Fig. 5.12: ddm_tile_materials); with several, cell k of a chart gets
//           tile (k + row) mod #tiles ("pattern") or one drawn by a mt19937 seeded with `seed` (seed Fig. 5.12);
//   base    limit: the Loop limit surface of the rest mesh (OpenSubdiv Bfr), three charts per triangle; teapot_body:
//           the teapot primitive's 8 Bézier body patches as one chart, periodic around the pot; uv: the rest mesh
//           rasterised in its texture coordinates (one chart; tiles wholly outside the UV islands are pruned);
//           auto_uv: the same in automatic texture coordinates (ddm_auto_uv; tiles whose centre lies between its
//           charts are pruned too); unset: the object's own (ddm_default_base, what the Tile Paint panel starts from);
//   tile_size  instead of counts: every chart gets ddm_counts_for_size of its world size (ddm_fill_chart_counts), so
//           tiles are of even size across charts.
// The layer is sampled into P/N maps and evaluated over them on the CPU reference (ddm_layer_mesh: what the GPU
// draws) and stored on the object (SceneObject::ddm_layers); a layer of the same name is replaced. It is laid on the
// object's rest surface and carried by whatever deforms the object — FFD, DFFD rig, glTF clip, incision, morph —
// after the DDM (core/scene/ddm_follow.h; the layer keeps the rest mesh as its host_mesh). At most max_vertices tile
// vertices (default and at most 10,000,000), refused with the count before anything is built.
// report.json: base (the one used), charts, tiles, tile_vertices, vertices, map_samples, ms; auto_uv adds uv_charts
// and uv_area_distortion_p95 (DdmAutoUvStats). Errors: see ddm_layer_spec.h.
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
  static Schema declare();
  bool preparable() const override { return true; }  // the editor builds a fill on a worker thread

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
