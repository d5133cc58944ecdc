// DdmLayer evaluation and editing. See ddm_layer.h. Sources: seed §5.3 (maps, instances), Eq. 5.3 (metamorphosis),
// §5.4.2 (texture-space offset, rotation, scale and w animation).
#include "core/ddm/ddm_layer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace trispline::core {

double DdmLayer::alpha_at(double time_s) const {
  return alpha_keys.empty() ? alpha : evaluate_offset_keys(alpha_keys, time_s).x;
}

glm::dvec2 DdmLayer::offset_at(double time_s) const {
  const glm::dvec2 keyed =
      offset_keys.empty() ? glm::dvec2(0.0) : glm::dvec2(evaluate_offset_keys(offset_keys, time_s));
  return keyed + offset_velocity * time_s;
}

DdmTileTransform DdmLayer::transform_at(double time_s) const {
  DdmTileTransform t = transform;
  if (!rotate_keys.empty()) t.rotate_deg += evaluate_offset_keys(rotate_keys, time_s).x;
  if (!scale_keys.empty()) t.scale *= evaluate_offset_keys(scale_keys, time_s).x;
  return t;
}

double DdmLayer::height_at(double time_s) const {
  return w_keys.empty() ? height : height * evaluate_offset_keys(w_keys, time_s).x;
}

bool DdmLayer::animated() const {
  return (!morph_tiles.empty() && alpha_keys.size() >= 2) || offset_keys.size() >= 2 ||
         offset_velocity != glm::dvec2(0.0) || rotate_keys.size() >= 2 || scale_keys.size() >= 2 ||
         w_keys.size() >= 2 || tile_clip != nullptr;
}

std::vector<DdmTile> DdmLayer::tiles_at(double a) const {
  if (morph_tiles.empty()) return tiles;
  std::vector<DdmTile> out;
  out.reserve(tiles.size());
  for (std::size_t i = 0; i < tiles.size(); ++i) out.push_back(ddm_morph(tiles[i], morph_tiles[i], a));
  return out;
}

std::vector<DdmTile> DdmLayer::tiles_at_time(double time_s) const {
  if (!tile_clip) return tiles_at(alpha_at(time_s));
  if (tiles.size() != 1 || !morph_tiles.empty())
    throw std::invalid_argument("layer '" + name + "': an articulated tile is the layer's only tile, without morph");
  return {tile_clip->pose(tiles[0], time_s)};
}

TriMesh ddm_layer_mesh(const DdmLayer& layer, double time_s, const ProgressSink* progress) {
  if (!layer.maps) throw std::invalid_argument("layer '" + layer.name + "': no maps");
  return ddm_evaluate(DdmMapsBase(layer.maps), layer.tiles_at_time(time_s), layer.instances, layer.height_at(time_s),
                      layer.transform_at(time_s), layer.offset_at(time_s), progress);
}

namespace {
std::vector<int> charts_of(const std::vector<DdmInstance>& instances) {
  std::vector<int> charts;
  charts.reserve(instances.size());
  for (const DdmInstance& i : instances) charts.push_back(i.chart);
  std::sort(charts.begin(), charts.end());
  charts.erase(std::unique(charts.begin(), charts.end()), charts.end());
  return charts;
}
}  // namespace

void ddm_layer_finish(DdmLayer& layer, glm::ivec2 map_resolution, const ProgressSink* progress) {
  check_progress(progress, 0.0);
  if (ddm_base_is_uv(layer.base)) {
    if (!layer.maps) throw std::invalid_argument("base: a uv layer needs its rasterised maps");
    // The validity bitmap prunes tiles lying wholly outside the UV islands (seed §5.4.1).
    // Automatic atlases also drop cells whose centre lies between charts (ddm_cell_centre_valid).
    std::erase_if(layer.instances, [&](const DdmInstance& c) { return !ddm_uv_cell_kept(layer.base, *layer.maps, c); });
  } else {
    if (!layer.surface) throw std::invalid_argument("base: the layer has no surface");
    layer.maps =
        std::make_shared<const DdmMaps>(ddm_sample_maps(*layer.surface, charts_of(layer.instances), map_resolution));
  }
  const ProgressSink evaluation = progress_range(progress, 0.1, 1.0);  // the maps take a small part of the time
  layer.mesh = std::make_shared<const TriMesh>(ddm_layer_mesh(layer, 0.0, progress ? &evaluation : nullptr));
}

