// `ddm.paint` — a brush stroke that adds tiles to (or erases them from) a DDM layer (seed ch. 5). Fields: declared in
// ddm_paint.cpp (ParamSchema), listed in docs/commands.md; the stroke and radius_px are viewport pixels (top-left
// origin) of the line's "camera", else of the last camera.set.
// The candidate cells are every cell of the layer's layout (ddm_layout_cells(layout, counts, #charts), or each chart's
// own counts for a layer laid by tile_size, DdmLayer::chart_counts) on every chart of its base (uv bases: cells the
// fill would prune are skipped, ddm_uv_cell_kept); at most kMaxDdmPaintCandidates of them in all, weighed from the
// counts before any is made (else CommandError "counts" or "tile_size"). A cell is touched when its centre — the
// base point S(chart, cell centre) (w = 0), through the object's transform — (1) projects within radius_px of the
// stroke polyline, (2) lies in front of the eye with its normal facing the camera and (3) is not occluded: the first
// hit of the eye ray towards it among the visible objects' world meshes is none, lies within a tolerance of it
// (2 × the gap between the limit point and the flat face on a limit base — the Loop limit surface lies inside a
// coarse cage —, 1 % of the object's diagonal otherwise), or — on a limit base — is on the object itself on a
// triangle sharing a vertex with the cell's face (ddm_paint_cells).
// Painting adds the touched cells the layer does not hold (appended in chart / layout order; with several tiles each
// cell gets the tile ddm.fill's "pattern" gives it, ddm_paint_tile_index); erase = true removes the touched cells it
// holds; cells already as asked change nothing (no error). The layer is rebuilt with ddm_layer_with_instances (maps
// extended, mesh re-evaluated); undo restores the previous layer pointer (the instance set exactly).
// When the object has no layer of that name, painting creates it (empty, then painted) from ddm.fill's fields, all
// optional here (DdmLayerSpec, ddm_layer_spec.h); they are ignored when the layer exists (it keeps its own) and
// logged back only when the line named any of them. Erasing needs the layer.
// report.json stats: created (the layer was made by this stroke), touched, cells_added, cells_removed, tiles
// (instances after), vertices (the layer's mesh), ms.
// Errors (CommandError, field named; the scene is unchanged): unknown object, or one with an FFD / DFFD / clip
// ("object"); empty layer name, erasing from a layer that does not exist ("layer"); the new layer's fields as
// ddm.fill ("tile", "counts", "base", …); no points, non-finite points, a stroke that touches no
// visible cell ("stroke"); radius_px ≤ 0 or not finite ("radius_px"); no camera.set and no "camera" ("camera");
// more than max_vertices tile vertices (default and at most 10,000,000; "stroke").
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "core/commands/ddm_layer_spec.h"
#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/scene/camera.h"

namespace trispline::core {

// Cells of a layer's layout (all charts) a ddm.paint stroke may choose from: each is evaluated on the base and kept
// with its point and normal (~250 bytes), so 2 M cost ~0.5 GB and a few seconds; more is refused before any is made.
inline constexpr std::size_t kMaxDdmPaintCandidates = 2'000'000;

// The cells of `layer` (on `object`, in `scene`) that a stroke touches, as described above: layout cells in chart /
// layout order, each with tile = ddm_paint_tile_index(its index and row in its chart, #tiles). Pure; TBB over charts
// and rays; deterministic.
// Throws std::invalid_argument: a layer without a surface or maps, non-finite world meshes.
std::vector<DdmInstance> ddm_paint_cells(const Scene& scene, const SceneObject& object, const DdmLayer& layer,
                                         const Camera& camera, const std::vector<glm::dvec2>& stroke_px,
                                         double radius_px);

// The tile painting gives a cell: `cell_index` is its position in ddm_layout_cells' list of one chart, `row` its row
// there; 0 for one tile, else (cell_index + row) mod tile_count — ddm.fill's "pattern" choice, so a painted cell gets
// the tile a pattern fill gives it whatever the stroke order.
int ddm_paint_tile_index(int cell_index, int row, int tile_count);

struct DdmPaintParams {
  std::string object, layer;
  DdmLayerSpec spec;               // the layer to create when the object has none of that name
  bool spec_named = false;         // the line named any of spec's fields (they are logged back only then)
  std::vector<glm::dvec2> stroke;  // #S × 2 viewport pixels
  double radius_px = 0.0;
  bool erase = false;
  std::optional<Camera> camera;  // the view the stroke was drawn in; unset = the scene's camera
};

struct DdmPaintCommand : ObjectSnapshotCommand<DdmPaintCommand, DdmPaintParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
