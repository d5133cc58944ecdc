#include "core/commands/ddm_remove.h"

namespace trispline::core {

auto DdmRemoveCommand::declare() -> Schema {
  return Schema("ddm.remove", "Delete a tile layer")
      .field("object", &P::object, {.required = true, .help = "The object holding the layer"})
      .field("layer", &P::layer, {.required = true, .help = "The layer to delete"})
      .label([](const P& p) { return "Remove tile layer " + p.object + "/" + p.layer; });
}

std::optional<SceneObject> DdmRemoveCommand::build(const Scene& scene) {
  const SceneObject* object = &require_object(scene, p_.object);
  const std::shared_ptr<const DdmLayer> layer = find_ddm_layer(*object, p_.layer);
  SceneObject out = *object;
  std::erase(out.ddm_layers, layer);
  stats_ = {{"tiles", layer->instances.size()}, {"vertices", layer->mesh ? layer->mesh->vertex_count() : 0}};
  return out;
}

}  // namespace trispline::core
