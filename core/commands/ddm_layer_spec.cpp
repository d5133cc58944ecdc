// The layer construction ddm.fill and ddm.paint share. See ddm_layer_spec.h.
// Source: seed ch. 5 (Eq. 5.1–5.2, §5.3, Fig. 5.11–5.12).
#include "core/commands/ddm_layer_spec.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <memory>
#include <mutex>
#include <random>
#include <stdexcept>

#include "core/ddm/ddm_auto_uv.h"
#include "core/ddm/ddm_chart_size.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/model_load.h"
#include "core/params/codecs.h"
#include "core/scene/ddm_follow.h"
#include "core/scene/primitives.h"

namespace trispline::core {
namespace {

using S = DdmLayerSpec;
using Field = ParamSchema<S>::Field;

// "tile": the first tile, not empty.
void read_tile(const Field& f, const nlohmann::json& v, S& s, const CommandContext& ctx) {
  s.tiles.clear(), s.tile_paths.clear();
  append_ddm_tiles(v, f.doc.name, false, ctx, s.tiles, s.tile_paths);
}

void write_tile(const Field& f, const S& s, nlohmann::json& line) {
  if (!s.tiles.empty()) line[f.doc.name] = ddm_tile_file(s.tiles, s.tile_paths, 0);
}

// "tiles": the tiles after the first, none empty.
void read_more_tiles(const Field& f, const nlohmann::json& v, S& s, const CommandContext& ctx) {
  s.tile_paths.resize(s.tiles.size());
  append_ddm_tiles(v, f.doc.name, true, ctx, s.tiles, s.tile_paths);
}

void write_more_tiles(const Field& f, const S& s, nlohmann::json& line) {
  if (s.tiles.size() >= 2) line[f.doc.name] = ddm_tile_files(s.tiles, s.tile_paths, 1);
}

// "map_resolution": a whole number R (read as [R, R]) or [Ru, Rv], whole numbers in the field's range (9.0 is 9).
void read_map_resolution(const Field& f, const nlohmann::json& v, S& s, const CommandContext&) {
  const glm::dvec2 r = UniformVec2Codec::read(v, f.doc.name);
  for (int i = 0; i < 2; ++i) {
    if (r[i] != std::floor(r[i])) params::fail(f.doc.name, "must be whole numbers");
    if (!f.range.contains(r[i])) params::fail(f.doc.name, params::range_error(f.range, f.doc.unit, r[i], i, 2));
  }
  s.map_resolution = glm::ivec2(r);
}

void read_base(const Field& f, const nlohmann::json& v, S& s, const CommandContext&) {
  const std::string name = params::Codec<std::string>::read(v, f.doc.name);
  for (DdmBaseKind k : {DdmBaseKind::limit, DdmBaseKind::teapot_body, DdmBaseKind::uv, DdmBaseKind::auto_uv})
    if (name == ddm_base_name(k)) {
      s.base = k;
      return;
    }
  params::fail(f.doc.name, "'" + name + "' is not one of limit|teapot_body|uv|auto_uv");
}

void write_base(const Field& f, const S& s, nlohmann::json& line) {
  if (s.base) line[f.doc.name] = ddm_base_name(*s.base);
}

void write_map_resolution(const Field& f, const S& s, nlohmann::json& line) {
  if (s.map_resolution) line[f.doc.name] = params::Codec<glm::ivec2>::write(*s.map_resolution);
}

const ParamSchema<DdmTileTransform>& tile_transform_schema() {
  using T = DdmTileTransform;
  static const ParamSchema<T> s =
      ParamSchema<T>("tile_transform", "A layer's transform in its tiles' texture space")
          .field_as<UniformVec2Codec>(
              "tile_scale", &T::scale,
              {.write = ParamWrite::UnlessDefault,
               .range = ParamRange::above(0),
               .help = "Tile units per cell along x, y (one number: both); 1 = the tile fills its cell"})
          .field("tile_rotate_deg", &T::rotate_deg,
                 {.write = ParamWrite::UnlessDefault,
                  .unit = "degrees",
                  .help = "Rotation of the tile in its cell, counter-clockwise"})
          .field_as<UniformVec2Codec>("tile_shift", &T::shift,
                                      {.write = ParamWrite::UnlessDefault,
                                       .unit = "cell units",
                                       .help = "Shift of the tile in its cell (one number: both)"});
  return s;
}

ParamSchema<S> make_layer_schema(bool fill) {
  const auto several = [](const S& s) { return s.tiles.size() > 1; };
  return ParamSchema<S>("ddm.layer", "The fields that make a tile layer")
      .custom("tile", read_tile, write_tile,
              {.required = fill,
               .default_text = "thorn",
               .type_text = "string",
               .help = "A generated tile (thorn, chain, hex, flower, hair) or a mesh file (OBJ/PLY/glTF) relative to "
                       "the log's folder, logged absolute"})
      .custom("tiles", read_more_tiles, write_more_tiles,
              {.default_text = "[]",
               .type_text = "[string,…]",
               .help = "More tiles for the layer (as tile), chosen per cell by choice"})
      .choice("tile_up", &S::tile_up, {"x", "y", "z"},
              {.write = ParamWrite::UnlessDefault,
               .ui = {"Up axis"},
               .help = "The tile files' axis that stands up from the surface (w): y for glTF figures, which stand on "
                       "y; generated tiles stand on z"})
      .field("tile_clip", &S::tile_clip,
             {.type_text = "string",
              .help = "An articulated tile (seed Fig. 5.13): every tile plays this animation of the glTF tile file "
                      "(\"\" = its first), looping from time 0; one tile, no morph"})
      .choice("choice", &S::choice, {"pattern", "random"},
              {.write_if = several,
               .help = "With several tiles: cell k of row r gets tile (k + r) mod #tiles, or one drawn with seed"})
      .field("seed", &S::seed,
             {.write = ParamWrite::UnlessDefault, .write_if = several, .help = "Seed of random's mt19937"})
      .choice("layout", &S::layout, {"rect", "hex", "brick"},
              {.required = fill, .help = "Cells per chart: rect n × m; hex and brick shift odd rows (n ≥ 2)"})
      .field("counts", &S::counts,
             {.default_text = fill ? "required without tile_size" : "[1,1]",
              .help = "Cells per chart n × m (the seed's parametric layouts); not with tile_size"})
      .field("tile_size", &S::tile_size,
             ParamSchema<S>::object_length("Tile size", {0.1, 0.001, 1.0, 0.01},
                                           "Tile width in object space: every chart gets the cells that make its "
                                           "tiles this size (not with counts)"))
      .field("max_vertices", &S::max_vertices,
             {.range = ParamRange{1, double(kMaxDdmLayerVertices)},
              .unit = "tile vertices",
              .default_text = "10000000",
              .help = "Refuse a layer of more tile vertices than this, counted before it is built (uv and auto_uv: "
                      "after the cells off the UV islands are pruned; ddm.paint: after the stroke)"})
      .field(
          "height", &S::height,
          ParamSchema<S>::object_length("Height", {0.033, 0.0005, 1.0, 0.01},
                                        "World units (object space) per tile unit of w, along the base normal", fill))
      .custom(
          "base", read_base, write_base,
          {.default_text = "the object's: teapot_body (teapot primitive), uv (texture coordinates), else auto_uv",
           .type_text = "limit|teapot_body|uv|auto_uv",
           .help =
               "limit: Loop limit surface, three charts per triangle; teapot_body: the teapot's body patches as one "
               "chart; uv: the mesh's texture coordinates; auto_uv: automatic ones (seams, CGAL LSCM, even density)"})
      .custom("map_resolution", read_map_resolution, write_map_resolution,
              {.range = ParamRange{2, 4097},
               .unit = "samples per chart edge",
               .default_text = "[9,9] limit, [513,257] teapot_body, [1025,1025] uv and auto_uv",
               .type_text = "integer or [a,b]",
               .help = "P/N map samples per chart edge; square for uv"})
      .embed(&S::transform, tile_transform_schema())
      .field("color", &S::color,
             {.range = ParamRange{0, 1},
              .unit = "linear RGB",
              .default_text = "the object's",
              .type_text = "[r,g,b]",
              .help = "The layer's own colour"})
      .check([fill](S& s) {  // the layout's own checks, before anything is built
        if (s.tile_clip && (s.tiles.size() != 1 || is_generated_ddm_tile(s.tiles[0])))
          params::fail("tile_clip", "plays an animation of the layer's one tile, a glTF file");
        if (s.counts && s.tile_size)
          params::fail("tile_size", "give tile_size (world units) or counts (cells per chart), not both");
        if (fill && !s.counts && !s.tile_size) params::fail("counts", "ddm.fill needs counts or tile_size");
        if (s.tile_size) return;
        const glm::ivec2 counts = s.counts.value_or(glm::ivec2(1));
        try {
          ddm_check_layout_counts(s.layout, counts);
        } catch (const std::invalid_argument& e) {
          const std::string msg = e.what();  // "counts: …"
          params::fail("counts", msg.substr(msg.find(':') + 2));
        }
        // One chart's cells, before any is made: each tile has a vertex at least, so more cells than the layer's
        // vertex budget can never be a layer (ddm.fill and ddm.paint weigh the charts together later).
        if (const std::size_t cells = ddm_layout_cell_count(s.layout, counts); cells > kMaxDdmLayerVertices)
          params::fail("counts", "[" + std::to_string(counts.x) + ", " + std::to_string(counts.y) + "] makes " +
                                     std::to_string(cells) + " cells on one chart, over the layer budget of " +
                                     std::to_string(kMaxDdmLayerVertices) + " tile vertices");
      });
}

// The teapot primitive's body patches as one chart, periodic round the pot; CommandError ("base") on another object.
std::shared_ptr<DdmBase> teapot_body_base(const SceneObject& object) {
  if (object.source != "primitive:teapot")
    throw CommandError(
        "field 'base': teapot_body needs the teapot primitive; '" + object.name + "' is " + object.source, "base");
  return std::make_shared<DdmSplineBase>(teapot_body_patches(), glm::ivec2(4, 2), glm::bvec2(true, false));
}

}  // namespace

const ParamSchema<DdmLayerSpec>& ddm_layer_schema(bool fill) {
  static const ParamSchema<S> fill_schema = make_layer_schema(true), paint_schema = make_layer_schema(false);
  return fill ? fill_schema : paint_schema;
}

std::string ddm_tile_file(const std::vector<std::string>& names, const std::vector<std::filesystem::path>& paths,
                          std::size_t i) {
  return i < paths.size() && !paths[i].empty() ? paths[i].string() : names.at(i);
}

std::filesystem::path resolve_ddm_tile(const std::string& name, const CommandContext& ctx) {
  return name.empty() || is_generated_ddm_tile(name) ? std::filesystem::path() : ctx.resolve(name);
}

nlohmann::json ddm_tile_files(const std::vector<std::string>& names, const std::vector<std::filesystem::path>& paths,
                              std::size_t first) {
  nlohmann::json files = nlohmann::json::array();
  for (std::size_t i = first; i < names.size(); ++i) files.push_back(ddm_tile_file(names, paths, i));
  return files;
}

void append_ddm_tiles(const nlohmann::json& v, const std::string& field, bool list, const CommandContext& ctx,
                      std::vector<std::string>& names, std::vector<std::filesystem::path>& paths) {
  const std::vector<std::string> read = list ? params::Codec<std::vector<std::string>>::read(v, field)
                                             : std::vector<std::string>{params::Codec<std::string>::read(v, field)};
  for (std::size_t i = 0; i < read.size(); ++i) {
    if (read[i].empty())
      params::fail(field, list ? "element " + std::to_string(i) + " is empty: every entry must be a tile name or file"
                               : std::string("must not be empty"));
    paths.push_back(resolve_ddm_tile(read[i], ctx));
    names.push_back(read[i]);
  }
}

DdmTile load_ddm_tile(const std::string& name, const std::filesystem::path& path, const char* field, int up_axis) {
  if (is_generated_ddm_tile(name)) return make_ddm_tile(name);
  try {
    LoadedModel model = load_model(path);  // a textured tile keeps its materials (seed Fig. 5.12)
    ddm_tile_up(model.mesh, up_axis);
    return canonical_ddm_tile(model.mesh, path.stem().string(), std::move(model.materials));
  } catch (const std::exception& e) {
    throw CommandError(std::string("field '") + field + "': " + e.what(), field);
  }
}

namespace {
// The clip `clip` of the layer's one tile file, framed as its rest tile was (ddm_tile_up, canonical_ddm_tile_frame).
// Throws CommandError (field "tile_clip").
std::shared_ptr<const DdmTileClip> load_ddm_tile_clip(const DdmLayer& layer, const std::filesystem::path& path,
                                                      const std::string& clip, int up_axis) {
  try {
    auto out = std::make_shared<DdmTileClip>();
    out->clip = MeshClip::load(path, clip);
    out->up_axis = up_axis;
    TriMesh rest = load_model(path).mesh;
    ddm_tile_up(rest, up_axis);
    out->frame = canonical_ddm_tile_frame(rest, layer.tiles[0].name);
    out->pose(layer.tiles[0], 0.0);  // the vertex counts agree and the first pose is finite
    return out;
  } catch (const std::exception& e) {
    throw CommandError(std::string("field 'tile_clip': ") + e.what(), "tile_clip");
  }
}
}  // namespace

namespace {
// The tile vertices of a uv layer's cells that the UV islands kept, against spec.max_vertices: refused before any
// tile is evaluated, naming the field that made the cells.
void ddm_check_kept_vertices(const DdmLayerSpec& spec, const DdmLayer& layer, std::size_t cells_laid) {
  std::size_t vertices = 0;
  for (const DdmInstance& c : layer.instances)
    vertices += layer.tiles[static_cast<std::size_t>(c.tile)].mesh.vertex_count();
  const std::size_t limit = spec.max_vertices ? static_cast<std::size_t>(*spec.max_vertices) : kMaxDdmLayerVertices;
  if (vertices <= limit) return;
  const char* field = spec.tile_size ? "tile_size" : "counts";
  char size[80] = "";
  if (spec.tile_size) std::snprintf(size, sizeof size, "tiles %g world units across make ", *spec.tile_size);
  throw CommandError("field '" + std::string(field) + "': " + size + std::to_string(layer.instances.size()) +
                         " tiles on the UV islands (of " + std::to_string(cells_laid) + " cells) with " +
                         std::to_string(vertices) + " tile vertices (at most " + std::to_string(limit) +
                         (spec.max_vertices ? ", max_vertices)" : ")"),
                     field);
}
}  // namespace

std::shared_ptr<DdmLayer> make_ddm_layer(const SceneObject& object, const std::string& name, const DdmLayerSpec& spec,
                                         bool fill, const ProgressSink* progress) {
  check_progress(progress, 0.0);
  auto layer = std::make_shared<DdmLayer>();
  layer->name = name;
  layer->tile_sources = spec.tiles;
  const int up_axis = spec.tile_up == "x" ? 0 : spec.tile_up == "y" ? 1 : 2;
  for (std::size_t i = 0; i < spec.tiles.size(); ++i)
    layer->tiles.push_back(load_ddm_tile(spec.tiles[i], ddm_tile_file(spec.tiles, spec.tile_paths, i),
                                         i == 0 ? "tile" : "tiles", up_axis));
  if (spec.tile_clip)
    layer->tile_clip =
        load_ddm_tile_clip(*layer, ddm_tile_file(spec.tiles, spec.tile_paths, 0), *spec.tile_clip, up_axis);
  layer->layout = spec.layout;
  layer->counts = spec.counts.value_or(glm::ivec2(1));
  layer->tile_size = spec.tile_size;
  layer->height = spec.height;
  layer->transform = spec.transform;
  layer->color = spec.color;
  layer->host_mesh = object.rest_mesh;  // tiles follow this surface where the object's own surface moves
  glm::ivec2 resolution{9, 9};
  int charts = 1;
  std::shared_ptr<const TriMesh> base_mesh = object.rest_mesh;  // the mesh the base is made from
  const DdmBaseKind base = spec.base.value_or(ddm_default_base(object));
  try {
    if (base == DdmBaseKind::teapot_body) {
      layer->base = DdmBaseKind::teapot_body;
      layer->surface = teapot_body_base(object);
      resolution = {513, 257};
    } else if (ddm_base_is_uv(base)) {
      layer->base = base;
      resolution = {1025, 1025};
      if (spec.map_resolution && spec.map_resolution->x != spec.map_resolution->y)
        throw CommandError("field 'map_resolution': a uv base is square ([R, R])", "map_resolution");
      if (base == DdmBaseKind::auto_uv) base_mesh = ddm_auto_uv_mesh(object.rest_mesh);
      layer->maps = std::make_shared<const DdmMaps>(
          ddm_rasterize_uv_maps(*base_mesh, spec.map_resolution.value_or(resolution).x));
    } else {
      layer->base = DdmBaseKind::limit;
      layer->surface = std::make_shared<DdmSubdivBase>(*object.rest_mesh);
      charts = layer->surface->chart_count();
    }
  } catch (const std::invalid_argument& e) {
    throw CommandError("field 'base': '" + object.name + "': " + e.what(), "base");
  }
  std::size_t largest = 0;
  for (const DdmTile& t : layer->tiles) largest = std::max(largest, t.mesh.vertex_count());
  // Checked before any cell is made: cells per chart × charts × tile vertices.
  std::vector<glm::ivec2> chart_counts =
      ddm_fill_chart_counts(spec, layer->base, *base_mesh, layer->surface.get(), charts, fill ? largest : 0);
  if (spec.tile_size) layer->counts = chart_counts.front();
  std::size_t cells_laid = 0;
  if (fill) {
    layer->instances = ddm_layout_cells(layer->layout, chart_counts);
    cells_laid = layer->instances.size();
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
  if (spec.tile_size) layer->chart_counts = std::move(chart_counts);
  if (fill && ddm_base_is_uv(layer->base)) {
    std::erase_if(layer->instances,
                  [&](const DdmInstance& c) { return !ddm_uv_cell_kept(layer->base, *layer->maps, c); });
    ddm_check_kept_vertices(spec, *layer, cells_laid);
  }
  const ProgressSink finishing = progress_range(progress, 0.05, 1.0);  // tiles, base and layout: the first 5 %
  try {
    ddm_layer_finish(*layer, spec.map_resolution.value_or(resolution), progress ? &finishing : nullptr);
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    const bool res = msg.rfind("map_resolution", 0) == 0;
    throw CommandError("field '" + std::string(res ? "map_resolution" : "base") + "': " + msg,
                       res ? "map_resolution" : "base");
  }
  return layer;
}

std::vector<glm::ivec2> ddm_fill_chart_counts(const DdmLayerSpec& spec, DdmBaseKind base, const TriMesh& base_mesh,
                                              const DdmBase* surface, int charts, std::size_t tile_vertices) {
  const char* field = spec.tile_size ? "tile_size" : "counts";
  std::vector<glm::ivec2> counts;
  try {
    if (!spec.tile_size) {
      counts.assign(static_cast<std::size_t>(charts), spec.counts.value_or(glm::ivec2(1)));
    } else {
      std::vector<glm::dvec2> sizes;
      if (base == DdmBaseKind::limit)
        sizes = ddm_limit_chart_sizes(base_mesh);
      else if (!surface)
        sizes.assign(1, ddm_uv_chart_size(base_mesh));
      else
        for (int c = 0; c < charts; ++c) sizes.push_back(ddm_chart_size(*surface, c));
      if (static_cast<int>(sizes.size()) != charts)
        throw std::invalid_argument("base: " + std::to_string(sizes.size()) + " chart sizes for " +
                                    std::to_string(charts) + " charts");
      counts.reserve(sizes.size());
      for (const glm::dvec2& size : sizes) counts.push_back(ddm_counts_for_size(spec.layout, size, *spec.tile_size));
    }
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    const bool sized = msg.rfind("tile_size", 0) == 0;
    const char* blamed = sized ? "tile_size" : "base";
    throw CommandError("field '" + std::string(blamed) + "': " + msg, blamed);
  }
  std::size_t cells = 0;
  for (const glm::ivec2& c : counts) cells += ddm_layout_cell_count(spec.layout, c);
  if (tile_vertices > 0 && ddm_base_is_uv(base)) {
    // Tiles come only where the UV islands are (pruned once the maps exist): the tile vertices are counted then
    // (ddm_check_kept_vertices); here only the cells, which are made before pruning, are bounded.
    if (cells > kMaxDdmLayoutCells) {
      char size[80] = "";
      if (spec.tile_size) std::snprintf(size, sizeof size, "tiles %g world units across make ", *spec.tile_size);
      throw CommandError("field '" + std::string(field) + "': " + size + std::to_string(cells) +
                             " cells before the UV islands prune them (at most " + std::to_string(kMaxDdmLayoutCells) +
                             ")",
                         field);
    }
    return counts;
  }
  const std::size_t per_tile = std::max<std::size_t>(tile_vertices, 1);
  const std::size_t limit = spec.max_vertices ? static_cast<std::size_t>(*spec.max_vertices) : kMaxDdmLayerVertices;
  if (cells > limit / per_tile) {
    char size[80] = "";
    if (spec.tile_size) std::snprintf(size, sizeof size, "tiles %g world units across make ", *spec.tile_size);
    const std::string count = tile_vertices == 0
                                  ? std::to_string(cells) + " cells to paint (at most "
                                  : std::to_string(cells) + " tiles × " + std::to_string(per_tile) +
                                        " vertices = " + std::to_string(cells * per_tile) + " tile vertices (at most ";
    throw CommandError("field '" + std::string(field) + "': " + size + count + std::to_string(limit) +
                           (spec.max_vertices ? ", max_vertices)" : ")"),
                       field);
  }
  return counts;
}

std::shared_ptr<const TriMesh> ddm_auto_uv_mesh(const std::shared_ptr<const TriMesh>& mesh, DdmAutoUvStats* stats) {
  struct Entry {
    std::weak_ptr<const TriMesh> mesh;
    std::shared_ptr<const TriMesh> unwrapped;
    DdmAutoUvStats stats;
  };
  static std::mutex mutex;
  static std::deque<Entry> cache;  // the last few meshes unwrapped (the panel's estimate, then Fill, then undo/redo)
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const Entry& e : cache)
      if (e.mesh.lock() == mesh) {
        if (stats) *stats = e.stats;
        return e.unwrapped;
      }
  }
  DdmAutoUvStats st;
  auto unwrapped = std::make_shared<const TriMesh>(ddm_auto_uv(*mesh, &st));
  const std::lock_guard<std::mutex> lock(mutex);
  cache.push_front({mesh, unwrapped, st});
  if (cache.size() > 4) cache.pop_back();
  if (stats) *stats = st;
  return unwrapped;
}

