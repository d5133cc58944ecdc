#include "core/commands/place_sketch.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/commands/camera_set.h"
#include "core/commands/json_fields.h"
#include "core/placement/sketch_placement.h"
#include "core/raycast/ray_caster.h"

namespace trispline::core {
namespace jf = json_fields;

namespace {
int axis_index(const std::string& a) { return a == "x" ? 0 : a == "y" ? 1 : 2; }

// The optional "springs" object (seed §2.3.2); errors name "springs.<field>".
SpringParams parse_springs(const nlohmann::json& j) {
  if (!j.is_object())
    throw CommandError("field 'springs': expected an object {stiffness, damping, mass, threshold_deg, "
                       "neighbourhood, max_steps, rest_length}, got " + std::string(j.type_name()),
                       "springs");
  try {
    SpringParams sp;
    sp.stiffness = jf::get_number(j, "stiffness", sp.stiffness);
    sp.damping = jf::get_number(j, "damping", sp.damping);
    sp.mass = jf::get_number(j, "mass", sp.mass);
    sp.angle_threshold_deg = jf::get_number(j, "threshold_deg", sp.angle_threshold_deg);
    sp.neighbourhood = jf::get_int(j, "neighbourhood", sp.neighbourhood);
    sp.max_steps = jf::get_int(j, "max_steps", sp.max_steps);
    sp.rest_length_initial = jf::get_enum(j, "rest_length", {"zero", "initial"}, "zero") == "initial";
    if (!(sp.stiffness > 0.0)) throw CommandError("field 'stiffness': must be > 0", "stiffness");
    if (!(sp.mass > 0.0)) throw CommandError("field 'mass': must be > 0", "mass");
    if (sp.damping < 0.0) throw CommandError("field 'damping': must be >= 0", "damping");
    if (!(sp.angle_threshold_deg > 0.0 && sp.angle_threshold_deg < 180.0))
      throw CommandError("field 'threshold_deg': must be in (0, 180) degrees", "threshold_deg");
    if (sp.max_steps < 0 || sp.max_steps > 1000000)
      throw CommandError("field 'max_steps': must be in [0, 1000000]", "max_steps");
    return sp;
  } catch (const CommandError& e) {  // name the nested field: 'springs.stiffness'
    std::string msg = e.what();
    if (msg.rfind("field '", 0) == 0) msg.insert(7, "springs.");
    throw CommandError(msg, "springs." + e.field());
  }
}

nlohmann::json springs_json(const SpringParams& sp) {
  return {{"stiffness", sp.stiffness},         {"damping", sp.damping},
          {"mass", sp.mass},                   {"threshold_deg", sp.angle_threshold_deg},
          {"neighbourhood", sp.neighbourhood}, {"max_steps", sp.max_steps},
          {"rest_length", sp.rest_length_initial ? "initial" : "zero"}};
}

// A JSON array of finite numbers (profile samples); the error names `field`.
std::vector<double> get_numbers(const nlohmann::json& a, const char* field) {
  if (!a.is_array())
    throw CommandError("field '" + std::string(field) + "': expected an array of numbers, got " + a.type_name(),
                       field);
  std::vector<double> out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_number() || !std::isfinite(a[i].get<double>()))
      throw CommandError("field '" + std::string(field) + "': element " + std::to_string(i) +
                             " is not a finite number",
                         field);
    out.push_back(a[i].get<double>());
  }
  return out;
}
const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }
}  // namespace

