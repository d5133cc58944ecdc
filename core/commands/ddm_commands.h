// DDM commands (seed ch. 5, deformation displacement maps): layers of geometric tiles over an object's surface.
//
// `ddm.fill` — a whole-surface layer (the painting tool's fill click):
//   {"cmd":"ddm.fill","object":"ID","layer":"NAME","tile":"PATH|thorn|chain|hex|flower","layout":"rect|hex|brick",
//    "counts":[n,m],"height":h}
//   optional (DdmLayerSpec): "base":"limit|teapot_body|uv" (default "limit"), "tiles":[more tiles …] with
//   "choice":"pattern|random" and "seed":s, "map_resolution":[Ru,Rv] (or one number), "tile_scale":[sx,sy] (or one
//   number), "tile_rotate_deg":r, "tile_shift":[dx,dy].
//   tile    a generated tile (ddm_tile.h) or a mesh file (OBJ/PLY/glTF, relative to the log's folder; logged absolute,
//           relative again in saved logs, like scene.load's path), made canonical by its bounding box; "tiles" adds
//           more (same rules): cell k of a chart gets tile (k + row) mod #tiles ("pattern", seed Fig. 5.12) or one
//           drawn by a mt19937 seeded with `seed` ("random");
//   base    limit: the Loop limit surface of the object's rest mesh (OpenSubdiv Bfr), three charts per triangle;
//           teapot_body: the teapot primitive's 8 Bézier body patches as one chart, periodic around the pot;
//           uv: the rest mesh rasterised in its texture coordinates (one chart; tiles wholly outside the UV islands
//           are pruned);
//   layout, counts: cells per chart (ddm_layout_cells): n × m, n ≥ 1 (≥ 2 for hex / brick), m ≥ 1;
//   height  world units (object space) per tile unit of w, along the base normal, > 0;
//   map_resolution  P/N map samples per chart edge (DdmMaps), default [9,9] (limit), [513,257] (teapot_body),
//           [1025,1025] (uv); tile_* the layer's DdmTileTransform (scale > 0, degrees, cell units).
//   The layer is sampled into P/N maps and evaluated over them on the CPU reference (ddm_layer_mesh: what the GPU
//   draws) and stored on the object (SceneObject::ddm_layers); a layer of the same name is replaced. Objects with an
//   FFD lattice, a DFFD rig or a glTF clip are refused (the tiles would not follow the deformation). At most
//   50,000,000 tile vertices.
//   report.json: charts, tiles, tile_vertices, vertices, map_samples, ms.
// `ddm.bake` — a layer as an ordinary mesh object (for export and for use elsewhere):
//   {"cmd":"ddm.bake","object":"ID","layer":"NAME","name":"NEW_ID"}
//   optional "frame":F (default: the layer at scene time 0) — the layer's animation at that timeline frame.
//   The new object's mesh is the layer's in world units (the object's transform applied), identity transform, the
//   object's colour; instances one after another, each in the tile's own vertex order. scene.glb then holds it.
//   report.json: vertices, triangles.
// Errors (CommandError, field named; the scene is unchanged): unknown object / deformed object / a base the mesh
// cannot give (non-manifold, no triangles, no uvs) ("object" / "base"); unknown tile, unreadable or bad tile file
// ("tile" / "tiles"); bad layout ("layout"); counts out of range or too many vertices ("counts"); height ≤ 0 or not
// finite ("height"); teapot_body on another object ("base"); no such layer ("layer"); name empty or taken ("name").
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/commands/snapshot_command.h"
#include "core/ddm/ddm_layer.h"

namespace trispline::core {

// The fields that make a layer: ddm.fill's, and ddm.paint's when it creates its layer. parse() reads them (all
// optional but layer/tile when `require_tile`), write() logs them back (tile files absolute).
struct DdmLayerSpec {
  std::string layer;
  std::vector<std::string> tiles;                 // "thorn" | … | a file as given; tiles[0] is the "tile" field
  std::vector<std::filesystem::path> tile_paths;  // per tile: resolved file, empty for generated tiles
  std::string base = "limit", layout = "rect", choice = "pattern";
  glm::ivec2 counts{1, 1};
  double height = 0.1;
  std::optional<glm::ivec2> map_resolution;
  DdmTileTransform transform;
  std::int64_t seed = 0;
  std::optional<glm::vec3> color;  // "color": the layer's linear RGB, each in [0, 1] (default: the object's)

  // Throws CommandError naming the field.
  static DdmLayerSpec parse(const nlohmann::json& j, const CommandContext& ctx, bool require_tile);
  void write(nlohmann::json& j) const;
};

// Loads a tile: a generated kind or a mesh file made canonical. Throws CommandError (`field`) on failure.
DdmTile load_ddm_tile(const std::string& name, const std::filesystem::path& path, const char* field);

// A new layer from `spec` on `object` (its rest mesh, object space): tiles loaded, base built, every layout cell
// filled (`fill`) or none, maps sampled, mesh evaluated. Throws CommandError naming the field (see ddm.fill).
std::shared_ptr<DdmLayer> make_ddm_layer(const SceneObject& object, const DdmLayerSpec& spec, bool fill);

// `object` with `layer` added, or replacing the layer of the same name.
SceneObject with_ddm_layer(const SceneObject& object, std::shared_ptr<const DdmLayer> layer);
// The object's layer called `name`; throws CommandError ("layer") when there is none.
std::shared_ptr<const DdmLayer> find_ddm_layer(const SceneObject& object, const std::string& name);

class DdmFillCommand : public SnapshotCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "ddm.fill"; }
  nlohmann::json to_json() const override;
  std::string label() const override;
  nlohmann::json stats() const override { return stats_; }

 protected:
  std::string target() const override { return object_; }
  std::optional<SceneObject> build(const Scene& scene) override;
  std::string failure_field() const override { return "tile"; }

 private:
  std::string object_;
  DdmLayerSpec spec_;
  nlohmann::json stats_ = nlohmann::json::object();
};

class DdmBakeCommand : public SnapshotCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "ddm.bake"; }
  nlohmann::json to_json() const override;
  std::string label() const override;
  nlohmann::json stats() const override { return stats_; }

 protected:
  std::string target() const override { return name_; }
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  std::string object_, layer_, name_;
  std::optional<double> frame_;
  nlohmann::json stats_ = nlohmann::json::object();
};

// {"cmd":"ddm.color","object":ID,"layer":NAME,"color":[r,g,b] | null}: sets a layer's own colour (linear RGB, each in
// [0, 1]) or, with null, makes it take its object's colour again. Only the colour changes (the tiles are shared).
// Errors (field named, scene unchanged): unknown object, no such layer, a colour out of range.
class DdmColorCommand : public SnapshotCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "ddm.color"; }
  nlohmann::json to_json() const override;
  std::string label() const override;

 protected:
  std::string target() const override { return object_; }
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  std::string object_, layer_;
  std::optional<glm::vec3> color_;
};

// {"cmd":"ddm.remove","object":ID,"layer":NAME}: deletes a tile layer (its tiles, maps and animation); undo brings it
// back as it was. Errors (field named, scene unchanged): unknown object, no such layer.
class DdmRemoveCommand : public SnapshotCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "ddm.remove"; }
  nlohmann::json to_json() const override;
  std::string label() const override;
  nlohmann::json stats() const override { return stats_; }

 protected:
  std::string target() const override { return object_; }
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  std::string object_, layer_;
  nlohmann::json stats_ = nlohmann::json::object();
};

}  // namespace trispline::core
