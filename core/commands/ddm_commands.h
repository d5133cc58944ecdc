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
// `ddm.bake` — a layer as an ordinary mesh object (for export and for use elsewhere):
//   {"cmd":"ddm.bake","object":"ID","layer":"NAME","name":"NEW_ID"}
//   optional "frame":F (default: the layer at scene time 0) — the layer's animation at that timeline frame.
//   The new object's mesh is the layer's in world units (the object's transform applied), identity transform, the
//   object's colour; instances one after another, each in the tile's own vertex order. scene.glb then holds it.
//   report.json: vertices, triangles.
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

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/ddm/ddm_auto_uv.h"
#include "core/ddm/ddm_layer.h"

namespace trispline::core {

// How to make a layer: ddm.fill's fields, and ddm.paint's when it creates its layer (ddm_layer_schema()).
struct DdmLayerSpec {
  // "tile" (tiles[0]) and "tiles" (the rest): generated kinds (is_generated_ddm_tile) or mesh files, as given.
  std::vector<std::string> tiles{"thorn"};
  // Per tile: the file resolved against the log's folder by parse (lines are written back with it); empty for
  // generated tiles, and for tiles not read from a line (then the name is used as it is).
  std::vector<std::filesystem::path> tile_paths;
  std::string choice = "pattern";  // with several tiles: "pattern" | "random"
  std::int64_t seed = 0;           // "random"'s mt19937 seed
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

// Tile i of a line's list (tiles / tile_paths, morph tiles): the resolved file when parse found one, else the name.
std::string ddm_tile_file(const std::vector<std::string>& names, const std::vector<std::filesystem::path>& paths,
                          std::size_t i);
// A tile a line names, resolved against the log's folder: empty for generated kinds and for "".
std::filesystem::path resolve_ddm_tile(const std::string& name, const CommandContext& ctx);

// Loads a tile: a generated kind or a mesh file made canonical. Throws CommandError (`field`) on failure.
DdmTile load_ddm_tile(const std::string& name, const std::filesystem::path& path, const char* field);

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
// both numbers. `tile_vertices` = 0 (a
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

struct DdmBakeParams {
  std::string object, layer;
  std::string name;             // the new object
  std::optional<double> frame;  // timeline frame of the layer's animation; unset = scene time 0
};

class DdmBakeCommand : public DeclaredCommand<DdmBakeCommand, DdmBakeParams, SnapshotCommand> {
 public:
  using DeclaredCommand::DeclaredCommand;
  static const ParamSchema<DdmBakeParams>& schema();
  std::string label() const override;
  bool preparable() const override { return true; }  // the editor bakes on a worker thread

 protected:
  std::string target() const override { return p_.name; }
  std::optional<SceneObject> build(const Scene& scene) override;
};

// {"cmd":"ddm.color","object":ID,"layer":NAME,"color":[r,g,b] | null}: sets a layer's own colour (linear RGB, each in
// [0, 1]) or, with null, makes it take its object's colour again. Only the colour changes (the tiles are shared).
// Errors (field named, scene unchanged): unknown object, no such layer, a colour out of range.
struct DdmColorParams {
  std::string object, layer;
  std::optional<glm::vec3> color;  // unset: "color": null (the object's colour again)
};

class DdmColorCommand : public ObjectSnapshotCommand<DdmColorCommand, DdmColorParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<DdmColorParams>& schema();
  std::string label() const override;

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

// {"cmd":"ddm.remove","object":ID,"layer":NAME}: deletes a tile layer (its tiles, maps and animation); undo brings it
// back as it was. Errors (field named, scene unchanged): unknown object, no such layer.
struct DdmRemoveParams {
  std::string object, layer;
};

class DdmRemoveCommand : public ObjectSnapshotCommand<DdmRemoveCommand, DdmRemoveParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<DdmRemoveParams>& schema();
  std::string label() const override;

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
