// `scene.load` — adds a mesh file as a new object. Fields: declared in scene_load.cpp (ParamSchema; the name,
// transform and colour in codecs.cpp object_fields_schema()), listed in docs/commands.md.
// The file loads whole or the command fails (core::load_model): the object keeps the file's materials, their images
// and its parts (SceneObject::materials, ::parts). A texture that cannot be read does not fail the command: stats()
// names it under "texture_errors" (and a material library left out under "warnings"). With loose "ignore", stats()
// counts the left-out point and line elements as ignored_points / ignored_lines.
// The command's own log line (to_json) holds the absolute path, so session logs replay from any folder.
// The default name is the file stem made unique ("bunny.001").
// Transform: scale, then rotation (about x, then y, then z), then translation.
#pragma once

#include "core/commands/add_object_command.h"
#include "core/commands/declared_command.h"
#include "core/mesh/model_load.h"

namespace trispline::core {

struct SceneLoadParams {
  std::string path;              // absolute and normalised once parsed
  std::string loose = "refuse";  // refuse | ignore
  ObjectFields object;
};

class SceneLoadCommand : public DeclaredSnapshotCommand<SceneLoadCommand, SceneLoadParams, AddObjectCommand> {
 public:
  static Schema declare();

 protected:
  ObjectFields& object_fields() override { return p_.object; }
  TriMesh make_mesh() const override;
  std::optional<SceneObject> build(const Scene& scene) override;
  std::string default_name() const override { return std::filesystem::path(p_.path).stem().string(); }
  std::string source() const override { return p_.path; }
  nlohmann::json stats() const override;

 private:
  mutable MeshLoadReport report_;  // of the last make_mesh()
  mutable LoadedModel loaded_;     // the last make_mesh()'s materials, parts and warnings (its mesh moved out)
};

}  // namespace trispline::core
