// ddm.fill and ddm.bake, and the layer construction ddm.paint shares. See ddm_commands.h.
// Source: seed ch. 5 (Eq. 5.1–5.2, §5.3, Fig. 5.11–5.12).
#include "core/commands/ddm_commands.h"

#include <chrono>
#include <memory>
#include <random>
#include <stdexcept>

#include "core/commands/json_fields.h"
#include "core/mesh/mesh_io.h"
#include "core/scene/primitives.h"

namespace trispline::core {
namespace jf = json_fields;
namespace {

constexpr std::size_t kMaxTileVertices = kMaxDdmLayerVertices;

DdmLayout layout_of(const std::string& s) {
  return s == "hex" ? DdmLayout::hex : s == "brick" ? DdmLayout::brick : DdmLayout::rect;
}

// "name": a number a (→ [a, a]) or [x, y].
glm::dvec2 get_vec2(const nlohmann::json& j, const char* field, glm::dvec2 fallback) {
  if (!jf::has(j, field)) return fallback;
  const nlohmann::json& v = j.at(field);
  if (v.is_number()) return glm::dvec2(jf::get_number(j, field));
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    throw CommandError(std::string("field '") + field + "': expected a number or [x, y]", field);
  const glm::dvec2 out(v[0].get<double>(), v[1].get<double>());
  if (!std::isfinite(out.x) || !std::isfinite(out.y))
    throw CommandError(std::string("field '") + field + "': must be finite", field);
  return out;
}

}  // namespace

DdmLayerSpec DdmLayerSpec::parse(const nlohmann::json& j, const CommandContext& ctx, bool require_tile) {
  DdmLayerSpec s;
  s.layer = jf::get_string(j, "layer");
  if (const std::string bad = object_name_error(s.layer); !bad.empty()) throw CommandError("field 'layer': " + bad, "layer");
  const std::string tile = require_tile ? jf::get_string(j, "tile") : jf::get_string(j, "tile", "thorn");
  if (tile.empty()) throw CommandError("field 'tile': must not be empty", "tile");
  s.tiles.push_back(tile);
  if (jf::has(j, "tiles")) {
    const nlohmann::json& more = j.at("tiles");
    if (!more.is_array()) throw CommandError("field 'tiles': expected a list of tiles", "tiles");
    for (const auto& t : more) {
      if (!t.is_string() || t.get<std::string>().empty())
        throw CommandError("field 'tiles': every entry must be a tile name or file", "tiles");
      s.tiles.push_back(t.get<std::string>());
    }
  }
  for (const std::string& t : s.tiles) s.tile_paths.push_back(is_generated_ddm_tile(t) ? std::filesystem::path()
                                                                                     : ctx.resolve(t));
  s.choice = jf::get_enum(j, "choice", {"pattern", "random"}, "pattern");
  s.seed = jf::get_int64(j, "seed", 0);
  s.layout = jf::get_enum(j, "layout", {"rect", "hex", "brick"}, require_tile ? "" : "rect");
  s.counts = jf::has(j, "counts") || require_tile ? jf::get_ivec2(j, "counts") : glm::ivec2(1, 1);
  s.height = require_tile ? jf::get_number(j, "height") : jf::get_number(j, "height", 0.1);
  if (!(s.height > 0.0)) throw CommandError("field 'height': must be > 0 (world units)", "height");
  s.base = jf::get_enum(j, "base", {"limit", "teapot_body", "uv"}, "limit");
  if (jf::has(j, "map_resolution")) {
    const glm::dvec2 r = get_vec2(j, "map_resolution", {0, 0});
    if (r.x != std::floor(r.x) || r.y != std::floor(r.y) || r.x < 2 || r.y < 2 || r.x > 4097 || r.y > 4097)
      throw CommandError("field 'map_resolution': whole numbers in [2, 4097] (samples per chart edge)",
                         "map_resolution");
    s.map_resolution = glm::ivec2(r);
  }
  s.transform.scale = get_vec2(j, "tile_scale", glm::dvec2(1.0));
  if (!(s.transform.scale.x > 0.0) || !(s.transform.scale.y > 0.0))
    throw CommandError("field 'tile_scale': must be > 0", "tile_scale");
  s.transform.rotate_deg = jf::get_number(j, "tile_rotate_deg", 0.0);
  s.transform.shift = get_vec2(j, "tile_shift", glm::dvec2(0.0));
  if (jf::has(j, "color")) {
    const glm::dvec3 c = jf::get_vec3(j, "color");
    if (!(glm::all(glm::greaterThanEqual(c, glm::dvec3(0.0))) && glm::all(glm::lessThanEqual(c, glm::dvec3(1.0)))))
      throw CommandError("field 'color': each component must be in [0, 1] (linear RGB)", "color");
    s.color = glm::vec3(c);
  }
  try {  // the layout's own checks, before anything is built
    (void)ddm_layout_cells(layout_of(s.layout), s.counts, 1);
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();  // "counts: …"
    throw CommandError("field 'counts': " + msg.substr(msg.find(':') + 2), "counts");
  }
  return s;
}

void DdmLayerSpec::write(nlohmann::json& j) const {
  // A tile file is logged absolute (replayable from anywhere), made relative again when a log is saved.
  auto logged = [&](std::size_t i) { return tile_paths[i].empty() ? tiles[i] : tile_paths[i].string(); };
  j["layer"] = layer;
  j["tile"] = logged(0);
  if (tiles.size() > 1) {
    nlohmann::json more = nlohmann::json::array();
    for (std::size_t i = 1; i < tiles.size(); ++i) more.push_back(logged(i));
    j["tiles"] = more;
    j["choice"] = choice;
    if (seed != 0) j["seed"] = seed;
  }
  j["layout"] = layout;
  j["counts"] = jf::to_json(counts);
  j["height"] = height;
  if (base != "limit") j["base"] = base;
  if (map_resolution) j["map_resolution"] = jf::to_json(*map_resolution);
  if (transform.scale != glm::dvec2(1.0)) j["tile_scale"] = {transform.scale.x, transform.scale.y};
  if (transform.rotate_deg != 0.0) j["tile_rotate_deg"] = transform.rotate_deg;
  if (transform.shift != glm::dvec2(0.0)) j["tile_shift"] = {transform.shift.x, transform.shift.y};
  if (color) j["color"] = jf::to_json(glm::dvec3(*color));
}

DdmTile load_ddm_tile(const std::string& name, const std::filesystem::path& path, const char* field) {
  if (is_generated_ddm_tile(name)) return make_ddm_tile(name);
  try {
    return canonical_ddm_tile(load_mesh(path), path.stem().string());
  } catch (const std::exception& e) {
    throw CommandError(std::string("field '") + field + "': " + e.what(), field);
  }
}

std::shared_ptr<DdmLayer> make_ddm_layer(const SceneObject& object, const DdmLayerSpec& spec, bool fill) {
  const char* deformed = object.ffd ? "an FFD lattice" : object.dffd ? "a DFFD split" : object.clip ? "a glTF clip"
                                                                                                    : nullptr;
  if (deformed)
    throw CommandError("field 'object': '" + object.name + "' has " + deformed +
                           "; tiles sit on the rest surface and would not follow it", "object");
  auto layer = std::make_shared<DdmLayer>();
  layer->name = spec.layer;
  layer->tile_sources = spec.tiles;
  for (std::size_t i = 0; i < spec.tiles.size(); ++i)
    layer->tiles.push_back(load_ddm_tile(spec.tiles[i], spec.tile_paths[i], i == 0 ? "tile" : "tiles"));
  layer->layout = layout_of(spec.layout);
  layer->counts = spec.counts;
  layer->height = spec.height;
  layer->transform = spec.transform;
  layer->color = spec.color;
  glm::ivec2 resolution{9, 9};
  int charts = 1;
  try {
    if (spec.base == "teapot_body") {
      if (object.source != "primitive:teapot")
        throw CommandError("field 'base': teapot_body needs the teapot primitive; '" + object.name + "' is " +
                               object.source, "base");
      layer->base = DdmBaseKind::teapot_body;
      layer->surface = std::make_shared<DdmSplineBase>(teapot_body_patches(), glm::ivec2(4, 2), glm::bvec2(true, false));
      resolution = {513, 257};
    } else if (spec.base == "uv") {
      layer->base = DdmBaseKind::uv;
      resolution = {1025, 1025};
      if (spec.map_resolution && spec.map_resolution->x != spec.map_resolution->y)
        throw CommandError("field 'map_resolution': a uv base is square ([R, R])", "map_resolution");
      layer->maps = std::make_shared<const DdmMaps>(
          ddm_rasterize_uv_maps(*object.rest_mesh, spec.map_resolution.value_or(resolution).x));
    } else {
      layer->base = DdmBaseKind::limit;
      layer->surface = std::make_shared<DdmSubdivBase>(*object.rest_mesh);
      charts = layer->surface->chart_count();
    }
  } catch (const std::invalid_argument& e) {
    throw CommandError("field 'base': '" + object.name + "': " + e.what(), "base");
  }
  if (fill) {
    // Checked before any cell is made: cells per chart × charts × tile vertices.
    std::size_t largest = 0;
    for (const DdmTile& t : layer->tiles) largest = std::max(largest, t.mesh.vertex_count());
    const std::size_t tiles = ddm_layout_cells(layer->layout, spec.counts, 1).size() * static_cast<std::size_t>(charts);
    if (tiles * largest > kMaxTileVertices)
      throw CommandError("field 'counts': " + std::to_string(tiles) + " tiles × " + std::to_string(largest) +
                             " vertices = " + std::to_string(tiles * largest) + " tile vertices (at most " +
                             std::to_string(kMaxTileVertices) + ")", "counts");
    layer->instances = ddm_layout_cells(layer->layout, spec.counts, charts);
    if (layer->tiles.size() > 1) {
      std::mt19937 rng(static_cast<std::uint32_t>(spec.seed));
      const std::size_t k = layer->tiles.size();
      int index = 0, row = 0, chart = -1;
      double row_v = -1.0;
      for (DdmInstance& c : layer->instances) {
        if (c.chart != chart) chart = c.chart, index = 0, row = 0, row_v = c.origin.y;
        if (c.origin.y != row_v) ++row, row_v = c.origin.y;
        c.tile = static_cast<int>(spec.choice == "random" ? rng() % k : static_cast<std::size_t>(index + row) % k);
        ++index;
      }
    }
  }
  try {
    ddm_layer_finish(*layer, spec.map_resolution.value_or(resolution));
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    const bool res = msg.rfind("map_resolution", 0) == 0;
    throw CommandError("field '" + std::string(res ? "map_resolution" : "base") + "': " + msg,
                       res ? "map_resolution" : "base");
  }
  return layer;
}

SceneObject with_ddm_layer(const SceneObject& object, std::shared_ptr<const DdmLayer> layer) {
  SceneObject out = object;
  bool replaced = false;
  for (auto& l : out.ddm_layers)
    if (l->name == layer->name) l = layer, replaced = true;
  if (!replaced) out.ddm_layers.push_back(std::move(layer));
  return out;
}

std::shared_ptr<const DdmLayer> find_ddm_layer(const SceneObject& object, const std::string& name) {
  for (const auto& l : object.ddm_layers)
    if (l->name == name) return l;
  throw CommandError("field 'layer': '" + object.name + "' has no tile layer '" + name + "'", "layer");
}

CommandPtr DdmFillCommand::parse(const nlohmann::json& j, const CommandContext& ctx) {
  auto c = std::make_unique<DdmFillCommand>();
  c->object_ = jf::get_string(j, "object");
  c->spec_ = DdmLayerSpec::parse(j, ctx, true);
  return c;
}

nlohmann::json DdmFillCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"object", object_}};
  spec_.write(j);
  return j;
}

