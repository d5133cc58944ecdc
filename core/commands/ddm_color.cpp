#include "core/commands/ddm_color.h"

#include <glm/glm.hpp>

namespace trispline::core {

namespace {

// "color": [r, g, b] in the field's range; null = unset.
void read_layer_color(const ParamSchema<DdmColorParams>::Field& f, const nlohmann::json& v, DdmColorParams& p,
                      const CommandContext&) {
  if (v.is_null()) {
    p.color.reset();
    return;
  }
  const glm::dvec3 rgb = params::Codec<glm::dvec3>::read(v, f.doc.name);
  for (int i = 0; i < 3; ++i)
    if (!f.range.contains(rgb[i])) params::fail(f.doc.name, params::range_error(f.range, f.doc.unit, rgb[i], i, 3));
  p.color = glm::vec3(rgb);
}

void write_layer_color(const ParamSchema<DdmColorParams>::Field& f, const DdmColorParams& p, nlohmann::json& line) {
  line[f.doc.name] = p.color ? params::Codec<glm::vec3>::write(*p.color) : nlohmann::json(nullptr);
}

}  // namespace

auto DdmColorCommand::declare() -> Schema {
  return Schema("ddm.color", "Give a tile layer its own colour, or its object's again")
      .field("object", &P::object, {.required = true, .help = "The object holding the layer"})
      .field("layer", &P::layer, {.required = true, .help = "The layer to colour"})
      .custom("color", read_layer_color, write_layer_color,
              {.required = true,
               .range = ParamRange{0, 1},
               .unit = "linear RGB",
               .type_text = "[r,g,b] or null",
               .help = "The layer's own colour; null: its object's again"})
      .label([](const P& p) { return "Colour of tile layer " + p.object + "/" + p.layer; });
}

std::optional<SceneObject> DdmColorCommand::build(const Scene& scene) {
  const SceneObject* object = &require_object(scene, p_.object);
  const std::shared_ptr<const DdmLayer> layer = find_ddm_layer(*object, p_.layer);
  auto recoloured = std::make_shared<DdmLayer>(*layer);  // tiles, maps and mesh stay shared
  recoloured->color = p_.color;
  return with_ddm_layer(*object, recoloured);
}

}  // namespace trispline::core