CommandPtr PlaceSketchCommand::parse(const nlohmann::json& j, const CommandContext&) {
  PlaceSketchParams p;
  p.object = jf::get_string(j, "object");
  p.stroke = jf::get_points2(j, "stroke");
  p.width = jf::get_number(j, "width");
  p.height = jf::get_number(j, "height");
  p.extent = jf::get_number(j, "extent", 1.0);
  if (!(p.extent > 0.0 && p.extent <= 1.0)) throw CommandError("field 'extent': must be in (0, 1]", "extent");
  if (jf::has(j, "springs")) p.springs = parse_springs(j.at("springs"));
  if (jf::has(j, "width_profile")) p.width_profile = get_numbers(j.at("width_profile"), "width_profile");
  if (jf::has(j, "height_profile")) {
    const nlohmann::json& h = j.at("height_profile");
    if (h.is_array() && !h.empty() && h[0].is_array()) {
      for (std::size_t r = 0; r < h.size(); ++r) p.height_profile.push_back(get_numbers(h[r], "height_profile"));
    } else {
      p.height_profile.push_back(get_numbers(h, "height_profile"));
    }
  }
  if (jf::has(j, "samples")) p.samples = jf::get_ivec2(j, "samples");
  p.volume = jf::get_enum(j, "volume", {"extrude", "offset"}, "extrude");
  if (jf::has(j, "order")) p.order = jf::get_ivec3(j, "order");
  if (jf::has(j, "controls")) p.controls = jf::get_ivec3(j, "controls");
  p.length_axis = jf::get_enum(j, "length_axis", {"x", "y", "z"}, "x");
  p.up_axis = jf::get_enum(j, "up_axis", {"x", "y", "z"}, "y");
  if (p.length_axis == p.up_axis)
    throw CommandError("field 'up_axis': must differ from length_axis ('" + p.length_axis + "')", "up_axis");
  if (jf::has(j, "camera")) {
    try {
      p.camera = CameraSetCommand::parse_camera(j.at("camera"));
    } catch (const CommandError& e) {  // name the nested field: 'camera.fov_deg'
      std::string msg = e.what();
      if (msg.rfind("field '", 0) == 0) msg.insert(7, "camera.");
      throw CommandError(msg, "camera." + e.field());
    }
  }
  if (jf::has(j, "ignore")) {  // ids the rays pass through (the editor's hidden objects)
    const nlohmann::json& list = j.at("ignore");
    if (!list.is_array())
      throw CommandError("field 'ignore': expected an array of object ids, got " + std::string(list.type_name()),
                         "ignore");
    for (std::size_t i = 0; i < list.size(); ++i) {
      try {
        p.ignore.push_back(jf::get_string(nlohmann::json{{"ignore", list[i]}}, "ignore"));
      } catch (const CommandError& e) {  // "field 'ignore': expected a string, got number" + which element
        const std::string what = e.what(), prefix = "field 'ignore': ";
        throw CommandError(prefix + "element " + std::to_string(i) + ": " + what.substr(prefix.size()), "ignore");
      }
    }
  }
  return std::make_unique<PlaceSketchCommand>(std::move(p));
}

nlohmann::json PlaceSketchCommand::params_json(const PlaceSketchParams& p) {
  nlohmann::json j = {{"cmd", "place.sketch"},
                      {"object", p.object},
                      {"stroke", jf::to_json(p.stroke)},
                      {"width", p.width},
                      {"height", p.height},
                      {"samples", jf::to_json(p.samples)},
                      {"volume", p.volume},
                      {"order", jf::to_json(p.order)},
                      {"controls", jf::to_json(p.controls)},
                      {"length_axis", p.length_axis},
                      {"up_axis", p.up_axis}};
  if (p.springs) j["springs"] = springs_json(*p.springs);
  if (p.extent != 1.0) j["extent"] = p.extent;
  if (!p.width_profile.empty()) j["width_profile"] = p.width_profile;
  if (p.height_profile.size() == 1) j["height_profile"] = p.height_profile[0];
  if (p.height_profile.size() > 1) j["height_profile"] = p.height_profile;
  if (p.camera) j["camera"] = CameraSetCommand::camera_json(*p.camera);
  if (!p.ignore.empty()) j["ignore"] = p.ignore;
  return j;
}