std::string DdmFillCommand::label() const {
  return "Fill '" + object_ + "' with " + spec_.tiles.front() + " (" + spec_.layer + ")";
}

std::optional<SceneObject> DdmFillCommand::build(const Scene& scene) {
  const auto t0 = std::chrono::steady_clock::now();
  const SceneObject* object = scene.find(object_);
  if (!object) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  std::shared_ptr<const DdmLayer> layer = make_ddm_layer(*object, spec_, true);
  std::size_t tile_vertices = 0;
  for (const DdmTile& t : layer->tiles) tile_vertices = std::max(tile_vertices, t.mesh.vertex_count());
  stats_ = {{"charts", layer->maps->slot_of_chart.size()},
            {"tiles", layer->instances.size()},
            {"tile_vertices", tile_vertices},
            {"vertices", layer->mesh->vertex_count()},
            {"map_samples", layer->maps->slot_count() * layer->maps->samples_per_slot()},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return with_ddm_layer(*object, std::move(layer));
}

CommandPtr DdmBakeCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<DdmBakeCommand>();
  c->object_ = jf::get_string(j, "object");
  c->layer_ = jf::get_string(j, "layer");
  c->name_ = jf::get_string(j, "name");
  if (const std::string bad = object_name_error(c->name_); !bad.empty())
    throw CommandError("field 'name': " + bad, "name");
  if (jf::has(j, "frame")) c->frame_ = jf::get_number(j, "frame");
  return c;
}

