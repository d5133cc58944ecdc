#include "core/commands/place_array.h"

#include <chrono>
#include <cmath>

#include "core/commands/snapshot_command.h"

namespace trispline::core {

auto PlaceArrayCommand::declare() -> Schema {
  return Schema("place.array", "Add copies of a placed object in a row along its path (seed Fig. 2.11, the ants)")
      .field("object", &P::object, {.required = true, .help = "A placed object"})
      .field("count", &P::count, {.range = ParamRange{1, 64}, .help = "Copies to add"})
      .field("spacing", &P::spacing,
             {.range = ParamRange::magnitude_at_most(10),
              .unit = "parameter units",
              .help = "u offset between neighbouring copies"})
      .field("clip_phase_s", &P::clip_phase_s,
             {.write = ParamWrite::UnlessDefault,
              .range = ParamRange::magnitude_at_most(1e4),
              .unit = "seconds",
              .help = "Each copy's glTF clip starts this much later than the one before"})
      .label([](const P& p) { return "Array " + std::to_string(p.count) + " × '" + p.object + "' along its path"; });
}

void PlaceArrayCommand::redo(Scene& scene) {
  const SceneObject& source = require_deformed_object(scene, p_.object);
  const auto t0 = std::chrono::steady_clock::now();
  // Build every copy first; the scene changes only after all of them evaluated.
  Scene names = scene;  // for unique names only (objects share their meshes: cheap)
  std::vector<SceneObject> copies;
  const int base_index = scene.index_of(p_.object);
  for (int k = 1; k <= p_.count; ++k) {
    SceneObject c = source;
    c.name = names.unique_name(p_.object);
    c.color = palette_color(static_cast<int>(scene.objects().size()) + k - 1);
    const double du = -p_.spacing * k;
    c.param_offset.x += du;
    for (OffsetKey& key : c.offset_keys) key.offset.x += du;
    if (c.clip) {
      auto b = std::make_shared<ClipBinding>(*c.clip);
      b->start_s += p_.clip_phase_s * k;
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
