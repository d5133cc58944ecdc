#include "core/commands/ddm_bake.h"

#include <stdexcept>

#include "core/scene/ddm_follow.h"

namespace trispline::core {

auto DdmBakeCommand::declare() -> Schema {
  return Schema("ddm.bake", "Turn a tile layer into an ordinary mesh object (for export)")
      .field("object", &P::object, {.required = true, .help = "The object holding the layer"})
      .field("layer", &P::layer, {.required = true, .help = "The layer to bake"})
      .field("name", &P::name, {.required = true, .help = "Id of the new object; an existing name is an error"})
      .check([](const P& p) {
        if (const std::string bad = object_name_error(p.name); !bad.empty()) params::fail("name", bad);
      })
      .field("frame", &P::frame,
             {.default_text = "scene time 0", .help = "Timeline frame of the layer's animation to bake"})
      .label([](const P& p) { return "Bake " + p.object + "/" + p.layer + " as '" + p.name + "'"; });
}

std::optional<SceneObject> DdmBakeCommand::build(const Scene& scene) {
  const SceneObject* object = &require_object(scene, p_.object);
  const std::shared_ptr<const DdmLayer> layer = find_ddm_layer(*object, p_.layer);
  if (scene.find(p_.name)) throw CommandError("field 'name': an object named '" + p_.name + "' already exists", "name");
  SceneObject baked;
  baked.name = p_.name;
  baked.source = "ddm.bake:" + p_.object + "/" + p_.layer;
  baked.color = layer->color.value_or(object->color);
  // Texture-mapped tiles keep their materials; plain ones among them take the layer's colour.
  baked.materials = ddm_tile_materials(layer->tiles, glm::dvec3(baked.color)).set;
  // In world units where the object's deformation carries the tiles at that time (ddm_follow.h). The evaluation
  // (a frame of the animation) or the copy takes the first 80 %, the deformation the rest.
  const double t = p_.frame ? scene.timeline.time_of_frame(*p_.frame) : 0.0;
  const ProgressSink evaluation = progress_range(progress(), 0.0, 0.8);
  const TriMesh mesh = p_.frame ? ddm_layer_mesh(*layer, t, progress() ? &evaluation : nullptr) : *layer->mesh;
  check_progress(progress(), 0.8);
  try {
    baked.rest_mesh = std::make_shared<const TriMesh>(ddm_layer_world_mesh(*object, *layer, mesh, t));
  } catch (const std::invalid_argument& e) {
    throw CommandError("field 'layer': " + std::string(e.what()), "layer");
  }
  check_progress(progress(), 0.95);
  baked.refresh();
  stats_ = {{"vertices", baked.rest_mesh->vertex_count()}, {"triangles", baked.rest_mesh->triangle_count()}};
  return baked;
}

}  // namespace trispline::core