std::optional<SceneObject> PlaceSketchCommand::build(const Scene& scene) {
  const SceneObject* target = scene.find(p_.object);
  if (!target) throw CommandError("field 'object': no object named '" + p_.object + "'", "object");
  require_no_tile_layers(*target, "an FFD placement");

  const auto t0 = std::chrono::steady_clock::now();
  RayCaster rays;
  for (const auto& o : scene.objects())
    if (o.visible && o.name != p_.object && o.world_mesh &&
        std::find(p_.ignore.begin(), p_.ignore.end(), o.name) == p_.ignore.end())
      rays.add_mesh(*o.world_mesh);
  rays.commit();
  const double bvh_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  SketchPlacementParams sp;
  sp.stroke_px = p_.stroke;
  if (!p_.camera && !scene.camera_set)
    throw CommandError(
        "field 'camera': stroke pixels need a camera: add a camera.set line before this one or a "
        "\"camera\" object to this line",
        "camera");
  sp.camera = p_.camera ? *p_.camera : scene.camera;
  sp.evaluate_positions = false;  // refresh() below evaluates positions and normals in one pass
  sp.half_width = p_.width;
  sp.height = p_.height;
  sp.width_profile = p_.width_profile;
  sp.height_profile = p_.height_profile;
  sp.springs = p_.springs;
  sp.samples_u = p_.samples.x;
  sp.samples_v = p_.samples.y;
  sp.volume = p_.volume == "offset" ? PlacementVolume::Offset : PlacementVolume::Extrude;
  sp.order = {p_.order.x, p_.order.y, p_.order.z};
  sp.controls = {p_.controls.x, p_.controls.y, p_.controls.z};
  sp.axes.length_axis = axis_index(p_.length_axis);
  sp.axes.up_axis = axis_index(p_.up_axis);

  const TriMesh rest = target->world_rest_mesh();
  SketchPlacementResult r = [&] {
    try {
      return place_along_stroke(rays, sp, rest.positions);
    } catch (const PlacementError& e) {
      // Map the placement's parameter names onto the log's field names.
      const std::string f = e.field() == "axes" ? "up_axis" : e.field();
      std::string msg = e.what();
      const std::string prefix = "place.sketch: " + e.field() + ": ";
      if (msg.rfind(prefix, 0) == 0) msg = msg.substr(prefix.size());
      throw CommandError("field '" + f + "': " + msg, f);
    }
  }();

  if (target->clip || p_.extent != 1.0) {
    FfdBinding& b = r.binding;
    if (target->clip) {  // embed the box of every pose, so the walking object stays inside the lattice
      std::vector<glm::dvec3> span = rest.positions;
      const ClipBinding& cb = *target->clip;
      std::vector<glm::dvec3> pos, nrm;
      for (int s = 0; s < 64; ++s) {
        cb.clip->pose(cb.clip->duration_s() * s / 63.0, pos, nrm);
        TriMesh m = *target->rest_mesh;
        m.positions = pos;
        const TriMesh w = transformed(m, target->transform);
        span.insert(span.end(), w.positions.begin(), w.positions.end());
      }
      b.embedding = embed_bounding_box(span, sp.axes);
    }
    for (int c = 0; c < 3; ++c) b.embedding.linear[c][0] *= p_.extent;  // u' = e·u: the object covers [0, e]
    b.embedding.offset.x *= p_.extent;
    b.params = embed_points(b.embedding, rest.positions);
  }
  SceneObject placed = *target;
  placed.ffd = std::make_shared<const FfdBinding>(std::move(r.binding));
  placed.placement = std::make_shared<const PlacementRecord>(std::move(r.record));
  const auto te = std::chrono::steady_clock::now();
  placed.refresh();
  const double eval_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - te).count();

  const PlacementStats& st = r.stats;
  stats_ = {{"rays_total", st.rays_total},
            {"rays_hit", st.rays_hit},
            {"rays_filled", st.rays_filled},
            {"stroke_depth", st.stroke_depth},
            {"half_width_px", st.half_width_px},
            {"curve_order", st.curve_order},
            {"curve_controls", st.curve_controls},
            {"curve_fit_rms_px", st.curve_fit_rms_px},
            {"surface_fit_rms", st.surface_fit_rms},
            {"surface_fit_max", st.surface_fit_max},
            {"min_det_jacobian", st.min_det_jacobian},
            {"ms",
             {{"fit", st.ms_fit},
              {"rays", st.ms_rays},
              {"surface", st.ms_surface},
              {"volume", st.ms_volume},
              {"embed", st.ms_embed}}}};
  if (p_.springs) stats_["ms"]["springs"] = st.ms_springs;  // a stage only when it ran
  if (p_.springs)
    stats_["springs"] = {{"steps", st.springs.steps},
                         {"converged", st.springs.converged},
                         {"max_displacement", st.springs.max_displacement},
                         {"dt", st.springs.dt},
                         {"active", st.springs.active},
                         {"floors", st.springs.floors}};
  stats_["bvh_ms"] = bvh_ms;
  stats_["evaluate_ms"] = eval_ms;
  stats_["vertices"] = placed.world_mesh->vertex_count();
  stats_["length_axis"] = axis_name(sp.axes.length_axis);
  return placed;
}

}  // namespace trispline::core
