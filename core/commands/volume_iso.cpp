#include "core/commands/volume_iso.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/commands/volume_silhouettes.h"

namespace trispline::core {
namespace {

using P = VolumeIsoParams;
using IsoField = ParamSchema<P>::Field;

// Distinct stroke colours (sRGB) for further levels without a colour of their own: dark blue, crimson, green, orange,
// purple, teal, brown (after the seed's one hue per level, Fig. 7.12).
constexpr glm::vec3 kLevelColors[] = {{0.10f, 0.25f, 0.75f}, {0.80f, 0.10f, 0.20f}, {0.10f, 0.55f, 0.25f},
                                      {0.90f, 0.50f, 0.05f}, {0.50f, 0.20f, 0.65f}, {0.05f, 0.55f, 0.60f},
                                      {0.50f, 0.30f, 0.10f}};

VolumeLevelSpec read_level(const nlohmann::json& v, std::size_t i) {
  const std::string at = "levels[" + std::to_string(i) + "]";
  VolumeLevelSpec spec;
  const nlohmann::json* level = &v;
  if (v.is_object()) {
    for (const auto& [key, value] : v.items())
      if (key != "level" && key != "style" && key != "color")
        params::fail("levels", at + ": unknown field '" + key + "' (level, style, color)");
    if (!v.contains("level")) params::fail("levels", at + ": needs \"level\"");
    level = &v["level"];
    if (v.contains("style")) {
      spec.style = params::Codec<std::string>::read(v["style"], "levels");
      const auto& styles = VolumeSilhouettesCommand::schema().find("style")->choices;
      if (std::find(styles.begin(), styles.end(), *spec.style) == styles.end())
        params::fail("levels", at + ": style must be one of " + params::choices_text(styles));
    }
    if (v.contains("color")) {
      spec.color = params::Codec<glm::vec3>::read(v["color"], "levels");
      for (int c = 0; c < 3; ++c)
        if (!((*spec.color)[c] >= 0.0f && (*spec.color)[c] <= 1.0f))
          params::fail("levels", at + ": color components must be in [0, 1]");
    }
  }
  if (!level->is_number()) params::fail("levels", at + ": expected a number or {\"level\":c,…}");
  spec.level = level->get<double>();
  if (!std::isfinite(spec.level) || std::abs(spec.level) > 1e30)
    params::fail("levels", at + ": the level must be finite, |c| ≤ 1e30");
  return spec;
}

void read_levels(const IsoField&, const nlohmann::json& v, P& p, const CommandContext&) {
  if (!v.is_array() || v.empty()) params::fail("levels", "expected a non-empty list of levels");
  if (v.size() > kMaxVolumeLevels)
    params::fail("levels", "at most " + std::to_string(kMaxVolumeLevels) + " levels, got " + std::to_string(v.size()));
  std::vector<VolumeLevelSpec> levels;
  for (std::size_t i = 0; i < v.size(); ++i) levels.push_back(read_level(v[i], i));
  p.levels = std::move(levels);
}

// The double with the fewest digits that reads back as `f` (0.1f is logged as 0.1, not 0.10000000149011612).
double shortest(float f) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, f);
  return std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
}

// A level with neither style nor colour is logged as its number.
void write_levels(const IsoField&, const P& p, nlohmann::json& line) {
  if (!p.levels) return;
  nlohmann::json out = nlohmann::json::array();
  for (const VolumeLevelSpec& l : *p.levels) {
    if (!l.style && !l.color) {
      out.push_back(l.level);
      continue;
    }
    nlohmann::json e = {{"level", l.level}};
    if (l.style) e["style"] = *l.style;
    if (l.color) e["color"] = {shortest(l.color->x), shortest(l.color->y), shortest(l.color->z)};
    out.push_back(std::move(e));
  }
  line["levels"] = std::move(out);
}

}  // namespace

auto VolumeIsoCommand::declare() -> Schema {
  return Schema("volume.iso", "Set a volume's iso-level (the surface D = level) and further levels' silhouettes")
      .field("object", &P::object, {.required = true, .help = "A volume"})
      .field("level", &P::level,
             {.range = ParamRange::magnitude_at_most(1e30),
              .unit = "volume units",
              .default_text = "levels[0]",
              .ui = {"Iso-level"},
              .help = "Iso-level in the volume's units (HU for CT)"})
      .custom("levels", read_levels, write_levels,
              {.default_text = "kept",
               .type_text = "[c,…] | [{level,style,color},…]",
               .help = "Every level, the first the ray-cast surface, the others drawn as silhouettes only (Figs. "
                       "7.4–7.6, 7.12); an entry is a number or {\"level\":c,\"style\":S,\"color\":[r,g,b]} (sRGB "
                       "in [0,1]), at most 8"})
      .check([](P& p) {
        if (!p.level && !p.levels) params::fail("level", "give level, or levels");
        if (p.level && p.levels && *p.level != p.levels->front().level)
          params::fail("level", "differs from levels[0]; give one of them");
        if (!p.level) p.level = p.levels->front().level;
      })
      .label([](const P& p) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%g", p.level.value_or(0.0));
        std::string l = "Iso-level of '" + p.object + "' " + buf;
        if (p.levels && p.levels->size() > 1)
          l += " (+" + std::to_string(p.levels->size() - 1) + (p.levels->size() == 2 ? " level)" : " levels)");
        return l;
      });
}

std::optional<VolumeObject> VolumeIsoCommand::build(const Scene& scene) {
  VolumeObject v = require_volume(scene, p_.object);
  const double level = *p_.level;
  v.iso = level;
  if (p_.levels) {
    const VolumeLevelSpec& first = p_.levels->front();
    if (first.style) v.silhouette.style = *first.style;
    if (first.color) v.color = *first.color;
    v.more_levels.clear();
    for (std::size_t i = 1; i < p_.levels->size(); ++i) {
      const VolumeLevelSpec& spec = (*p_.levels)[i];
      VolumeIsoLevel l;
      l.iso = spec.level;
      l.style = spec.style.value_or("plain");
      l.color = spec.color.value_or(kLevelColors[(i - 1) % std::size(kLevelColors)]);
      v.more_levels.push_back(std::move(l));
    }
  }
  const bool in_range = level >= v.table->range_min() && level <= v.table->range_max();
  stats_["level"] = level;
  stats_["in_range"] = in_range;
  stats_["cells"] = v.table->cells_holding(level).size();
  stats_["levels"] = 1 + v.more_levels.size();
  return volume_with_silhouettes(v, scene.camera, &stats_);
}

}  // namespace trispline::core
