// trispline::core::DdmLayer — one layer of tiles painted or filled over an object (seed ch. 5): its tiles, how their
// instances are laid out on the object's base surface, the base's P/N maps, its animation, and the evaluated mesh.
// Held by SceneObject::ddm_layers (immutable, shared between undo states); made by the ddm.* commands
// (core/commands/ddm_layer_spec.h) through ddm_layer_build / ddm_layer_with_instances.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ddm/ddm_base.h"
#include "core/ddm/ddm_pn_maps.h"
#include "core/ddm/ddm_tile.h"
#include "core/mesh/tri_mesh.h"
#include "core/spline/keyframes.h"

namespace trispline::core {

// Which surface of the object the tiles sit on.
enum class DdmBaseKind {
  limit,        // the Loop limit surface of the object's rest mesh, three charts per triangle (DdmSubdivBase)
  teapot_body,  // the teapot primitive's 8 Bézier body patches as one chart, periodic around (DdmSplineBase grid)
  uv,           // the rest mesh rasterised in its texture coordinates (ddm_rasterize_uv_maps), one chart
  auto_uv,      // as uv, in automatic texture coordinates (ddm_auto_uv: seams, CGAL LSCM, even texel density)
};
const char* ddm_base_name(DdmBaseKind k);  // "limit" | "teapot_body" | "uv" | "auto_uv"
// uv and auto_uv: the maps are the base (rasterised in texture space, invalid texels pruned).
inline bool ddm_base_is_uv(DdmBaseKind k) { return k == DdmBaseKind::uv || k == DdmBaseKind::auto_uv; }
// Whether a cell of a uv-based layer holds a tile: a valid sample in the cell (uv, seed §5.4.1), and for auto_uv
// also at its centre (ddm_cell_centre_valid) and no seam across it (ddm_cell_continuous).
inline bool ddm_uv_cell_kept(DdmBaseKind k, const DdmMaps& maps, const DdmInstance& cell) {
  return ddm_cell_valid(maps, cell) &&
         (k != DdmBaseKind::auto_uv || (ddm_cell_centre_valid(maps, cell) && ddm_cell_continuous(maps, cell)));
}

// Tile vertices one layer may hold (ddm.fill, ddm.paint refuse more before evaluating anything). Measured at peak
// (`replay` of a full layer writing scene.glb): ~255 bytes a vertex across the double-precision mesh, its triangles,
// the maps and the float32 export, so 10 M vertices peak near 2.6 GB; the largest shipped layer (bust_chains) holds
// 4.9 M.
inline constexpr std::size_t kMaxDdmLayerVertices = 10'000'000;
// Layout cells a uv or auto_uv layer may lay before its UV islands prune them (DdmInstance: 48 bytes a cell, so
// ~100 MB at most for the moment before pruning); the kept cells' tile vertices are then held to the vertex budget.
inline constexpr std::size_t kMaxDdmLayoutCells = 2'000'000;

struct DdmLayer {
  std::string name;                       // unique per object
  std::vector<std::string> tile_sources;  // per tile: "thorn" | "chain" | "hex" | "flower" | the tile file as logged
  std::vector<DdmTile> tiles;             // ≥ 1, canonical tile space (ddm_tile.h)
  DdmBaseKind base = DdmBaseKind::limit;
  DdmLayout layout = DdmLayout::rect;
  glm::ivec2 counts{1, 1};                 // cells per chart (n along u, m along v) when chart_counts is empty
  std::optional<double> tile_size;         // world units: the size the chart counts were derived from (unset: counts)
  std::vector<glm::ivec2> chart_counts;    // empty, or per chart of the base: its own counts (layers laid by size)
  double height = 0.1;                     // world units per tile unit of w, along the base normal
  std::optional<glm::vec3> color;          // the tiles' linear RGB in [0,1]³; unset: the object's colour
  DdmTileTransform transform;              // in the tile's texture space
  std::vector<DdmInstance> instances;      // the cells that hold a tile (order: as filled / painted)
  std::shared_ptr<const DdmBase> surface;  // the exact base (null for uv: the maps are the base)
  std::shared_ptr<const DdmMaps> maps;     // P/N maps of every chart that holds an instance (GPU + CPU reference)

