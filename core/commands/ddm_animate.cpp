// ddm.animate. See ddm_animate.h. Sources: seed §5.4.2 (animated DDMs), Eq. 5.3 (metamorphosis).
#include "core/commands/ddm_animate.h"

#include <algorithm>
#include <cmath>

#include "core/commands/anim_commands.h"
#include "core/commands/json_fields.h"

namespace trispline::core {
namespace jf = json_fields;
namespace {

// [[a, b(, c)], ...] rows of `width` finite numbers.
std::vector<std::vector<double>> get_rows(const nlohmann::json& j, const char* field, std::size_t width) {
  const nlohmann::json& v = jf::require(j, field);
  const std::string want = width == 2 ? "[frame, alpha]" : "[frame, du, dv]";
  if (!v.is_array()) throw CommandError(std::string("field '") + field + "': expected a list of " + want, field);
  std::vector<std::vector<double>> rows;
  for (const auto& r : v) {
    if (!r.is_array() || r.size() != width)
      throw CommandError(std::string("field '") + field + "': every key is " + want, field);
    std::vector<double> row;
    for (const auto& x : r) {
      if (!x.is_number() || !std::isfinite(x.get<double>()))
        throw CommandError(std::string("field '") + field + "': every entry must be a finite number", field);
      row.push_back(x.get<double>());
    }
    rows.push_back(row);
  }
  return rows;
}

// Keys from (frame, value) rows, sorted by time; two keys on one frame are an error.
std::vector<OffsetKey> keys_of(const std::vector<glm::dvec3>& rows, bool two, const Timeline& timeline,
                               KeyInterpolation interpolation, const char* field) {
  std::vector<OffsetKey> keys;
  for (const glm::dvec3& r : rows)
    keys.push_back({timeline.time_of_frame(r.x), two ? glm::dvec3(r.y, r.z, 0.0) : glm::dvec3(r.y, 0.0, 0.0),
                    interpolation});
  std::sort(keys.begin(), keys.end(), [](const OffsetKey& a, const OffsetKey& b) { return a.time_s < b.time_s; });
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i].time_s == keys[i - 1].time_s)
      throw CommandError(std::string("field '") + field + "': two keys on frame " +
                             std::to_string(timeline.frame_of_time(keys[i].time_s)), field);
  return keys;
}

}  // namespace

CommandPtr DdmAnimateCommand::parse(const nlohmann::json& j, const CommandContext& ctx) {
  auto c = std::make_unique<DdmAnimateCommand>();
  c->object_ = jf::get_string(j, "object");
  c->layer_ = jf::get_string(j, "layer");
  c->clear_ = jf::get_bool(j, "clear", false);
  if (jf::has(j, "morph_tile")) c->morph_ = std::vector<std::string>{jf::get_string(j, "morph_tile")};
  if (jf::has(j, "morph_tiles")) {
    const nlohmann::json& m = j.at("morph_tiles");
    if (!m.is_array() || m.empty())
      throw CommandError("field 'morph_tiles': expected a list of tiles, one per layer tile", "morph_tiles");
    std::vector<std::string> names;
    for (const auto& t : m) {
      if (!t.is_string() || t.get<std::string>().empty())
        throw CommandError("field 'morph_tiles': every entry must be a tile name or file", "morph_tiles");
      names.push_back(t.get<std::string>());
    }
    c->morph_ = names;
  }
  if (c->morph_)
    for (const std::string& t : *c->morph_)
      c->morph_paths_.push_back(t.empty() || is_generated_ddm_tile(t) ? std::filesystem::path() : ctx.resolve(t));
  if (jf::has(j, "alpha_keys")) {
    std::vector<glm::dvec2> keys;
    for (const auto& r : get_rows(j, "alpha_keys", 2)) keys.push_back({r[0], r[1]});
    c->alpha_keys_ = keys;
  }
  if (jf::has(j, "offset_keys")) {
    std::vector<glm::dvec3> keys;
    for (const auto& r : get_rows(j, "offset_keys", 3)) keys.push_back({r[0], r[1], r[2]});
    c->offset_keys_ = keys;
  }
  if (jf::has(j, "offset_velocity")) {
    const auto rows = get_rows(nlohmann::json{{"offset_velocity", {j.at("offset_velocity")}}}, "offset_velocity", 2);
    c->offset_velocity_ = glm::dvec2(rows[0][0], rows[0][1]);
  }
  if (jf::has(j, "alpha")) c->alpha_ = jf::get_number(j, "alpha");
  const std::string interp = jf::get_enum(j, "interpolation", {"linear", "constant", "smooth"}, "linear");
  c->interpolation_ = interp == "constant" ? KeyInterpolation::constant
                      : interp == "smooth" ? KeyInterpolation::smooth
                                           : KeyInterpolation::linear;
  return c;
}

