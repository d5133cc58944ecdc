#include "core/commands/add_object_command.h"

namespace trispline::core {

std::optional<SceneObject> AddObjectCommand::build(const Scene& scene) {
  ObjectFields& fields = object_fields();
  if (fields.name.empty()) fields.name = scene.unique_name(sanitized_object_name(default_name()));
  if (scene.index_of(fields.name) >= 0)
    throw CommandError("field 'name': an object named '" + fields.name + "' already exists", "name");
  SceneObject o;
  o.name = fields.name;
  o.source = source();
  o.rest_mesh = std::make_shared<const TriMesh>(make_mesh());
  o.transform = fields.transform;
  o.color = fields.color ? glm::vec3(*fields.color) : palette_color(static_cast<int>(scene.objects().size()));
  o.refresh();
  vertices_ = o.rest_mesh->vertex_count();
  triangles_ = o.rest_mesh->triangle_count();
  return o;
}

}  // namespace trispline::core
