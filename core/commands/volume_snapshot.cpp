#include "core/commands/volume_snapshot.h"

namespace trispline::core {

const VolumeObject& require_volume(const Scene& scene, const std::string& name, const char* field) {
  if (const VolumeObject* v = scene.find_volume(name)) return *v;
  if (scene.find(name))
    throw CommandError("field '" + std::string(field) + "': '" + name + "' is a mesh object, not a volume", field);
  throw CommandError("field '" + std::string(field) + "': no volume named '" + name + "'", field);
}

VolumeObject volume_with_silhouettes(const VolumeObject& volume, const Camera& camera, nlohmann::json* stats) {
  VolumeObject out = volume;
  if (!volume.silhouette.enabled) {
    out.silhouettes.reset();
    for (VolumeIsoLevel& l : out.more_levels) l.silhouettes.reset();
    return out;
  }
  SilhouetteParams params = volume.silhouette.params;
  params.hidden_test = volume.silhouette.hidden != "show";
  auto r = std::make_shared<SilhouetteResult>(
      extract_silhouettes(*volume.spline, *volume.table, volume.iso, volume.silhouette_view(camera), params));
  if (stats) {
    (*stats)["points"] = r->points;
    (*stats)["polylines"] = r->polylines.size();
    (*stats)["length_mm"] = r->length_mm;
    (*stats)["candidates"] = r->candidates;
    (*stats)["seeds"] = r->seeds;
    (*stats)["extract_ms"] = r->extract_ms;
    (*stats)["hidden_ms"] = r->hidden_ms;
    (*stats)["max_value_residual"] = r->max_value_residual;
    (*stats)["max_dot_residual"] = r->max_dot_residual;
  }
  out.silhouettes = std::move(r);
  std::size_t points = out.silhouettes->points;
  for (VolumeIsoLevel& l : out.more_levels) {
    l.silhouettes = std::make_shared<SilhouetteResult>(
        extract_silhouettes(*volume.spline, *volume.table, l.iso, volume.silhouette_view(camera), params));
    points += l.silhouettes->points;
  }
  if (stats && !out.more_levels.empty()) (*stats)["points_all_levels"] = points;
  out.silhouette_camera = camera;
  return out;
}

}  // namespace trispline::core
