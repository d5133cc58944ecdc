#include "core/commands/add_object_command.h"

#include "core/commands/json_fields.h"

namespace trispline::core {
namespace jf = json_fields;

void AddObjectCommand::parse_object_fields(const nlohmann::json& j) {
  name_ = jf::get_string(j, "name", "");
  if (!name_.empty())
    if (const std::string bad = object_name_error(name_); !bad.empty()) throw CommandError("field 'name': " + bad, "name");
  transform_ = jf::get_transform(j);
  if (jf::has(j, "color")) {
    color_ = jf::get_vec3(j, "color");
    if (glm::any(glm::lessThan(*color_, glm::dvec3(0.0))) || glm::any(glm::greaterThan(*color_, glm::dvec3(1.0))))
      throw CommandError("field 'color': each component must be in [0, 1]", "color");
  }
}

void AddObjectCommand::put_object_fields(nlohmann::json& j) const {
  j["name"] = name_;
  jf::put_transform(j, transform_);
  if (color_) j["color"] = jf::to_json(*color_);
}

std::optional<SceneObject> AddObjectCommand::build(const Scene& scene) {
  if (name_.empty()) name_ = scene.unique_name(sanitized_object_name(default_name()));
  if (scene.index_of(name_) >= 0)
    throw CommandError("field 'name': an object named '" + name_ + "' already exists", "name");
  SceneObject o;
  o.name = name_;
  o.source = source();
  o.rest_mesh = std::make_shared<const TriMesh>(make_mesh());
  o.transform = transform_;
  o.color = color_ ? glm::vec3(*color_) : palette_color(static_cast<int>(scene.objects().size()));
  o.refresh();
  vertices_ = o.rest_mesh->vertex_count();
  triangles_ = o.rest_mesh->triangle_count();
  return o;
}

}  // namespace trispline::core
