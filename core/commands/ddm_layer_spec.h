// How a DDM layer (seed ch. 5: Eq. 5.1–5.2, §5.3) is made from a log line: DdmLayerSpec, the fields ddm.fill and
// ddm.paint share, declared once, and the construction both commands run (tiles loaded, base built, cells laid out,
// maps sampled, tiles evaluated), with the estimate the Tile Paint panel shows before a Fill.
// Errors (CommandError, field named; the scene is unchanged): unknown object / a base the mesh
// cannot give (non-manifold, no triangles, no uvs) ("object" / "base"); unknown tile, unreadable or bad tile file
// ("tile" / "tiles"); bad layout ("layout"); counts out of range or too many vertices ("counts"); tile_size ≤ 0, with
// counts, or too many vertices ("tile_size"); neither counts nor tile_size on ddm.fill ("counts"); height ≤ 0 or not
// finite ("height"); teapot_body on another object ("base"); no such layer ("layer"); name empty or taken ("name").
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ddm/ddm_auto_uv.h"
#include "core/ddm/ddm_layer.h"
#include "core/params/params.h"
#include "core/scene/scene.h"
#include "core/spline/progress.h"

namespace trispline::core {

// How to make a layer: ddm.fill's fields, and ddm.paint's when it creates its layer (ddm_layer_schema()).
struct DdmLayerSpec {
  // "tile" (tiles[0]) and "tiles" (the rest): generated kinds (is_generated_ddm_tile) or mesh files, as given.
  std::vector<std::string> tiles{"thorn"};
  // Per tile: the file resolved against the log's folder by parse (lines are written back with it); empty for
  // generated tiles, and for tiles not read from a line (then the name is used as it is).
  std::vector<std::filesystem::path> tile_paths;
  std::string tile_up = "z";             // the tile files' axis that stands up from the surface: "x" | "y" | "z"
  std::optional<std::string> tile_clip;  // the glTF tile's animation to play (articulated); "" = its first
  std::string choice = "pattern";        // with several tiles: "pattern" | "random"
  std::int64_t seed = 0;                 // "random"'s mt19937 seed
  DdmLayout layout = DdmLayout::rect;
  std::optional<glm::ivec2> counts;  // cells per chart; unset: from tile_size, or [1, 1] without it
  std::optional<double> tile_size;   // world units: cells per chart from each chart's world size (not with counts)
  std::optional<std::int64_t> max_vertices;  // refuse more tile vertices than this; unset = kMaxDdmLayerVertices
  double height = 0.1;
  // unset: the object's own (ddm_default_base), the base the Tile Paint panel starts from
  std::optional<DdmBaseKind> base;
  std::optional<glm::ivec2> map_resolution;  // unset = the base's default
  DdmTileTransform transform;                // "tile_scale", "tile_rotate_deg", "tile_shift"
  std::optional<glm::vec3> color;            // the layer's linear RGB in [0, 1]; unset = the object's
};

// DdmLayerSpec's fields, declared once: `fill` = ddm.fill's (tile, layout, height and counts or tile_size required),
// else
// ddm.paint's (every field optional, with the defaults above).
const ParamSchema<DdmLayerSpec>& ddm_layer_schema(bool fill);

// The "object" field of the commands that make a layer (ddm.fill, ddm.paint).
inline constexpr const char* kDdmLayerObjectHelp =
    "The object; tiles lie on its rest surface and ride on its deformation (FFD, DFFD, clip, incision)";

// Tile i of a line's list (tiles / tile_paths, morph tiles): the resolved file when parse found one, else the name.
std::string ddm_tile_file(const std::vector<std::string>& names, const std::vector<std::filesystem::path>& paths,
                          std::size_t i);
// A tile a line names, resolved against the log's folder: empty for generated kinds and for "".
std::filesystem::path resolve_ddm_tile(const std::string& name, const CommandContext& ctx);
// Tiles from `first` on as a JSON array of ddm_tile_file's.
nlohmann::json ddm_tile_files(const std::vector<std::string>& names, const std::vector<std::filesystem::path>& paths,
                              std::size_t first);
// Reads a tile field of a line — one name (`list` false: a JSON string) or a JSON array of names — and appends each
// name and its resolve_ddm_tile path to `names` / `paths` (tiles, morph tiles). Throws CommandError naming `field`
// (params::fail): a value of another type, or an empty name.
void append_ddm_tiles(const nlohmann::json& v, const std::string& field, bool list, const CommandContext& ctx,
                      std::vector<std::string>& names, std::vector<std::filesystem::path>& paths);

// Loads a tile: a generated kind or a mesh file turned so that its axis `up_axis` (0 x, 1 y, 2 z) is w, made
// canonical. Throws CommandError (`field`) on failure.
DdmTile load_ddm_tile(const std::string& name, const std::filesystem::path& path, const char* field, int up_axis = 2);

// A new layer `name` from `spec` on `object` (its rest mesh, object space): tiles loaded, base built, every layout
// cell filled (`fill`) or none, maps sampled, mesh evaluated. `progress` (may be null) is reported in [0, 1] and
// checked between chunks of the evaluation. Throws CommandError naming the field (see ddm.fill); OperationCancelled
// through `progress`.
std::shared_ptr<DdmLayer> make_ddm_layer(const SceneObject& object, const std::string& name, const DdmLayerSpec& spec,
                                         bool fill, const ProgressSink* progress = nullptr);

// The cells per chart a layer of `spec` gets on a base of `charts` charts: `counts` on every chart, or with tile_size
// ddm_counts_for_size of each chart's world size — ddm_limit_chart_sizes(base_mesh) for a limit base,
// ddm_uv_chart_size(base_mesh) for uv and auto_uv (the unwrapped mesh), ddm_chart_size(*surface) otherwise. Throws
// CommandError ("tile_size", or "counts" without it): cells × `tile_vertices` (the largest tile's vertex count) over
// spec.max_vertices (default and at most kMaxDdmLayerVertices) — counted before any cell is made, the message giving
// both numbers; for uv and auto_uv bases only cells over kMaxDdmLayoutCells, since make_ddm_layer counts their tile
// vertices after the cells off the UV islands are pruned (before any tile is evaluated). `tile_vertices` = 0 (a
// layer ddm.paint makes: its cells are candidates, tiles come only where painted) weighs the cells alone.
std::vector<glm::ivec2> ddm_fill_chart_counts(const DdmLayerSpec& spec, DdmBaseKind base, const TriMesh& base_mesh,
                                              const DdmBase* surface, int charts, std::size_t tile_vertices);

// The base a layer on `object` gets when its line names none, and the Tile Paint panel's first choice: the teapot
// primitive's body patches (teapot_body), the
// mesh's own texture coordinates when every vertex has one (uv), else automatic ones (auto_uv); limit on request.
DdmBaseKind ddm_default_base(const SceneObject& object);

// ddm_auto_uv of `mesh` (the auto_uv base), kept for the last few meshes (a mesh is immutable and shared between
// undo states, so its pointer is its identity): the panel's estimate and the Fill after it unwrap once. Thread-safe.
// Throws as ddm_auto_uv.
std::shared_ptr<const TriMesh> ddm_auto_uv_mesh(const std::shared_ptr<const TriMesh>& mesh,
                                                DdmAutoUvStats* stats = nullptr);

// What ddm.fill of `spec` on `object` would make, from the same layout code without sampling maps or evaluating tiles
// (the Tile Paint panel shows it before Fill): charts, cells, and tile vertices = cells × the largest tile's vertex
// count (exact for one tile). For uv and auto_uv bases the cells are counted before pruning (cells outside the UV
// islands are dropped when the maps exist), so `upper_bound` is set. Throws CommandError as ddm.fill ("tile", "base",
// "tile_size", "counts").
struct DdmFillEstimate {
  std::size_t charts = 0, cells = 0, tile_vertices = 0;
  bool upper_bound = false;
};
DdmFillEstimate ddm_fill_estimate(const SceneObject& object, const DdmLayerSpec& spec);

// `object` with `layer` added, or replacing the layer of the same name.
SceneObject with_ddm_layer(const SceneObject& object, std::shared_ptr<const DdmLayer> layer);
// The object's layer called `name`; throws CommandError ("layer") when there is none.
std::shared_ptr<const DdmLayer> find_ddm_layer(const SceneObject& object, const std::string& name);
// The "layer" a command may create (ddm.fill, ddm.paint): a valid name (object_name_error). Throws naming "layer".
void check_ddm_layer_name(const std::string& name);

}  // namespace trispline::core
