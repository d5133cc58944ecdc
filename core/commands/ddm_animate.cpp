// ddm.animate. See ddm_animate.h. Sources: seed §5.4.2 (animated DDMs, texture-space transforms), Eq. 5.3
// (metamorphosis).
#include "core/commands/ddm_animate.h"

#include <algorithm>
#include <cmath>

#include "core/commands/anim_keys.h"

namespace trispline::core {
namespace {

using P = DdmAnimateParams;
using AnimateField = ParamSchema<P>::Field;

// "morph_tile" (one tile; "" removes the layer's morph) or "morph_tiles" (a non-empty list, one per layer tile).
void read_morph(const AnimateField& f, const nlohmann::json& v, P& p, const CommandContext& ctx) {
  p.morph.emplace(), p.morph_paths.clear();
  if (v.is_string() && v.get<std::string>().empty() && f.doc.name == "morph_tile") {
    p.morph->push_back(""), p.morph_paths.emplace_back();
    return;
  }
  append_ddm_tiles(v, f.doc.name, f.doc.name == "morph_tiles", ctx, *p.morph, p.morph_paths);
  if (p.morph->empty()) params::fail(f.doc.name, "expected a list of tiles, one per layer tile");
}

// One morph tile is logged as "morph_tile", several as "morph_tiles".
void write_morph(const AnimateField& f, const P& p, nlohmann::json& line) {
  if (!p.morph || (p.morph->size() == 1) != (f.doc.name == "morph_tile")) return;
  const nlohmann::json tiles = ddm_tile_files(*p.morph, p.morph_paths, 0);
  line[f.doc.name] = tiles.size() == 1 ? tiles[0] : tiles;
}

// Largest |degrees| of a rotation key: a thousand turns, ample for a wheel spinning through a long shot.
constexpr double kMaxKeyedDegrees = 360'000.0;

// Every key of a [frame, value] list finite with its value in [lo, hi] (lo excluded when `above`).
void check_keys(const std::optional<std::vector<glm::dvec2>>& keys, const char* field, double lo, double hi,
                bool above) {
  if (!keys) return;
  for (std::size_t i = 0; i < keys->size(); ++i) {
    const double v = (*keys)[i].y;
    if (!std::isfinite((*keys)[i].x) || !std::isfinite(v) || v > hi || (above ? !(v > lo) : v < lo))
      params::fail(field, "key " + std::to_string(i) + ": the value must be finite and in " + (above ? "(" : "[") +
                              params::format_number(lo) + ", " + params::format_number(hi) + "]");
  }
}

}  // namespace

auto DdmAnimateCommand::declare() -> Schema {
  return Schema("ddm.animate",
                "Animate a tile layer: texture-space offset, rotation, scale, w and metamorphosis (seed §5.4.2)")
      .field("object", &P::object, {.required = true, .help = "The object holding the layer"})
      .field("layer", &P::layer, {.required = true, .help = "The layer to animate"})
      .field("clear", &P::clear,
             {.write = ParamWrite::UnlessDefault,
              .help = "Remove the layer's animation first (the other fields of the line then apply)"})
      .custom("morph_tile", read_morph, write_morph,
              {.default_text = "kept",
               .type_text = "string",
               .help = "Metamorphosis partner of the layer's tile (as ddm.fill's tile), of the same topology; "
                       "\"\" removes it"})
      .custom("morph_tiles", read_morph, write_morph,
              {.default_text = "kept",
               .type_text = "[string,…]",
               .help = "One morph tile per tile of a several-tile layer (instead of morph_tile)"})
      .field("alpha_keys", &P::alpha_keys,
             {.default_text = "kept",
              .type_text = "[[frame,α],…]",
              .help = "[timeline frame, α] keys of the metamorphosis, V = V1·(1 − α) + V2·α (Eq. 5.3)"})
      .field("offset_keys", &P::offset_keys,
             {.default_text = "kept",
              .type_text = "[[frame,du,dv],…]",
              .help = "[frame, du, dv] keys of the tiles' texture-space offset, chart parameter units"})
      .field("offset_velocity", &P::offset_velocity,
             {.default_text = "kept", .type_text = "[du,dv]", .help = "Offset added per second, chart parameter units"})
      .field("rotate_keys", &P::rotate_keys,
             {.default_text = "kept",
              .type_text = "[[frame,degrees],…]",
              .help = "[frame, degrees] keys of the tiles' rotation in texture space about their cells' centres, "
                      "added to the layer's rotate_deg"})
      .field("scale_keys", &P::scale_keys,
             {.default_text = "kept",
              .type_text = "[[frame,s],…]",
              .help = "[frame, s] keys of the tiles' texture-space scale about their cells' centres, s > 0 times "
                      "the layer's scale"})
      .field("w_keys", &P::w_keys,
             {.default_text = "kept",
              .type_text = "[[frame,w],…]",
              .help = "[frame, w] keys of the tiles' height along the surface normal, w > 0 times the layer's height"})
      .check([](const P& p) {
        check_keys(p.rotate_keys, "rotate_keys", -kMaxKeyedDegrees, kMaxKeyedDegrees, false);
        check_keys(p.scale_keys, "scale_keys", 0.0, kMaxKeyedWeight, true);
        check_keys(p.w_keys, "w_keys", 0.0, kMaxKeyedWeight, true);
      })
      .field("alpha", &P::alpha, {.default_text = "kept", .help = "α shown when there are no alpha keys (0 at first)"})
      .choice("interpolation", &P::interpolation, {"linear", "constant", "smooth"},
              {.write = ParamWrite::UnlessDefault, .help = "How this line's keys move to the next key"})
      .label([](const P& p) { return "Animate tiles " + p.object + "/" + p.layer; })
      .failure_field("morph_tile");
}

std::optional<SceneObject> DdmAnimateCommand::build(const Scene& scene) {
  const SceneObject* object = &require_object(scene, p_.object);
  auto layer = std::make_shared<DdmLayer>(*find_ddm_layer(*object, p_.layer));
  const KeyInterpolation interpolation = interpolation_of(p_.interpolation);
  if (p_.clear) {
    layer->morph_sources.clear(), layer->morph_tiles.clear(), layer->alpha_keys.clear(), layer->offset_keys.clear();
    layer->rotate_keys.clear(), layer->scale_keys.clear(), layer->w_keys.clear();
    layer->alpha = 0.0, layer->offset_velocity = glm::dvec2(0.0);
  }
  if (p_.morph) {
    const bool remove = p_.morph->size() == 1 && p_.morph->front().empty();
    layer->morph_sources.clear(), layer->morph_tiles.clear();
    if (!remove) {
      if (layer->tile_clip)
        throw CommandError("field 'morph_tile': the layer's tile plays a clip (tile_clip); it cannot morph too",
                           "morph_tile");
      if (p_.morph->size() != layer->tiles.size())
        throw CommandError("field 'morph_tile': the layer has " + std::to_string(layer->tiles.size()) +
                               " tiles; give one morph tile per tile (morph_tiles)",
                           "morph_tile");
      for (std::size_t i = 0; i < p_.morph->size(); ++i) {
        DdmTile partner = load_ddm_tile((*p_.morph)[i], ddm_tile_file(*p_.morph, p_.morph_paths, i), "morph_tile");
        try {
          require_same_ddm_topology(layer->tiles[i], partner);
        } catch (const std::invalid_argument& e) {
          throw CommandError(std::string("field 'morph_tile': ") + e.what(), "morph_tile");
        }
        layer->morph_sources.push_back((*p_.morph)[i]);
        layer->morph_tiles.push_back(std::move(partner));
      }
    }
  }
  if (p_.alpha_keys)
    layer->alpha_keys = weight_keys_from_frames(*p_.alpha_keys, scene.timeline, interpolation, "alpha_keys");
  if (p_.rotate_keys)
    layer->rotate_keys = weight_keys_from_frames(*p_.rotate_keys, scene.timeline, interpolation, "rotate_keys");
  if (p_.scale_keys)
    layer->scale_keys = weight_keys_from_frames(*p_.scale_keys, scene.timeline, interpolation, "scale_keys");
  if (p_.w_keys) layer->w_keys = weight_keys_from_frames(*p_.w_keys, scene.timeline, interpolation, "w_keys");
  if (p_.offset_keys)
    layer->offset_keys = keys_from_frames(*p_.offset_keys, true, scene.timeline, interpolation, "offset_keys");
  if (p_.offset_velocity) layer->offset_velocity = *p_.offset_velocity;
  if (p_.alpha) layer->alpha = *p_.alpha;
  if (layer->morph_tiles.empty() && (!layer->alpha_keys.empty() || layer->alpha != 0.0))
    throw CommandError("field 'alpha_keys': layer '" + p_.layer + "' has no morph tile to blend to (give morph_tile)",
                       "alpha_keys");
  layer->mesh = std::make_shared<const TriMesh>(ddm_layer_mesh(*layer, 0.0));
  stats_ = {{"alpha_keys", layer->alpha_keys.size()},   {"offset_keys", layer->offset_keys.size()},
            {"rotate_keys", layer->rotate_keys.size()}, {"scale_keys", layer->scale_keys.size()},
            {"w_keys", layer->w_keys.size()},           {"morph", !layer->morph_tiles.empty()},
            {"vertices", layer->mesh->vertex_count()}};
  return with_ddm_layer(*object, std::move(layer));
}

}  // namespace trispline::core
