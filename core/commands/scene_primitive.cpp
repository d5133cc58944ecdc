#include "core/commands/scene_primitive.h"

#include "core/commands/json_fields.h"
#include "core/scene/primitives.h"

namespace trispline::core {
namespace jf = json_fields;

CommandPtr ScenePrimitiveCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<ScenePrimitiveCommand>();
  c->kind_ = jf::get_enum(j, "kind", {"teapot", "plane", "sphere", "box", "cylinder", "terrain"});
  c->seed_ = jf::get_int64(j, "seed", 0);
  c->parse_object_fields(j);
  return c;
}

nlohmann::json ScenePrimitiveCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"kind", kind_}, {"seed", seed_}};
  put_object_fields(j);
  return j;
}

TriMesh ScenePrimitiveCommand::make_mesh() const {
  return make_primitive(parse_primitive_kind(kind_), static_cast<std::uint64_t>(seed_));
}

}  // namespace trispline::core
