#include "core/commands/scene_load.h"

#include "core/commands/json_fields.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace jf = json_fields;

CommandPtr SceneLoadCommand::parse(const nlohmann::json& j, const CommandContext& ctx) {
  auto c = std::make_unique<SceneLoadCommand>();
  c->path_ = jf::get_string(j, "path");
  if (c->path_.empty()) throw CommandError("field 'path': must not be empty", "path");
  // Logged with its absolute path, so the session log replays from anywhere; Save makes it relative again
  // (editor::make_paths_relative).
  c->resolved_ = std::filesystem::absolute(ctx.resolve(c->path_)).lexically_normal();
  c->path_ = c->resolved_.string();
  c->name_ = jf::get_string(j, "name", "");
  c->transform_ = jf::get_transform(j);
  if (jf::has(j, "color")) c->color_ = jf::get_vec3(j, "color");
  return c;
}

nlohmann::json SceneLoadCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"path", path_}, {"name", name_}};
  jf::put_transform(j, transform_);
  if (color_) j["color"] = jf::to_json(*color_);
  return j;
}

std::string SceneLoadCommand::label() const { return "Load '" + name_ + "'"; }

nlohmann::json SceneLoadCommand::stats() const { return {{"vertices", vertices_}, {"triangles", triangles_}}; }

std::optional<SceneObject> SceneLoadCommand::build(const Scene& scene) {
  if (name_.empty()) name_ = scene.unique_name(std::filesystem::path(path_).stem().string());
  if (scene.index_of(name_) >= 0) throw CommandError("an object named '" + name_ + "' already exists", "name");
  SceneObject o;
  o.name = name_;
  o.source = path_;
  o.rest_mesh = std::make_shared<const TriMesh>(load_mesh(resolved_));
  o.transform = transform_;
  o.color = color_ ? glm::vec3(*color_) : palette_color(static_cast<int>(scene.objects().size()));
  o.refresh();
  vertices_ = o.rest_mesh->vertex_count();
  triangles_ = o.rest_mesh->triangle_count();
  return o;
}

}  // namespace trispline::core