nlohmann::json DdmAnimateCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"object", object_}, {"layer", layer_}};
  if (clear_) j["clear"] = true;
  if (morph_) {
    nlohmann::json m = nlohmann::json::array();
    for (std::size_t i = 0; i < morph_->size(); ++i)
      m.push_back(morph_paths_[i].empty() ? (*morph_)[i] : morph_paths_[i].string());
    if (m.size() == 1) j["morph_tile"] = m[0];
    else j["morph_tiles"] = m;
  }
  if (alpha_keys_) {
    nlohmann::json k = nlohmann::json::array();
    for (const glm::dvec2& r : *alpha_keys_) k.push_back({r.x, r.y});
    j["alpha_keys"] = k;
  }
  if (offset_keys_) {
    nlohmann::json k = nlohmann::json::array();
    for (const glm::dvec3& r : *offset_keys_) k.push_back({r.x, r.y, r.z});
    j["offset_keys"] = k;
  }
  if (offset_velocity_) j["offset_velocity"] = {offset_velocity_->x, offset_velocity_->y};
  if (alpha_) j["alpha"] = *alpha_;
  if (interpolation_ != KeyInterpolation::linear) j["interpolation"] = interpolation_name(interpolation_);
  return j;
}

std::string DdmAnimateCommand::label() const { return "Animate tiles " + object_ + "/" + layer_; }

std::optional<SceneObject> DdmAnimateCommand::build(const Scene& scene) {
  const SceneObject* object = scene.find(object_);
  if (!object) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  auto layer = std::make_shared<DdmLayer>(*find_ddm_layer(*object, layer_));
  if (clear_) {
    layer->morph_sources.clear(), layer->morph_tiles.clear(), layer->alpha_keys.clear(), layer->offset_keys.clear();
    layer->alpha = 0.0, layer->offset_velocity = glm::dvec2(0.0);
  }
  if (morph_) {
    const bool remove = morph_->size() == 1 && morph_->front().empty();
    layer->morph_sources.clear(), layer->morph_tiles.clear();
    if (!remove) {
      if (morph_->size() != layer->tiles.size())
        throw CommandError("field 'morph_tile': the layer has " + std::to_string(layer->tiles.size()) +
                               " tiles; give one morph tile per tile (morph_tiles)", "morph_tile");
      for (std::size_t i = 0; i < morph_->size(); ++i) {
        DdmTile partner = load_ddm_tile((*morph_)[i], morph_paths_[i], "morph_tile");
        try {
          require_same_ddm_topology(layer->tiles[i], partner);
        } catch (const std::invalid_argument& e) {
          throw CommandError(std::string("field 'morph_tile': ") + e.what(), "morph_tile");
        }
        layer->morph_sources.push_back((*morph_)[i]);
        layer->morph_tiles.push_back(std::move(partner));
      }
    }
  }
  if (alpha_keys_) {
    std::vector<glm::dvec3> rows;
    for (const glm::dvec2& r : *alpha_keys_) rows.push_back({r.x, r.y, 0.0});
    layer->alpha_keys = keys_of(rows, false, scene.timeline, interpolation_, "alpha_keys");
  }
  if (offset_keys_) layer->offset_keys = keys_of(*offset_keys_, true, scene.timeline, interpolation_, "offset_keys");
  if (offset_velocity_) layer->offset_velocity = *offset_velocity_;
  if (alpha_) layer->alpha = *alpha_;
  if (layer->morph_tiles.empty() && (!layer->alpha_keys.empty() || layer->alpha != 0.0))
    throw CommandError("field 'alpha_keys': layer '" + layer_ + "' has no morph tile to blend to (give morph_tile)",
                       "alpha_keys");
  layer->mesh = std::make_shared<const TriMesh>(ddm_layer_mesh(*layer, 0.0));
  stats_ = {{"alpha_keys", layer->alpha_keys.size()}, {"offset_keys", layer->offset_keys.size()},
            {"morph", !layer->morph_tiles.empty()}, {"vertices", layer->mesh->vertex_count()}};
  return with_ddm_layer(*object, std::move(layer));
}

}  // namespace trispline::core
