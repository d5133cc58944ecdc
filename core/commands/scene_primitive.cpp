#include "core/commands/scene_primitive.h"

#include "core/commands/json_fields.h"
#include "core/scene/primitives.h"

namespace trispline::core {
namespace jf = json_fields;

CommandPtr ScenePrimitiveCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<ScenePrimitiveCommand>();
  c->kind_ = jf::get_enum(j, "kind", {"teapot", "plane", "sphere", "box", "cylinder", "terrain"});
  c->name_ = jf::get_string(j, "name", "");
  c->transform_ = jf::get_transform(j);
  c->seed_ = jf::get_int(j, "seed", 0);
  if (jf::has(j, "color")) c->color_ = jf::get_vec3(j, "color");
  return c;
}

nlohmann::json ScenePrimitiveCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"kind", kind_}, {"name", name_}};
  jf::put_transform(j, transform_);
  j["seed"] = seed_;
  if (color_) j["color"] = jf::to_json(*color_);
  return j;
}

std::string ScenePrimitiveCommand::label() const { return "Add " + kind_ + " '" + name_ + "'"; }

nlohmann::json ScenePrimitiveCommand::stats() const { return {{"vertices", vertices_}, {"triangles", triangles_}}; }

std::optional<SceneObject> ScenePrimitiveCommand::build(const Scene& scene) {
  if (name_.empty()) name_ = scene.unique_name(kind_);
  if (scene.index_of(name_) >= 0) throw CommandError("an object named '" + name_ + "' already exists", "name");
  SceneObject o;
  o.name = name_;
  o.source = "primitive:" + kind_;
  o.rest_mesh = std::make_shared<const TriMesh>(make_primitive(parse_primitive_kind(kind_),
                                                               static_cast<std::uint64_t>(seed_)));
  o.transform = transform_;
  o.color = color_ ? glm::vec3(*color_) : palette_color(static_cast<int>(scene.objects().size()));
  o.refresh();
  vertices_ = o.rest_mesh->vertex_count();
  triangles_ = o.rest_mesh->triangle_count();
  return o;
}

}  // namespace trispline::core
