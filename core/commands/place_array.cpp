#include "core/commands/place_array.h"

#include <chrono>
#include <cmath>

#include "core/commands/json_fields.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {
namespace jf = json_fields;

CommandPtr PlaceArrayCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<PlaceArrayCommand>();
  c->object_ = jf::get_string(j, "object");
  c->count_ = jf::get_int(j, "count", c->count_);
  if (c->count_ < 1 || c->count_ > 64) throw CommandError("field 'count': must be in [1, 64]", "count");
  c->spacing_ = jf::get_number(j, "spacing", c->spacing_);
  if (std::abs(c->spacing_) > 10.0) throw CommandError("field 'spacing': |spacing| must be ≤ 10 parameter units", "spacing");
  c->clip_phase_s_ = jf::get_number(j, "clip_phase_s", 0.0);
  if (std::abs(c->clip_phase_s_) > 1e4) throw CommandError("field 'clip_phase_s': |phase| must be ≤ 1e4 s", "clip_phase_s");
  return c;
}

nlohmann::json PlaceArrayCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"object", object_}, {"count", count_}, {"spacing", spacing_}};
  if (clip_phase_s_ != 0.0) j["clip_phase_s"] = clip_phase_s_;
  return j;
}

std::string PlaceArrayCommand::label() const {
  return "Array " + std::to_string(count_) + " × '" + object_ + "' along its path";
}

void PlaceArrayCommand::redo(Scene& scene) {
  const SceneObject& source = require_deformed_object(scene, object_);
  const auto t0 = std::chrono::steady_clock::now();
  // Build every copy first; the scene changes only after all of them evaluated.
  Scene names = scene;  // for unique names only (objects share their meshes: cheap)
  std::vector<SceneObject> copies;
  const int base_index = scene.index_of(object_);
  for (int k = 1; k <= count_; ++k) {
    SceneObject c = source;
    c.name = names.unique_name(object_);
    c.color = palette_color(static_cast<int>(scene.objects().size()) + k - 1);
    const double du = -spacing_ * k;
    c.param_offset.x += du;
    for (OffsetKey& key : c.offset_keys) key.offset.x += du;
    if (c.clip) {
      auto b = std::make_shared<ClipBinding>(*c.clip);
      b->start_s += clip_phase_s_ * k;
      c.clip = std::move(b);
    }
    try {
      c.refresh();
    } catch (const std::exception& e) {
      throw CommandError(std::string("field 'object': ") + e.what(), "object");
    }
    SceneObject placeholder;
    placeholder.name = c.name;
    names.insert(std::move(placeholder));
    copies.push_back(std::move(c));
  }
  added_.clear();
  std::size_t vertices = 0;
  for (std::size_t k = 0; k < copies.size(); ++k) {
    added_.push_back(copies[k].name);
    vertices += copies[k].world_mesh->positions.size();
    scene.insert(std::move(copies[k]), base_index + 1 + static_cast<int>(k));
  }
  stats_ = {{"copies", added_},
            {"vertices", vertices},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
}

void PlaceArrayCommand::undo(Scene& scene) {
  for (auto it = added_.rbegin(); it != added_.rend(); ++it) scene.remove(*it);
}

}  // namespace trispline::core
