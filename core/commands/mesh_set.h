// `mesh.set` — replace an object's rest mesh with given vertices and triangles (Python's trispline.Scene.set_mesh,
// the Blender add-on's meshes): a SnapshotCommand like every command that changes one object, undone and redone bit
// for bit through History; its log line carries the mesh, so every replay (the editor, `trispline replay`, Python's
// Scene.open) rebuilds it. A log line is at most 8 MiB (the command log's limit), about 150 K vertices.
//
//   {"cmd": "mesh.set", "object": "pot", "vertices": [[x,y,z], ...], "faces": [[a,b,c], ...]}
//   vertices  #V × 3  object space, world units; finite
//   faces     #F × 3  vertex indices in [0, #V), counter-clockwise seen from outside
// The object keeps its name, transform, colour and visibility; vertex normals are recomputed (area-weighted); its uvs
// are kept when #V is unchanged, its per-face materials when #F is. Refused (CommandError, field "object") for an
// object with an FFD lattice, a DFFD split, a glTF clip, a morph or tile layers, whose data is bound to the old
// vertices. report.json stats: vertices_before, vertices_after, triangles_before, triangles_after.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/commands/snapshot_command.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

class MeshSetCommand : public SnapshotCommand {
 public:
  static constexpr const char* kId = "mesh.set";
  // `mesh`: positions and triangles checked by the caller (finite, indices in range); normals are computed here.
  MeshSetCommand(std::string object, TriMesh mesh);
  // From a log line. Throws CommandError naming the field (object, vertices, faces).
  static CommandPtr parse(const nlohmann::json& line);

  std::string id() const override { return kId; }
  nlohmann::json to_json() const override;
  std::string label() const override;

 protected:
  std::string target() const override { return object_; }
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  std::string object_;
  std::shared_ptr<const TriMesh> mesh_;
};

}  // namespace trispline::core
