#include "core/commands/incision_draw.h"

#include "core/commands/codecs.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/commands/json_fields.h"
#include "core/raycast/ray_caster.h"

namespace trispline::core {
namespace jf = json_fields;

CommandPtr IncisionDrawCommand::parse(const nlohmann::json& j, const CommandContext& ctx) {
  auto c = std::make_unique<IncisionDrawCommand>();
  c->object_ = jf::get_string(j, "object");
  c->stroke_ = jf::get_points2(j, "stroke");
  if (c->stroke_.size() < 2) throw CommandError("field 'stroke': needs at least 2 points", "stroke");
  if (jf::has(j, "camera"))  // the view the stroke was drawn in (as place.sketch): no camera.set needed
    c->camera_ = camera_schema().parse_nested(j.at("camera"), "camera", ctx);
  for (const glm::dvec2& p : c->stroke_)
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
      throw CommandError("field 'stroke': points must be finite", "stroke");
  IncisionParams& p = c->params_;
  p.width = jf::get_number(j, "width");
  if (!(p.width > 0.0)) throw CommandError("field 'width': must be > 0 world units", "width");
  p.depth = jf::get_number(j, "depth");
  if (!(p.depth > 0.0))
    throw CommandError("field 'depth': zero depth: the cut must go below the surface (depth > 0)", "depth");
  p.opening = jf::get_number(j, "opening", 0.0);
  if (p.opening < 0.0) throw CommandError("field 'opening': must be ≥ 0 world units", "opening");
  p.walls = jf::get_bool(j, "walls", true);
  p.order = jf::get_int(j, "order", 3);
  if (p.order < 2 || p.order > 4) throw CommandError("field 'order': must be in 2..4", "order");
  if (jf::has(j, "controls")) {
    const glm::ivec3 n = jf::get_ivec3(j, "controls");
    if (n.x % 2 == 0 || n.x < std::max(3, p.order) || n.x > 31 || n.y < p.order || n.y > 64 || n.z % 2 == 0 ||
        n.z < std::max(3, p.order) || n.z > 31)
      throw CommandError("field 'controls': [l, m, n] with l, n odd in max(3, order)..31 and m in order..64",
                         "controls");
    p.controls_u = n.x, p.controls_v = n.y, p.controls_w = n.z;
    c->has_controls_ = true;
  }
  p.kernel = jf::get_enum(j, "kernel", {"gaussian", "bspline"}, "gaussian") == "bspline" ? IncisionKernel::bspline
                                                                                         : IncisionKernel::gaussian;
  p.wall_rows = jf::get_int(j, "wall_rows", 4);
  if (p.wall_rows < 1 || p.wall_rows > 32) throw CommandError("field 'wall_rows': must be in 1..32", "wall_rows");
  return c;
}

nlohmann::json IncisionDrawCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()},
                      {"object", object_},
                      {"stroke", jf::to_json(stroke_)},
                      {"width", params_.width},
                      {"depth", params_.depth},
                      {"opening", params_.opening},
                      {"walls", params_.walls},
                      {"order", params_.order},
                      {"kernel", params_.kernel == IncisionKernel::bspline ? "bspline" : "gaussian"},
                      {"wall_rows", params_.wall_rows}};
  if (has_controls_) j["controls"] = {params_.controls_u, params_.controls_v, params_.controls_w};
  if (camera_) j["camera"] = camera_schema().fields_json(*camera_);
  return j;
}

std::string IncisionDrawCommand::label() const {
  char buf[96];
  std::snprintf(buf, sizeof buf, " (depth %g, opening %g)", params_.depth, params_.opening);
  return "Incision on '" + object_ + "'" + buf;
}

