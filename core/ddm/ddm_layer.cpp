// DdmLayer evaluation and editing. See ddm_layer.h. Sources: seed §5.3 (maps, instances), Eq. 5.3 (metamorphosis),
// §5.4.2 (texture-space offset animation).
#include "core/ddm/ddm_layer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace trispline::core {

double DdmLayer::alpha_at(double time_s) const {
  return alpha_keys.empty() ? alpha : evaluate_offset_keys(alpha_keys, time_s).x;
}

glm::dvec2 DdmLayer::offset_at(double time_s) const {
  const glm::dvec2 keyed = offset_keys.empty() ? glm::dvec2(0.0) : glm::dvec2(evaluate_offset_keys(offset_keys, time_s));
  return keyed + offset_velocity * time_s;
}

bool DdmLayer::animated() const {
  return (!morph_tiles.empty() && alpha_keys.size() >= 2) || offset_keys.size() >= 2 ||
         offset_velocity != glm::dvec2(0.0);
}

std::vector<DdmTile> DdmLayer::tiles_at(double a) const {
  if (morph_tiles.empty()) return tiles;
  std::vector<DdmTile> out;
  out.reserve(tiles.size());
  for (std::size_t i = 0; i < tiles.size(); ++i) out.push_back(ddm_morph(tiles[i], morph_tiles[i], a));
  return out;
}

TriMesh ddm_layer_mesh(const DdmLayer& layer, double time_s) {
  if (!layer.maps) throw std::invalid_argument("layer '" + layer.name + "': no maps");
  return ddm_evaluate(DdmMapsBase(layer.maps), layer.tiles_at(layer.alpha_at(time_s)), layer.instances, layer.height,
                      layer.transform, layer.offset_at(time_s));
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

void ddm_layer_finish(DdmLayer& layer, glm::ivec2 map_resolution) {
  if (layer.base == DdmBaseKind::uv) {
    if (!layer.maps) throw std::invalid_argument("base: a uv layer needs its rasterised maps");
    // The validity bitmap prunes tiles lying wholly outside the UV islands (seed §5.4.1).
    std::erase_if(layer.instances, [&](const DdmInstance& c) { return !ddm_cell_valid(*layer.maps, c); });
  } else {
    if (!layer.surface) throw std::invalid_argument("base: the layer has no surface");
    layer.maps = std::make_shared<const DdmMaps>(ddm_sample_maps(*layer.surface, charts_of(layer.instances), map_resolution));
  }
  layer.mesh = std::make_shared<const TriMesh>(ddm_layer_mesh(layer, 0.0));
}

std::shared_ptr<DdmLayer> ddm_layer_with_instances(const DdmLayer& layer, std::vector<DdmInstance> instances) {
  if (!layer.maps) throw std::invalid_argument("layer '" + layer.name + "': no maps");
  auto out = std::make_shared<DdmLayer>(layer);
  const int charts = static_cast<int>(layer.maps->slot_of_chart.size());
  for (const DdmInstance& i : instances) {
    if (i.chart < 0 || i.chart >= charts)
      throw std::invalid_argument("base: instance on chart " + std::to_string(i.chart) + " of " + std::to_string(charts));
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
  out->mesh = std::make_shared<const TriMesh>(ddm_layer_mesh(*out, 0.0));
  return out;
}

}  // namespace trispline::core
