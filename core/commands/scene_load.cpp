#include "core/commands/scene_load.h"

#include "core/mesh/model_load.h"

namespace trispline::core {

auto SceneLoadCommand::declare() -> Schema {
  return Schema("scene.load", "Load a mesh file (OBJ, PLY, OFF, STL, Collada, FBX, glTF, GLB) as a new object")
      // Logged with its absolute path so the session log replays from anywhere; Save makes it relative again
      // (editor::make_paths_relative).
      .field("path", &P::path,
             {.required = true,
              .path = true,
              .help = "OBJ, PLY, OFF, STL, DAE, FBX (assimp) or glTF/GLB (tinygltf), relative to the log's folder; "
                      "loads whole or fails"})
      .choice("loose", &P::loose, {"refuse", "ignore"},
              {.write = ParamWrite::UnlessDefault,
               .help = "Point and line elements beside the faces: fail naming their counts, or leave them out "
                       "(counted in report.json)"})
      .embed(&P::object, object_fields_schema())
      .label([](const P& p) { return "Load '" + p.object.name + "'"; })
      .failure_field("path");
}

TriMesh SceneLoadCommand::make_mesh() const {
  MeshLoadOptions options;
  options.ignore_loose = p_.loose == "ignore";
  loaded_ = load_model(p_.path, options, &report_);
  return std::move(loaded_.mesh);
}

std::optional<SceneObject> SceneLoadCommand::build(const Scene& scene) {
  std::optional<SceneObject> o = AddObjectCommand::build(scene);
  if (o) {
    o->materials = loaded_.materials;
    o->parts = loaded_.parts;
  }
  return o;
}

nlohmann::json SceneLoadCommand::stats() const {
  nlohmann::json s = AddObjectCommand::stats();
  s["loader"] = report_.loader;
  if (report_.ignored_points) s["ignored_points"] = report_.ignored_points;
  if (report_.ignored_lines) s["ignored_lines"] = report_.ignored_lines;
  if (report_.duplicate_faces) s["duplicate_faces"] = report_.duplicate_faces;
  if (loaded_.materials) {
    s["materials"] = loaded_.materials->materials.size();
    s["images"] = loaded_.materials->images.size();
  }
  if (!loaded_.parts.empty()) s["parts"] = loaded_.parts.size();
  if (const auto errors = loaded_.texture_errors(); !errors.empty()) s["texture_errors"] = errors;
  if (!loaded_.warnings.empty()) s["warnings"] = loaded_.warnings;
  return s;
}

}  // namespace trispline::core