nlohmann::json DdmBakeCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"object", object_}, {"layer", layer_}, {"name", name_}};
  if (frame_) j["frame"] = *frame_;
  return j;
}

std::string DdmBakeCommand::label() const { return "Bake " + object_ + "/" + layer_ + " as '" + name_ + "'"; }

std::optional<SceneObject> DdmBakeCommand::build(const Scene& scene) {
  const SceneObject* object = scene.find(object_);
  if (!object) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  const std::shared_ptr<const DdmLayer> layer = find_ddm_layer(*object, layer_);
  if (scene.find(name_)) throw CommandError("field 'name': an object named '" + name_ + "' already exists", "name");
  SceneObject baked;
  baked.name = name_;
  baked.source = "ddm.bake:" + object_ + "/" + layer_;
  baked.color = layer->color.value_or(object->color);
  const TriMesh mesh = frame_ ? ddm_layer_mesh(*layer, scene.timeline.time_of_frame(*frame_)) : *layer->mesh;
  baked.rest_mesh = std::make_shared<const TriMesh>(transformed(mesh, object->transform));
  baked.refresh();
  stats_ = {{"vertices", baked.rest_mesh->vertex_count()}, {"triangles", baked.rest_mesh->triangle_count()}};
  return baked;
}

CommandPtr DdmColorCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<DdmColorCommand>();
  c->object_ = jf::get_string(j, "object");
  c->layer_ = jf::get_string(j, "layer");
  if (!j.contains("color")) throw CommandError("field 'color': missing ([r, g, b] in [0, 1], or null)", "color");
  if (!j.at("color").is_null()) {
    const glm::dvec3 rgb = jf::get_vec3(j, "color");
    if (!(glm::all(glm::greaterThanEqual(rgb, glm::dvec3(0.0))) && glm::all(glm::lessThanEqual(rgb, glm::dvec3(1.0)))))
      throw CommandError("field 'color': each component must be in [0, 1] (linear RGB)", "color");
    c->color_ = glm::vec3(rgb);
  }
  return c;
}

