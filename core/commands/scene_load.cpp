#include "core/commands/scene_load.h"

#include "core/commands/json_fields.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {

CommandPtr SceneLoadCommand::parse(const nlohmann::json& j, const CommandContext& ctx) {
  auto c = std::make_unique<SceneLoadCommand>();
  const std::string path = json_fields::get_string(j, "path");
  if (path.empty()) throw CommandError("field 'path': must not be empty", "path");
  // Logged with its absolute path so the session log replays from anywhere; Save makes it relative again
  // (editor::make_paths_relative).
  c->resolved_ = std::filesystem::absolute(ctx.resolve(path)).lexically_normal();
  c->ignore_loose_ = json_fields::get_enum(j, "loose", {"refuse", "ignore"}, "refuse") == "ignore";
  c->parse_object_fields(j);
  return c;
}

nlohmann::json SceneLoadCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"path", resolved_.string()}};
  if (ignore_loose_) j["loose"] = "ignore";
  put_object_fields(j);
  return j;
}

TriMesh SceneLoadCommand::make_mesh() const {
  MeshLoadOptions options;
  options.ignore_loose = ignore_loose_;
  return load_mesh(resolved_, options, &report_);
}

nlohmann::json SceneLoadCommand::stats() const {
  nlohmann::json s = AddObjectCommand::stats();
  s["loader"] = report_.loader;
  if (report_.ignored_points) s["ignored_points"] = report_.ignored_points;
  if (report_.ignored_lines) s["ignored_lines"] = report_.ignored_lines;
  if (report_.duplicate_faces) s["duplicate_faces"] = report_.duplicate_faces;
  return s;
}

}  // namespace trispline::core
