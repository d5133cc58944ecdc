// Source: seed ch. 5 (Eq. 5.1–5.2, §5.3, Fig. 5.11–5.12).
#include "core/commands/ddm_fill.h"

#include <algorithm>
#include <chrono>

namespace trispline::core {

auto DdmFillCommand::declare() -> Schema {
  return Schema("ddm.fill", "Cover an object's surface with a layer of geometric tiles (DDM, seed ch. 5)")
      .field("object", &P::object, {.required = true, .help = kDdmLayerObjectHelp})
      .field("layer", &P::layer, {.required = true, .help = "Name of the layer; a layer of that name is replaced"})
      .check([](const P& p) { check_ddm_layer_name(p.layer); })
      .embed(&P::spec, ddm_layer_schema(true))
      .label([](const P& p) { return "Fill '" + p.object + "' with " + p.spec.tiles.front() + " (" + p.layer + ")"; })
      .failure_field("tile");
}

std::optional<SceneObject> DdmFillCommand::build(const Scene& scene) {
  const auto t0 = std::chrono::steady_clock::now();
  const SceneObject* object = &require_object(scene, p_.object);
  std::shared_ptr<const DdmLayer> layer = make_ddm_layer(*object, p_.layer, p_.spec, true, progress());
  std::size_t tile_vertices = 0;
  for (const DdmTile& t : layer->tiles) tile_vertices = std::max(tile_vertices, t.mesh.vertex_count());
  stats_ = {{"base", ddm_base_name(layer->base)},
            {"charts", layer->maps->slot_of_chart.size()},
            {"tiles", layer->instances.size()},
            {"tile_vertices", tile_vertices},
            {"vertices", layer->mesh->vertex_count()},
            {"map_samples", layer->maps->slot_count() * layer->maps->samples_per_slot()},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  if (layer->base == DdmBaseKind::auto_uv) {  // the unwrap is cached: its figures for the report
    DdmAutoUvStats uv;
    (void)ddm_auto_uv_mesh(object->rest_mesh, &uv);
    stats_["uv_charts"] = uv.charts;
    stats_["uv_area_distortion_p95"] = uv.area_distortion_p95;
  }
  return with_ddm_layer(*object, std::move(layer));
}

}  // namespace trispline::core