std::optional<SceneObject> IncisionDrawCommand::build(const Scene& scene) {
  const SceneObject* object = scene.find(object_);
  if (!object) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  require_no_tile_layers(*object, "an incision");
  if (object->ffd || object->dffd || object->clip)
    throw CommandError("field 'object': '" + object_ +
                           "' is deformed (FFD, DFFD or clip); incisions cut "
                           "undeformed objects only",
                       "object");
  if (!object->rest_mesh || object->rest_mesh->empty())
    throw CommandError("field 'object': '" + object_ + "' has no triangles to cut", "object");
  if (!camera_ && !scene.camera_set)
    throw CommandError("field 'camera': stroke pixels need a camera: add a camera.set line before this one or a "
                       "\"camera\" object to this line", "camera");
  const Camera& camera = camera_ ? *camera_ : scene.camera;
  const auto t0 = std::chrono::steady_clock::now();
  // world_mesh is T(rest) for an object without ffd / dffd / clip (SceneObject::refresh).
  const TriMesh fallback = object->world_mesh ? TriMesh{} : object->world_rest_mesh();
  const TriMesh& world = object->world_mesh ? *object->world_mesh : fallback;
  // The target object only, and only its triangles under the stroke (same first hits, a much smaller BVH).
  const RayCaster rays = stroke_ray_caster(world, camera, stroke_, BuildQuality::high);
  const std::optional<IncisionFrame> frame = fit_incision_frame(stroke_, camera, rays);
  if (!frame) throw CommandError("field 'stroke': the stroke misses the surface of '" + object_ + "'", "stroke");
  IncisionResult r = [&] {
    try {
      return incise(world, *frame, params_);
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      const std::size_t colon = msg.find(':');
      std::string field = colon == std::string::npos ? "stroke" : msg.substr(0, colon);
      if (field == "eps") field = "stroke";
      throw CommandError("field '" + field + "': " + (colon == std::string::npos ? msg : msg.substr(colon + 2)), field);
    }
  }();
  if (r.cut_edges == 0)
    throw CommandError("field 'stroke': the cut crosses no edge of '" + object_ + "' (stroke too short?)", "stroke");

  // Back to object space: only what the cut moved or added; the rest keeps its rest values bit for bit.
  const TriMesh& rest = *object->rest_mesh;
  TriMesh out = std::move(r.mesh);
  const glm::dmat4 m = object->transform.matrix();
  const bool identity = object->transform.is_identity();
  const glm::dmat4 inv = glm::inverse(m);
  const glm::dmat3 nrm_back = glm::transpose(glm::dmat3(m));  // inverse transpose of T⁻¹'s linear part
  const bool flip = glm::determinant(glm::dmat3(m)) < 0.0;
  // (With the identity, T(rest) is rest itself: nothing to map.)
  for (std::size_t v = 0; !identity && v < out.positions.size(); ++v) {
    if (v < rest.positions.size() && !r.moved[v]) {
      out.positions[v] = rest.positions[v];
      if (!out.normals.empty() && rest.normals.size() == rest.positions.size()) out.normals[v] = rest.normals[v];
      if (!out.uvs.empty() && rest.uvs.size() == rest.positions.size()) out.uvs[v] = rest.uvs[v];
      continue;
    }
    out.positions[v] = glm::dvec3(inv * glm::dvec4(out.positions[v], 1.0));
    if (!out.normals.empty()) {
      const glm::dvec3 q = nrm_back * out.normals[v];
      const double len = glm::length(q);
      if (len > 0.0) out.normals[v] = q / len;
    }
  }
  if (flip)
    for (auto& f : out.triangles) std::swap(f.y, f.z);

  SceneObject cut = *object;
  const std::size_t before = rest.positions.size();
  cut.rest_mesh = std::make_shared<const TriMesh>(std::move(out));
  cut.refresh();
  stats_ = {{"hits", frame->hits.size()},
            {"embedded_vertices", r.embedded_vertices},
            {"newton_fallbacks", r.newton_fallbacks},
            {"cut_edges", r.cut_edges},
            {"split_faces", r.split_faces},
            {"tips", r.tips},
            {"wall_faces", r.wall_faces},
            {"controls", {r.controls.x, r.controls.y, r.controls.z}},
            {"vertices_before", before},
            {"vertices_after", cut.rest_mesh->positions.size()},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return cut;
}

}  // namespace trispline::core
