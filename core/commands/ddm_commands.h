// DDM commands (seed ch. 5, deformation displacement maps): layers of geometric tiles over an object's surface.
//
// `ddm.fill` — a whole-surface layer (the painting tool's fill click):
//   {"cmd":"ddm.fill","object":"ID","layer":"NAME","tile":"PATH|thorn|chain|hex|flower","layout":"rect|hex|brick",
//    "counts":[n,m],"height":h}
//   optional: "base":"limit|teapot_body" (default "limit").
//   tile    a generated tile (ddm_tile.h) or a mesh file (OBJ/PLY/glTF, relative to the log's folder; logged absolute,
//           relative again in saved logs, like scene.load's path), made canonical by its bounding box;
//   base    limit: the Loop limit surface of the object's rest mesh (OpenSubdiv Bfr), three charts per triangle;
//           teapot_body: the teapot primitive's 8 Bézier body patches (objects made by scene.primitive "teapot");
//   layout, counts: cells per chart (ddm_layout_cells): n × m, n ≥ 1 (≥ 2 for hex / brick), m ≥ 1;
//   height  world units (object space) per tile unit of w, along the base normal, > 0.
//   The layer is evaluated on the CPU reference (ddm_evaluate, exact normals) and stored on the object
//   (SceneObject::ddm_layers); a layer of the same name is replaced. Objects with an FFD lattice, a DFFD rig or a
//   glTF clip are refused (the tiles would not follow the deformation). At most 50,000,000 tile vertices.
//   report.json: charts, tiles, tile_vertices, vertices, ms.
// `ddm.bake` — a layer as an ordinary mesh object (for export and for use elsewhere):
//   {"cmd":"ddm.bake","object":"ID","layer":"NAME","name":"NEW_ID"}
//   The new object's mesh is the layer's in world units (the object's transform applied), identity transform, the
//   object's colour; instances one after another, each in the tile's own vertex order. scene.glb then holds it.
//   report.json: vertices, triangles.
// Errors (CommandError, field named; the scene is unchanged): unknown object / deformed object / a base the mesh
// cannot give (non-manifold, no triangles) ("object"); unknown tile, unreadable or bad tile file ("tile"); bad
// layout ("layout"); counts out of range or too many vertices ("counts"); height ≤ 0 or not finite ("height");
// teapot_body on another object ("base"); no such layer ("layer"); name empty or taken ("name").
#pragma once

#include "core/commands/snapshot_command.h"

namespace trispline::core {

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
  std::string object_, layer_, tile_, base_ = "limit", layout_ = "rect";
  std::filesystem::path tile_path_;  // resolved when tile_ is a file
  glm::ivec2 counts_{1, 1};
  double height_ = 0.1;
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
  nlohmann::json stats_ = nlohmann::json::object();
};

}  // namespace trispline::core
