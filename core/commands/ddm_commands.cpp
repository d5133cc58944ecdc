// ddm.fill and ddm.bake. See ddm_commands.h. Source: seed ch. 5 (Eq. 5.1–5.2, §5.3).
#include "core/commands/ddm_commands.h"

#include <chrono>
#include <memory>
#include <stdexcept>

#include "core/commands/json_fields.h"
#include "core/ddm/ddm_layer.h"
#include "core/mesh/mesh_io.h"
#include "core/scene/primitives.h"

namespace trispline::core {
namespace jf = json_fields;
namespace {

constexpr std::size_t kMaxTileVertices = 50'000'000;

DdmLayout layout_of(const std::string& s) {
  return s == "hex" ? DdmLayout::hex : s == "brick" ? DdmLayout::brick : DdmLayout::rect;
}

}  // namespace

CommandPtr DdmFillCommand::parse(const nlohmann::json& j, const CommandContext& ctx) {
  auto c = std::make_unique<DdmFillCommand>();
  c->object_ = jf::get_string(j, "object");
  c->layer_ = jf::get_string(j, "layer");
  if (c->layer_.empty()) throw CommandError("field 'layer': must not be empty", "layer");
  c->tile_ = jf::get_string(j, "tile");
  if (c->tile_.empty()) throw CommandError("field 'tile': must not be empty", "tile");
  if (!is_generated_ddm_tile(c->tile_)) c->tile_path_ = ctx.resolve(c->tile_);
  c->layout_ = jf::get_enum(j, "layout", {"rect", "hex", "brick"});
  c->counts_ = jf::get_ivec2(j, "counts");
  c->height_ = jf::get_number(j, "height");
  if (!(c->height_ > 0.0)) throw CommandError("field 'height': must be > 0 (world units)", "height");
  c->base_ = jf::get_enum(j, "base", {"limit", "teapot_body"}, "limit");
  try {  // the layout's own checks, before anything is built
    (void)ddm_layout_cells(layout_of(c->layout_), c->counts_, 1);
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();  // "counts: …"
    throw CommandError("field 'counts': " + msg.substr(msg.find(':') + 2), "counts");
  }
  return c;
}

nlohmann::json DdmFillCommand::to_json() const {
  // A tile file is logged absolute (replayable from anywhere), made relative again when a log is saved.
  const std::string tile = tile_path_.empty() ? tile_ : tile_path_.string();
  nlohmann::json j = {{"cmd", id()},         {"object", object_}, {"layer", layer_},   {"tile", tile},
                      {"layout", layout_},   {"counts", jf::to_json(counts_)},        {"height", height_}};
  if (base_ != "limit") j["base"] = base_;
  return j;
}

std::string DdmFillCommand::label() const { return "Fill '" + object_ + "' with " + tile_ + " (" + layer_ + ")"; }

std::optional<SceneObject> DdmFillCommand::build(const Scene& scene) {
  const auto t0 = std::chrono::steady_clock::now();
  const SceneObject* object = scene.find(object_);
  if (!object) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  const char* deformed = object->ffd ? "an FFD lattice" : object->dffd ? "a DFFD split" : object->clip ? "a glTF clip"
                                                                                                      : nullptr;
  if (deformed)
    throw CommandError("field 'object': '" + object_ + "' has " + deformed +
                           "; tiles sit on the rest surface and would not follow it", "object");
  DdmTile tile;
  if (is_generated_ddm_tile(tile_)) {
    tile = make_ddm_tile(tile_);
  } else {
    try {
      tile = canonical_ddm_tile(load_mesh(tile_path_), tile_path_.stem().string());
    } catch (const std::exception& e) {
      throw CommandError("field 'tile': " + std::string(e.what()), "tile");
    }
  }
  std::unique_ptr<DdmBase> base;
  if (base_ == "teapot_body") {
    if (object->source != "primitive:teapot")
      throw CommandError("field 'base': teapot_body needs the teapot primitive; '" + object_ + "' is " +
                             object->source, "base");
    base = std::make_unique<DdmSplineBase>(teapot_body_patches());
  } else {
    try {
      base = std::make_unique<DdmSubdivBase>(*object->rest_mesh);
    } catch (const std::invalid_argument& e) {
      throw CommandError("field 'object': '" + object_ + "': " + e.what(), "object");
    }
  }
  auto layer = std::make_shared<DdmLayer>();
  layer->name = layer_;
  layer->tile_source = tile_;
  layer->base = base_ == "teapot_body" ? DdmBaseKind::teapot_body : DdmBaseKind::limit;
  layer->layout = layout_of(layout_);
  layer->counts = counts_;
  layer->height = height_;
  // Checked before any cell is made: cells per chart × charts × tile vertices.
  const std::size_t tiles =
      ddm_layout_cells(layer->layout, counts_, 1).size() * static_cast<std::size_t>(base->chart_count());
  const std::size_t vertices = tiles * tile.mesh.vertex_count();
  if (vertices > kMaxTileVertices)
    throw CommandError("field 'counts': " + std::to_string(tiles) + " tiles × " +
                           std::to_string(tile.mesh.vertex_count()) + " vertices = " + std::to_string(vertices) +
                           " tile vertices (at most " + std::to_string(kMaxTileVertices) + ")", "counts");
  layer->instances = ddm_layout_cells(layer->layout, counts_, base->chart_count());
  layer->mesh = std::make_shared<const TriMesh>(ddm_evaluate(*base, tile, layer->instances, height_));
  layer->tile = std::move(tile);
  SceneObject out = *object;
  bool replaced = false;
  for (auto& l : out.ddm_layers)
    if (l->name == layer_) l = layer, replaced = true;
  if (!replaced) out.ddm_layers.push_back(layer);
  stats_ = {{"charts", base->chart_count()},
            {"tiles", layer->instances.size()},
            {"tile_vertices", layer->tile.mesh.vertex_count()},
            {"vertices", layer->mesh->vertex_count()},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

CommandPtr DdmBakeCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<DdmBakeCommand>();
  c->object_ = jf::get_string(j, "object");
  c->layer_ = jf::get_string(j, "layer");
  c->name_ = jf::get_string(j, "name");
  if (c->name_.empty()) throw CommandError("field 'name': must not be empty", "name");
  return c;
}

nlohmann::json DdmBakeCommand::to_json() const {
  return {{"cmd", id()}, {"object", object_}, {"layer", layer_}, {"name", name_}};
}

std::string DdmBakeCommand::label() const { return "Bake " + object_ + "/" + layer_ + " as '" + name_ + "'"; }

std::optional<SceneObject> DdmBakeCommand::build(const Scene& scene) {
  const SceneObject* object = scene.find(object_);
  if (!object) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  std::shared_ptr<const DdmLayer> layer;
  for (const auto& l : object->ddm_layers)
    if (l->name == layer_) layer = l;
  if (!layer) throw CommandError("field 'layer': '" + object_ + "' has no tile layer '" + layer_ + "'", "layer");
  if (scene.find(name_)) throw CommandError("field 'name': an object named '" + name_ + "' already exists", "name");
  SceneObject baked;
  baked.name = name_;
  baked.source = "ddm.bake:" + object_ + "/" + layer_;
  baked.color = object->color;
  baked.rest_mesh = std::make_shared<const TriMesh>(transformed(*layer->mesh, object->transform));
  baked.refresh();
  stats_ = {{"vertices", baked.rest_mesh->vertex_count()}, {"triangles", baked.rest_mesh->triangle_count()}};
  return baked;
}

}  // namespace trispline::core
