// `scene.primitive` — adds a generated object.
//   {"cmd":"scene.primitive","kind":"teapot|plane|sphere|box|cylinder|terrain","name":"ID","translate":[..],
//    "rotate_deg":[..],"scale":s|[..],"seed":n,"color":[r,g,b]}
// Before the transform: plane 2×2 in xz, sphere radius 1, box 2×2×2, cylinder radius 1 height 2 along y (centred),
// terrain 2×2 in xz with heights in [0,0.3] (seeded), teapot on y = 0 with height 1 (Newell's 32 Bézier patches).
#pragma once

#include "core/commands/add_object_command.h"
#include "core/commands/declared_command.h"

namespace trispline::core {

struct ScenePrimitiveParams {
  std::string kind;
  std::int64_t seed = 0;  // terrain heights
  ObjectFields object;
};

class ScenePrimitiveCommand : public DeclaredCommand<ScenePrimitiveCommand, ScenePrimitiveParams, AddObjectCommand> {
 public:
  using DeclaredCommand::DeclaredCommand;
  static const ParamSchema<ScenePrimitiveParams>& schema();

  std::string label() const override { return "Add " + p_.kind + " '" + p_.object.name + "'"; }

 protected:
  ObjectFields& object_fields() override { return p_.object; }
  TriMesh make_mesh() const override;
  std::string default_name() const override { return p_.kind; }
  std::string source() const override { return "primitive:" + p_.kind; }
  std::string failure_field() const override { return "kind"; }
};

}  // namespace trispline::core