  // Animation (seed §5.4.2), scene time in seconds. Metamorphosis (Eq. 5.3): morph_tiles is empty or one tile per
  // entry of `tiles`, each of the same topology; α(t) = alpha_keys (in .offset.x) or `alpha` without keys.
  std::vector<std::string> morph_sources;
  std::vector<DdmTile> morph_tiles;
  double alpha = 0.0;
  std::vector<OffsetKey> alpha_keys;
  // Texture-space offset of every tile (chart parameter units; wraps on periodic axes): offset_keys (.offset.xy) or
  // zero, plus offset_velocity·t.
  std::vector<OffsetKey> offset_keys;
  glm::dvec2 offset_velocity{0.0};
  // Keyed texture-space transform and w (seed §5.4.2), each in .offset.x, relative to the layer's own: rotate_keys
  // add degrees to transform.rotate_deg, scale_keys multiply transform.scale, w_keys multiply height (the tile's w
  // along the base normal). Empty = that part does not move.
  std::vector<OffsetKey> rotate_keys, scale_keys, w_keys;
  // Articulated tile (seed §5.5, Fig. 5.13): the layer's one tile plays this glTF clip (looping from scene time 0);
  // null: the tile is still. Not with morph tiles.
  std::shared_ptr<const DdmTileClip> tile_clip;

  // The layer at scene time 0 evaluated on the CPU reference over `maps` (what the GPU draws, object space).
  std::shared_ptr<const TriMesh> mesh;
  // The object's rest mesh (object space) the layer was laid on; null for layers of older logs' objects. When the
  // object's surface later moves away from it — a glTF clip poses it, an incision cuts and opens it — every tile
  // follows the triangle of this mesh under its root (core/scene/ddm_follow.h). Its vertex indices must survive
  // those changes (clips pose vertices in place; incisions keep the input vertices first).
  std::shared_ptr<const TriMesh> host_mesh;

  double alpha_at(double time_s) const;
  glm::dvec2 offset_at(double time_s) const;
  DdmTileTransform transform_at(double time_s) const;  // transform with rotate_keys and scale_keys applied
  double height_at(double time_s) const;               // height · w(t), world units per tile unit of w
  // α, the offset, the rotation, the scale or w changes with time, or the tile plays a clip
  bool animated() const;
  // The tiles at α (tiles themselves when there are no morph tiles).
  std::vector<DdmTile> tiles_at(double alpha) const;
  // The tiles at scene time `time_s`: the articulated tile posed (tile_clip), else tiles_at(alpha_at(time_s)).
  std::vector<DdmTile> tiles_at_time(double time_s) const;
};

// The layer's mesh at scene time `time_s`: ddm_evaluate over DdmMapsBase(maps) with tiles_at_time(t),
// height_at(t), transform_at(t) and offset_at(t). Object space, #V = Σ instance tile vertex counts. Deterministic.
// `progress` as ddm_evaluate's.
TriMesh ddm_layer_mesh(const DdmLayer& layer, double time_s, const ProgressSink* progress = nullptr);

// A copy of `layer` with `instances` (maps extended to the charts they reach, mesh at time 0): what ddm.paint makes.
// Only instances `layer` does not hold are evaluated; the vertices of those it holds (matched in order, as painting
// appends and erasing removes) are copied from its mesh — bit for bit what ddm_layer_mesh(result, 0) gives. Throws
// std::invalid_argument: an instance on a chart out of range or with a tile index out of range, no surface to sample
// new charts from (uv layers are sampled whole).
std::shared_ptr<DdmLayer> ddm_layer_with_instances(const DdmLayer& layer, std::vector<DdmInstance> instances);

// Sets maps (every chart of `instances`, at `map_resolution`; a uv layer keeps its maps) and mesh of a layer whose
// other fields are set. `progress` (may be null): the maps, then the evaluation, reported in [0, 1] on the calling
// thread. Throws as ddm_sample_maps and ddm_evaluate; OperationCancelled through `progress` (the layer is then
// half-made: drop it).
void ddm_layer_finish(DdmLayer& layer, glm::ivec2 map_resolution, const ProgressSink* progress = nullptr);

}  // namespace trispline::core