nlohmann::json DdmColorCommand::to_json() const {
  return {{"cmd", id()},
          {"object", object_},
          {"layer", layer_},
          {"color", color_ ? jf::to_json(glm::dvec3(*color_)) : nlohmann::json(nullptr)}};
}

std::string DdmColorCommand::label() const { return "Colour of tile layer " + object_ + "/" + layer_; }

std::optional<SceneObject> DdmColorCommand::build(const Scene& scene) {
  const SceneObject* object = scene.find(object_);
  if (!object) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  const std::shared_ptr<const DdmLayer> layer = find_ddm_layer(*object, layer_);
  auto recoloured = std::make_shared<DdmLayer>(*layer);  // tiles, maps and mesh stay shared
  recoloured->color = color_;
  return with_ddm_layer(*object, recoloured);
}

CommandPtr DdmRemoveCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<DdmRemoveCommand>();
  c->object_ = jf::get_string(j, "object");
  c->layer_ = jf::get_string(j, "layer");
  return c;
}

nlohmann::json DdmRemoveCommand::to_json() const {
  return {{"cmd", id()}, {"object", object_}, {"layer", layer_}};
}

std::string DdmRemoveCommand::label() const { return "Remove tile layer " + object_ + "/" + layer_; }

std::optional<SceneObject> DdmRemoveCommand::build(const Scene& scene) {
  const SceneObject* object = scene.find(object_);
  if (!object) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  const std::shared_ptr<const DdmLayer> layer = find_ddm_layer(*object, layer_);
  SceneObject out = *object;
  std::erase(out.ddm_layers, layer);
  stats_ = {{"tiles", layer->instances.size()}, {"vertices", layer->mesh ? layer->mesh->vertex_count() : 0}};
  return out;
}

}  // namespace trispline::core
