// `scene.load` — adds a mesh file as a new object.
//   {"cmd":"scene.load","path":"PATH","name":"ID","translate":[x,y,z],"rotate_deg":[x,y,z],"scale":s|[sx,sy,sz],
//    "color":[r,g,b],"loose":"refuse"|"ignore"}
// path: OBJ, PLY, OFF, STL (assimp) or glTF/GLB (tinygltf), relative to the log's folder unless absolute; the file
// loads whole or the command fails (core::load_mesh).
// loose: what to do with point and line elements beside the faces: "refuse" (default: the command fails naming their
// counts) or "ignore" (they are left out; stats() counts them as ignored_points / ignored_lines).
// The command's own log line (to_json) holds the absolute path, so session logs replay from any folder.
// name: optional, defaults to the file stem made unique ("bunny.001"); an existing name is an error.
// Transform: scale, then rotation (degrees about x, then y, then z), then translation; world units.
#pragma once

#include "core/commands/add_object_command.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {

class SceneLoadCommand : public AddObjectCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "scene.load"; }
  nlohmann::json to_json() const override;
  std::string label() const override { return "Load '" + name_ + "'"; }

 protected:
  TriMesh make_mesh() const override;
  std::string default_name() const override { return resolved_.stem().string(); }
  std::string source() const override { return resolved_.string(); }
  std::string failure_field() const override { return "path"; }
  nlohmann::json stats() const override;

 private:
  std::filesystem::path resolved_;  // absolute, normalised
  bool ignore_loose_ = false;
  mutable MeshLoadReport report_;  // of the last make_mesh()
};

}  // namespace trispline::core
