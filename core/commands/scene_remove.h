// `scene.remove` — removes an object.   {"cmd":"scene.remove","name":"ID"}
#pragma once

#include "core/commands/snapshot_command.h"

namespace trispline::core {

class SceneRemoveCommand : public SnapshotCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "scene.remove"; }
  nlohmann::json to_json() const override { return {{"cmd", id()}, {"name", name_}}; }
  std::string label() const override { return "Remove '" + name_ + "'"; }

 protected:
  std::string target() const override { return name_; }
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  std::string name_;
};

}  // namespace trispline::core
