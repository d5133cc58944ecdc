// `scene.primitive` — adds a generated object. Fields: declared in scene_primitive.cpp (ParamSchema; the name,
// transform and colour in codecs.cpp object_fields_schema()), listed in docs/commands.md; the help of `kind` gives
// each kind's size before the transform. The cylinder is centred; the teapot is Newell's 32 Bézier patches.
#pragma once

#include "core/commands/add_object_command.h"
#include "core/commands/declared_command.h"

namespace trispline::core {

struct ScenePrimitiveParams {
  std::string kind;
  std::int64_t seed = 0;  // terrain heights
  ObjectFields object;
};

class ScenePrimitiveCommand
    : public DeclaredSnapshotCommand<ScenePrimitiveCommand, ScenePrimitiveParams, AddObjectCommand> {
 public:
  static Schema declare();

 protected:
  ObjectFields& object_fields() override { return p_.object; }
  TriMesh make_mesh() const override;
  std::string default_name() const override { return p_.kind; }
  std::string source() const override { return "primitive:" + p_.kind; }
};

}  // namespace trispline::core