namespace {
// `layer`'s mesh at time 0 (as ddm_layer_mesh) when it differs from `previous` — its source, whose mesh is that layer
// at time 0 — only in instances and in maps extended by new charts: the vertices of instances both hold are copied
// (each instance depends on itself and its chart's map samples alone, and ddm_sample_maps keeps old slots bit for
// bit), the others evaluated. Bit for bit the same as ddm_layer_mesh(layer, 0).
// Where each instance's vertices and triangles start in a layer mesh (instances one after another); #I + 1 entries.
struct InstanceStarts {
  std::vector<std::size_t> vertex, triangle;
};
InstanceStarts instance_starts(const std::vector<DdmTile>& tiles, const std::vector<DdmInstance>& instances) {
  InstanceStarts s{std::vector<std::size_t>(instances.size() + 1, 0),
                   std::vector<std::size_t>(instances.size() + 1, 0)};
  for (std::size_t k = 0; k < instances.size(); ++k) {
    const TriMesh& tm = tiles[static_cast<std::size_t>(instances[k].tile)].mesh;
    s.vertex[k + 1] = s.vertex[k] + tm.vertex_count();
    s.triangle[k + 1] = s.triangle[k] + tm.triangle_count();
  }
  return s;
}

TriMesh mesh_reusing(const DdmLayer& layer, const DdmLayer& previous) {
  const InstanceStarts old_at = instance_starts(previous.tiles, previous.instances);
  const std::size_t old_vertices = old_at.vertex.back();
  if (!previous.mesh || previous.mesh->vertex_count() != old_vertices || previous.mesh->normals.size() != old_vertices)
    return ddm_layer_mesh(layer, 0.0);
  if (ddm_tile_materials(layer.tiles).set &&
      (previous.mesh->uvs.size() != old_vertices || previous.mesh->face_material.size() != old_at.triangle.back()))
    return ddm_layer_mesh(layer, 0.0);
  for (std::size_t c = 0; c < previous.maps->slot_of_chart.size(); ++c)
    if (previous.maps->slot_of_chart[c] >= 0 && layer.maps->slot_of_chart[c] != previous.maps->slot_of_chart[c])
      return ddm_layer_mesh(layer, 0.0);

  // Match the new instances against the old ones in order (painting appends, erasing removes; both keep order).
  std::vector<std::ptrdiff_t> reused(layer.instances.size(), -1);
  std::vector<DdmInstance> fresh;
  std::vector<std::size_t> fresh_index(layer.instances.size(), 0);
  std::size_t j = 0;
  for (std::size_t k = 0; k < layer.instances.size(); ++k) {
    std::size_t probe = j;
    while (probe < previous.instances.size() && !(previous.instances[probe] == layer.instances[k])) ++probe;
    if (probe < previous.instances.size()) {
      reused[k] = static_cast<std::ptrdiff_t>(probe);
      j = probe + 1;
    } else {
      fresh_index[k] = fresh.size();
      fresh.push_back(layer.instances[k]);
    }
  }
  TriMesh added;
  if (!fresh.empty())
    added = ddm_evaluate(DdmMapsBase(layer.maps), layer.tiles_at_time(0.0), fresh, layer.height_at(0.0),
                         layer.transform_at(0.0), layer.offset_at(0.0));
  const InstanceStarts fresh_at = instance_starts(layer.tiles, fresh);
  const InstanceStarts at = instance_starts(layer.tiles, layer.instances);
  if (at.vertex.back() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("counts: " + std::to_string(at.vertex.back()) + " vertices exceed 32-bit indices");
  TriMesh out;
  out.positions.resize(at.vertex.back());
  out.normals.resize(at.vertex.back());
  out.triangles.resize(at.triangle.back());
  const bool textured = ddm_tile_materials(layer.tiles).set != nullptr;  // uvs and face materials per copy
  if (textured) {
    out.uvs.resize(at.vertex.back());
    out.face_material.resize(at.triangle.back());
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, layer.instances.size(), 64), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      const bool from_old = reused[k] >= 0;
      const TriMesh& src = from_old ? *previous.mesh : added;
      const InstanceStarts& src_at = from_old ? old_at : fresh_at;
      const std::size_t i = from_old ? static_cast<std::size_t>(reused[k]) : fresh_index[k];
      const auto v0 = static_cast<std::ptrdiff_t>(src_at.vertex[i]), v = static_cast<std::ptrdiff_t>(at.vertex[k]);
      const std::size_t nv = at.vertex[k + 1] - at.vertex[k], nt = at.triangle[k + 1] - at.triangle[k];
      std::copy_n(src.positions.begin() + v0, nv, out.positions.begin() + v);
      std::copy_n(src.normals.begin() + v0, nv, out.normals.begin() + v);
      const glm::uvec3 back(static_cast<unsigned>(v0)), shift(static_cast<unsigned>(v));  // modulo 2³², exact
      for (std::size_t f = 0; f < nt; ++f)
        out.triangles[at.triangle[k] + f] = src.triangles[src_at.triangle[i] + f] - back + shift;
      if (textured) {
        std::copy_n(src.uvs.begin() + v0, nv, out.uvs.begin() + v);
        std::copy_n(src.face_material.begin() + static_cast<std::ptrdiff_t>(src_at.triangle[i]), nt,
                    out.face_material.begin() + static_cast<std::ptrdiff_t>(at.triangle[k]));
      }
    }
  });
  return out;
}
}  // namespace

std::shared_ptr<DdmLayer> ddm_layer_with_instances(const DdmLayer& layer, std::vector<DdmInstance> instances) {
  if (!layer.maps) throw std::invalid_argument("layer '" + layer.name + "': no maps");
  auto out = std::make_shared<DdmLayer>(layer);
  const int charts = static_cast<int>(layer.maps->slot_of_chart.size());
  for (const DdmInstance& i : instances) {
    if (i.chart < 0 || i.chart >= charts)
      throw std::invalid_argument("base: instance on chart " + std::to_string(i.chart) + " of " +
                                  std::to_string(charts));
    if (i.tile < 0 || i.tile >= static_cast<int>(layer.tiles.size()))
      throw std::invalid_argument("tile: tile " + std::to_string(i.tile) + " of " + std::to_string(layer.tiles.size()));
  }
  std::vector<int> missing;
  for (int c : charts_of(instances))
    if (layer.maps->slot_of_chart[static_cast<std::size_t>(c)] < 0) missing.push_back(c);
  if (!missing.empty()) {
    if (!layer.surface)
      throw std::invalid_argument("base: chart " + std::to_string(missing.front()) + " is not in the layer's maps");
    out->maps = std::make_shared<const DdmMaps>(
        ddm_sample_maps(*layer.surface, missing, layer.maps->resolution, layer.maps.get()));
  }
  out->instances = std::move(instances);
  out->mesh = std::make_shared<const TriMesh>(mesh_reusing(*out, layer));
  return out;
}

}  // namespace trispline::core
