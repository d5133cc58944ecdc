#include "core/commands/volume_export.h"

#include <chrono>
#include <glm/gtc/color_space.hpp>

#include "core/base/text.h"
#include "core/mesh/gltf_io.h"
#include "core/params/codecs.h"
#include "core/scene/scene_check.h"
#include "core/volume/iso_mesh.h"
#include "core/volume/silhouette_export.h"

namespace trispline::core {

namespace {

// Refuses a result holding a non-finite coordinate or one beyond kMaxWorldCoordinate, before a file is written.
template <class Points>
void require_finite_points(const Points& points, const char* what) {
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int a = 0; a < 3; ++a)
      if (!(std::abs(double(points[i][a])) <= kMaxWorldCoordinate))
        throw CommandError("field 'object': " + std::string(what) + " " + std::to_string(i) +
                               " is not finite or out of range (" + params::format_number(points[i][a]) +
                               "): the volume's geometry is degenerate; nothing written",
                           "object");
}

}  // namespace

auto VolumeExportCommand::declare() -> Schema {
  return Schema("volume.export", "Export a volume's silhouettes (SVG, glTF lines) or its iso-surface mesh")
      .field("object", &P::object, {.required = true, .help = "A volume"})
      .choice("what", &P::what, {"silhouettes", "iso"},
              {.help = "silhouettes: for the current camera, as .svg or .glb line strips; iso: the surface D = iso "
                       "as a triangle mesh, .glb/.obj/.ply"})
      .field("path", &P::path,
             {.required = true,
              .help = "Output file, relative to the output folder (replay's --out, else the log's folder); "
                      "absolute paths and paths that leave the folder are refused"})
      .field("samples_per_voxel", &P::samples_per_voxel,
             {.write = ParamWrite::UnlessDefault,
              .range = ParamRange{1, 4},
              .help = "iso: grid samples per voxel and axis before meshing (1 = at the control points)"})
      .object("camera", &P::camera, camera_schema(),
              {.help = "silhouettes: the view they are taken for (camera.set's fields); default: the scene camera"})
      .check([](const P& p) {
        const std::string e = lower_extension(p.path);
        if (p.what == "silhouettes" && e != ".svg" && e != ".glb")
          params::fail("path", "silhouettes are written as .svg or .glb, not '" + e + "'");
        if (p.what == "iso" && e != ".glb" && e != ".obj" && e != ".ply")
          params::fail("path", "an iso-surface is written as .glb, .obj or .ply, not '" + e + "'");
      })
      .label([](const P& p) { return "Export " + p.what + " of '" + p.object + "'"; })
      .failure_field("path");
}

std::optional<VolumeObject> VolumeExportCommand::build(const Scene& scene) {
  const VolumeObject& before = require_volume(scene, p_.object);
  const auto t0 = std::chrono::steady_clock::now();
  VolumeObject v = before;
  const std::string file = output_path().string();
  if (p_.what == "silhouettes") {
    // The view, its far plane beyond the volume (the SVG's projection clips to it; camera.set carries none).
    Camera cam = p_.camera ? *p_.camera : scene.camera;
    const Aabb box = v.world_bounds();
    cam.far_plane = std::max(cam.far_plane, glm::length(box.center() - cam.eye) + 0.51 * box.diagonal());
    v.silhouette.enabled = true;
    v = volume_with_silhouettes(v, cam, &stats_);
    v.silhouette.enabled = before.silhouette.enabled;
    const auto& polylines = v.silhouettes->polylines;
    for (const SilhouettePolyline& pl : polylines) require_finite_points(pl.points, "silhouette point");
    // The file is written from these (shared, immutable) results, now or later (write_files: History's Run again).
    // Every level: the first in the volume's style (black where the style has one colour), then each further level in
    // its own style and colour.
    struct Level {
      std::shared_ptr<const SilhouetteResult> result;
      std::string style;
      glm::vec3 color;  // sRGB
    };
    std::vector<Level> levels{{v.silhouettes, v.silhouette.style, glm::vec3(0.0f)}};
    for (const VolumeIsoLevel& l : v.more_levels) {
      for (const SilhouettePolyline& pl : l.silhouettes->polylines)
        require_finite_points(pl.points, "silhouette point");
      levels.push_back({l.silhouettes, l.style, l.color});
    }
    const glm::dmat4 view_projection = cam.projection_matrix() * cam.view_matrix();
    const glm::ivec2 viewport = cam.viewport;
    const std::string hidden = v.silhouette.hidden, name = p_.object + "/silhouettes";
    Writer writer = [levels, view_projection, viewport, hidden, name](const std::filesystem::path& out) {
      std::filesystem::create_directories(out.parent_path());
      if (lower_extension(out.string()) == ".svg") {
        std::vector<std::vector<SilhouettePolyline>> drawn;
        for (const Level& l : levels) {
          drawn.push_back(l.result->polylines);
          if (hidden == "show")
            for (auto& pl : drawn.back()) std::fill(pl.visible.begin(), pl.visible.end(), 1);
        }
        std::vector<SvgLayer> layers;
        for (std::size_t i = 0; i < levels.size(); ++i) {
          SvgLayer layer{&drawn[i], {}};
          layer.style.stroke = levels[i].style;  // hue | glyphs | fans | width | plain | chromadepth
          layer.style.hidden = hidden == "dashed" ? "dashed" : "remove";
          layer.style.color = levels[i].color;
          layers.push_back(layer);
        }
        write_silhouettes_svg(out, layers, view_projection, viewport);
      } else {
        std::vector<std::vector<std::vector<glm::vec3>>> strips;
        for (const Level& l : levels) strips.push_back(silhouette_line_strips(l.result->polylines, hidden != "remove"));
        std::vector<GltfNode> nodes;
        for (std::size_t i = 0; i < levels.size(); ++i) {
          GltfNode node;
          node.name = i == 0 ? name : name + "." + std::to_string(i);
          node.line_strips = &strips[i];
          node.color = glm::convertSRGBToLinear(levels[i].color);
          nodes.push_back(node);
        }
        write_glb(out, nodes);
      }
    };
    keep_writer(std::move(writer));
  } else {
    if (!(v.iso >= v.table->range_min() && v.iso <= v.table->range_max()))
      throw CommandError("field 'object': the iso-level " + params::format_number(v.iso) + " of '" + p_.object +
                             "' lies outside its values [" + params::format_number(v.table->range_min()) + ", " +
                             params::format_number(v.table->range_max()) +
                             "]: no surface to export (volume.iso sets it)",
                         "object");
    IsoMeshOptions opt;
    opt.samples_per_voxel = p_.samples_per_voxel;
    IsoMeshStats ms;
    auto mesh = std::make_shared<const TriMesh>(extract_iso_mesh(*v.spline, v.iso, opt, nullptr, &ms));
    require_finite_points(mesh->positions, "iso-surface vertex");
    keep_writer([mesh](const std::filesystem::path& out) {
      std::filesystem::create_directories(out.parent_path());
      write_iso_mesh(out, *mesh);
    });
    stats_["vertices"] = mesh->positions.size();
    stats_["triangles"] = mesh->triangles.size();
    v.iso_mesh = std::move(mesh);
  }
  stats_["path"] = file;
  stats_["ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return v;
}

}  // namespace trispline::core
