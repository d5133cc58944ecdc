#include "core/commands/scene_primitive.h"

#include "core/scene/primitives.h"

namespace trispline::core {

auto ScenePrimitiveCommand::declare() -> Schema {
  return Schema("scene.primitive", "Add a teapot, plane, sphere, box, cylinder or terrain")
      .choice("kind", &P::kind, {"teapot", "plane", "sphere", "box", "cylinder", "terrain"},
              {.required = true,
               .help = "plane 2×2 in xz, sphere radius 1, box 2×2×2, cylinder r 1 h 2 along y, terrain 2×2 with "
                       "heights in [0, 0.3], teapot height 1 on y = 0 (Newell's patches)"})
      .field("seed", &P::seed, {.help = "Terrain heights' random seed"})
      .embed(&P::object, object_fields_schema())
      .label([](const P& p) { return "Add " + p.kind + " '" + p.object.name + "'"; })
      .failure_field("kind");
}

TriMesh ScenePrimitiveCommand::make_mesh() const {
  return make_primitive(parse_primitive_kind(p_.kind), static_cast<std::uint64_t>(p_.seed));
}

}  // namespace trispline::core
