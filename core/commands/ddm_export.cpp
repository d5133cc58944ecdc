#include "core/commands/ddm_export.h"

#include <chrono>
#include <memory>

#include "core/base/text.h"
#include "core/commands/ddm_layer_spec.h"
#include "core/ddm/ddm_map_image.h"
#include "core/image/image_io.h"

namespace trispline::core {

auto DdmExportCommand::declare() -> Schema {
  return Schema("ddm.export", "Export a tile layer's sampled position or normal map as a picture (seed Figs. 5.3, 5.5)")
      .field("object", &P::object, {.required = true, .help = "The object holding the layer"})
      .field("layer", &P::layer, {.required = true, .help = "The tile layer whose maps are written"})
      .choice("what", &P::what, {"positions", "normals"},
              {.help = "positions: P(u, v), x y z as red green blue over the surface's bounding box; normals: "
                       "N(u, v) as (n + 1) / 2. One pixel per sample, charts side by side, v upwards; alpha 96 "
                       "where a UV-mapped base's diffusion filled the sample"})
      .field("path", &P::path,
             {.required = true,
              .help = "Output .png, relative to the output folder (replay's --out, else the log's folder); "
                      "absolute paths and paths that leave the folder are refused"})
      .check([](const P& p) {
        const std::string e = lower_extension(p.path);
        if (e != ".png") params::fail("path", "a map is written as .png, not '" + e + "'");
      })
      .label([](const P& p) { return "Export the " + p.what + " map of " + p.object + "/" + p.layer; })
      .failure_field("path");
}

std::optional<SceneObject> DdmExportCommand::build(const Scene& scene) {
  const SceneObject& object = require_object(scene, p_.object);
  const std::shared_ptr<const DdmLayer> layer = find_ddm_layer(object, p_.layer);
  if (!layer->maps) throw CommandError("field 'layer': '" + p_.layer + "' holds no sampled maps", "layer");
  const auto t0 = std::chrono::steady_clock::now();
  std::shared_ptr<const DdmMapImage> image;
  try {
    image = std::make_shared<const DdmMapImage>(
        ddm_map_image(*layer->maps, p_.what == "normals" ? DdmMapQuantity::normals : DdmMapQuantity::positions));
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("field 'layer': ") + e.what(), "layer");
  }
  keep_writer([image](const std::filesystem::path& out) {
    std::filesystem::create_directories(out.parent_path());
    write_image_rgba8(out, image->width, image->height, image->rgba);
  });
  stats_["width"] = image->width;
  stats_["height"] = image->height;
  stats_["charts"] = layer->maps->slot_count();
  stats_["path"] = output_path().string();
  stats_["ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return object;
}

}  // namespace trispline::core
