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
  c->parse_object_fields(j);
  return c;
}

nlohmann::json SceneLoadCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"path", resolved_.string()}};
  put_object_fields(j);
  return j;
}

TriMesh SceneLoadCommand::make_mesh() const { return load_mesh(resolved_); }

}  // namespace trispline::core
