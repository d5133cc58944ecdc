// `scene.primitive` — adds a generated object.
//   {"cmd":"scene.primitive","kind":"teapot|plane|sphere|box|cylinder|terrain","name":"ID","translate":[..],
//    "rotate_deg":[..],"scale":s|[..],"seed":n,"color":[r,g,b]}
// Before the transform: plane 2×2 in xz, sphere radius 1, box 2×2×2, cylinder radius 1 height 2 along y (centred),
// terrain 2×2 in xz with heights in [0,0.3] (seeded), teapot on y = 0 with height 1 (Newell's 32 Bézier patches).
#pragma once

#include "core/commands/add_object_command.h"

namespace trispline::core {

class ScenePrimitiveCommand : public AddObjectCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "scene.primitive"; }
  nlohmann::json to_json() const override;
  std::string label() const override { return "Add " + kind_ + " '" + name_ + "'"; }

 protected:
  TriMesh make_mesh() const override;
  std::string default_name() const override { return kind_; }
  std::string source() const override { return "primitive:" + kind_; }
  std::string failure_field() const override { return "kind"; }

 private:
  std::string kind_;
  std::int64_t seed_ = 0;
};

}  // namespace trispline::core