DdmBaseKind ddm_default_base(const SceneObject& object) {
  if (object.source == "primitive:teapot") return DdmBaseKind::teapot_body;
  const TriMesh* mesh = object.rest_mesh.get();
  if (mesh && !mesh->empty() && mesh->uvs.size() == mesh->vertex_count()) return DdmBaseKind::uv;
  return DdmBaseKind::auto_uv;
}

DdmFillEstimate ddm_fill_estimate(const SceneObject& object, const DdmLayerSpec& spec) {
  if (!object.rest_mesh) throw CommandError("field 'object': '" + object.name + "' has no mesh", "object");
  std::size_t largest = 0;
  for (std::size_t i = 0; i < spec.tiles.size(); ++i)
    largest = std::max(
        largest, load_ddm_tile(spec.tiles[i], ddm_tile_file(spec.tiles, spec.tile_paths, i), i == 0 ? "tile" : "tiles")
                     .mesh.vertex_count());
  std::shared_ptr<DdmBase> surface;
  int charts = 1;
  const DdmBaseKind base = spec.base.value_or(ddm_default_base(object));
  if (base == DdmBaseKind::teapot_body) {
    surface = teapot_body_base(object);
  } else if (base == DdmBaseKind::limit) {
    charts = static_cast<int>(3 * object.rest_mesh->triangle_count());
  }
  std::shared_ptr<const TriMesh> base_mesh = object.rest_mesh;
  if (base == DdmBaseKind::auto_uv) {
    try {
      base_mesh = ddm_auto_uv_mesh(object.rest_mesh);
    } catch (const std::invalid_argument& e) {
      throw CommandError("field 'base': '" + object.name + "': " + e.what(), "base");
    }
  }
  DdmFillEstimate e;
  const std::vector<glm::ivec2> counts = ddm_fill_chart_counts(spec, base, *base_mesh, surface.get(), charts, largest);
  e.charts = counts.size();
  for (const glm::ivec2& c : counts) e.cells += ddm_layout_cell_count(spec.layout, c);
  e.tile_vertices = e.cells * largest;
  e.upper_bound = ddm_base_is_uv(base);
  return e;
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

void check_ddm_layer_name(const std::string& name) {
  if (const std::string bad = object_name_error(name); !bad.empty()) params::fail("layer", bad);
}

}  // namespace trispline::core
