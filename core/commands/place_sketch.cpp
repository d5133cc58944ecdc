#include "core/commands/place_sketch.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/params/codecs.h"
#include "core/placement/sketch_placement.h"
#include "core/raycast/ray_caster.h"

namespace trispline::core {

namespace {

// "height_profile": one list of factors over u, or rows of factors over (u, v).
void read_height_profile(const ParamSchema<PlaceSketchParams>::Field& f, const nlohmann::json& h, PlaceSketchParams& p,
                         const CommandContext&) {
  using Numbers = params::Codec<std::vector<double>>;
  p.height_profile.clear();
  if (h.is_array() && !h.empty() && h[0].is_array()) {
    for (const nlohmann::json& row : h) p.height_profile.push_back(Numbers::read(row, f.doc.name));
  } else {
    p.height_profile.push_back(Numbers::read(h, f.doc.name));
  }
}

void write_height_profile(const ParamSchema<PlaceSketchParams>::Field& f, const PlaceSketchParams& p,
                          nlohmann::json& line) {
  if (p.height_profile.size() == 1) line[f.doc.name] = p.height_profile[0];
  if (p.height_profile.size() > 1) line[f.doc.name] = p.height_profile;
}

// The rays' scene, committed: the world meshes of the visible objects other than the one placed and those p.ignore
// lists.
void add_sketch_ray_meshes(RayCaster& rays, const Scene& scene, const PlaceSketchParams& p) {
  for (const auto& o : scene.objects())
    if (o.visible && o.name != p.object && o.world_mesh &&
        std::find(p.ignore.begin(), p.ignore.end(), o.name) == p.ignore.end())
      rays.add_mesh(*o.world_mesh);
  rays.commit();
}

// The placement pipeline's parameters (sketch_placement.h) from the line's: the stroke in the view it was drawn in.
SketchPlacementParams sketch_placement_params(const Scene& scene, const PlaceSketchParams& p) {
  SketchPlacementParams sp;
  sp.stroke_px = p.stroke;
  sp.camera = stroke_camera(scene, p.camera);
  sp.evaluate_positions = false;  // SceneObject::refresh() evaluates positions and normals in one pass
  sp.half_width = p.width;
  sp.height = p.height;
  sp.width_profile = p.width_profile;
  sp.height_profile = p.height_profile;
  sp.springs = p.springs;
  sp.samples_u = p.samples.x;
  sp.samples_v = p.samples.y;
  sp.volume = p.volume == "offset" ? PlacementVolume::Offset : PlacementVolume::Extrude;
  sp.order = {p.order.x, p.order.y, p.order.z};
  sp.controls = {p.controls.x, p.controls.y, p.controls.z};
  sp.axes.length_axis = axis_index(p.length_axis);
  sp.axes.up_axis = axis_index(p.up_axis);
  return sp;
}

// place_along_stroke for `target` (world rest mesh `rest`); a PlacementError becomes a CommandError naming the
// log's field.
SketchPlacementResult place_sketch_or_throw(const RayCaster& rays, const SketchPlacementParams& sp,
                                            const SceneObject& target, const TriMesh& rest) {
  try {
    // With tile layers the box embeds the tiles too (their tips rest on the contact surface); the binding's
    // parameters are then re-embedded for the mesh's own vertices (reembed_for_extent).
    return place_along_stroke(rays, sp,
                              target.ddm_layers.empty() ? rest.positions : positions_with_tile_layers(target, rest));
  } catch (const PlacementError& e) {
    // Map the placement's parameter names onto the log's field names.
    const std::string f = e.field() == "axes" ? "up_axis" : e.field();
    std::string msg = e.what();
    const std::string prefix = "place.sketch: " + e.field() + ": ";
    if (msg.rfind(prefix, 0) == 0) msg = msg.substr(prefix.size());
    throw CommandError("field '" + f + "': " + msg, f);
  }
}

// fit "keep": the fraction of the path (at most `extent`) over which the object keeps its proportions — its length
// scaled as its height is (height ÷ its extent along axes.up_axis) — measured along the contact curve F(u, ½, 0) by
// arc length (the lattice's speed along u is not uniform near its ends). Sets path_length to the curve's length,
// world units. Throws CommandError ("fit") when the proportions give no length along the stroke.
double keep_fit_extent(const std::vector<glm::dvec3>& rest, const FfdBinding& binding, const EmbeddingAxes& axes,
                       double height, double extent, double& path_length) {
  const int a = axes.length_axis, w = axes.up_axis;
  double lo_a = INFINITY, hi_a = -INFINITY, lo_w = INFINITY, hi_w = -INFINITY;
  for (const glm::dvec3& x : rest)
    lo_a = std::min(lo_a, x[a]), hi_a = std::max(hi_a, x[a]), lo_w = std::min(lo_w, x[w]), hi_w = std::max(hi_w, x[w]);
  // The contact curve F(u, ½, 0) by arc length (the lattice's speed along u is not uniform near its ends).
  constexpr int kSamples = 1024;
  std::vector<double> arc(kSamples + 1, 0.0);
  glm::dvec3 last = binding.lattice.eval({0.0, 0.5, 0.0});
  for (int i = 1; i <= kSamples; ++i) {
    const glm::dvec3 x = binding.lattice.eval({double(i) / kSamples, 0.5, 0.0});
    arc[i] = arc[i - 1] + glm::length(x - last);
    last = x;
  }
  const double path = arc[kSamples];
  const double object_height = hi_w - lo_w, object_length = hi_a - lo_a;
  if (object_height > 0.0 && object_length > 0.0 && path > 0.0 && std::isfinite(path)) {
    // The u where the arc length reaches the object's length scaled as its height is.
    const double length = object_length * (height / object_height);
    const auto it = std::lower_bound(arc.begin(), arc.end(), length);
    double u = 1.0;
    if (it != arc.end()) {
      const std::size_t i = std::max<std::size_t>(1, std::size_t(it - arc.begin()));
      const double span = arc[i] - arc[i - 1];
      u = (double(i - 1) + (span > 0.0 ? (length - arc[i - 1]) / span : 1.0)) / kSamples;
    }
    extent = std::min(extent, u);
  }
  if (!(extent > 0.0) || !std::isfinite(extent))
    throw CommandError("field 'fit': the object's proportions give no length along the stroke", "fit");
  path_length = path;
  return extent;
}

// Re-embeds the object's rest positions for the extent used, u' = e·u (the object covers u ∈ [0, e]). An object with
// a glTF clip is embedded by the box of its poses over the clip (64 samples, tile layers included).
void reembed_for_extent(FfdBinding& b, const SceneObject& target, const TriMesh& rest, const EmbeddingAxes& axes,
                        double extent) {
  if (target.clip) {  // embed the box of every pose, so the walking object stays inside the lattice
    std::vector<glm::dvec3> span = positions_with_tile_layers(target, rest);
    const ClipBinding& cb = *target.clip;
    std::vector<glm::dvec3> pos, nrm;
    for (int s = 0; s < 64; ++s) {
      cb.clip->pose(cb.clip->duration_s() * s / 63.0, pos, nrm);
      TriMesh m = *target.rest_mesh;
      m.positions = pos;
      const TriMesh w = transformed(m, target.transform);
      span.insert(span.end(), w.positions.begin(), w.positions.end());
    }
    b.embedding = embed_bounding_box(span, axes);
  }
  for (int c = 0; c < 3; ++c) b.embedding.linear[c][0] *= extent;  // u' = e·u: the object covers [0, e]
  b.embedding.offset.x *= extent;
  b.params = embed_points(b.embedding, rest.positions);
}

// report.json of place.sketch: the pipeline's figures (PlacementStats; the springs' only when they ran), the fit, the
// extent used, the keep fit's path length (world units), the BVH build and evaluation times (ms), the placed
// object's vertices and its length axis.
nlohmann::json place_sketch_report(const PlaceSketchParams& p, const PlacementStats& st, double extent,
                                   double path_length, double bvh_ms, double eval_ms, const SceneObject& placed,
                                   int length_axis) {
  nlohmann::json stats = {{"rays_total", st.rays_total},
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
  if (p.springs) stats["ms"]["springs"] = st.ms_springs;  // a stage only when it ran
  if (p.springs)
    stats["springs"] = {{"steps", st.springs.steps},
                        {"converged", st.springs.converged},
                        {"max_displacement", st.springs.max_displacement},
                        {"dt", st.springs.dt},
                        {"candidates", st.springs.candidates},
                        {"active", st.springs.active},
                        {"floors", st.springs.floors}};
  stats["fit"] = p.fit;
  stats["extent"] = extent;
  if (p.fit == "keep") stats["path_length"] = path_length;
  stats["bvh_ms"] = bvh_ms;
  stats["evaluate_ms"] = eval_ms;
  stats["vertices"] = placed.world_mesh->vertex_count();
  stats["length_axis"] = axis_name(length_axis);
  return stats;
}

}  // namespace

const ParamSchema<SpringParams>& spring_schema() {
  using S = SpringParams;
  static const ParamSchema<S> s =
      ParamSchema<S>("springs", "Mass-spring contact surface (seed §2.3.2)")
          .field("stiffness", &S::stiffness,
                 {.range = ParamRange::above(0),
                  .ui = {"Stiffness", 1.0, "%.1f"},
                  .help = "k: spring stiffness, force per world unit"})
          .field("damping", &S::damping,
                 {.range = ParamRange::at_least(0),
                  .ui = {"Damping", 0.5, "%.1f"},
                  .help = "ρ: damping, force per unit velocity; ρ ≥ √(8kM) is critically damped"})
          .field("mass", &S::mass,
                 {.range = ParamRange::above(0), .ui = {"Mass", 0.01, "%.3f"}, .help = "M: mass of each control point"})
          .field("threshold_deg", &S::angle_threshold_deg,
                 {.range = ParamRange{0, 180, true, true},
                  .unit = "degrees",
                  .ui = {"Threshold", 0.05, "%.2f deg"},
                  .help = "Roughness threshold: points whose neighbouring normals differ more move"})
          .field("neighbourhood", &S::neighbourhood,
                 {.range = ParamRange::at_least(-1),
                  .ui = {"Neighbourhood", 0.1},
                  .help = "Grid steps around rough points that may move; -1 = every point moves"})
          .field("max_steps", &S::max_steps,
                 {.range = ParamRange{0, 1000000}, .ui = {"Max steps", 50}, .help = "Integration steps at most"})
          .choice(
              "rest_length", &S::rest_length_initial, {"zero", "initial"},
              {.ui = {"Rest length"},
               .help =
                   "zero: springs pull neighbours together (the seed); initial: springs keep the starting distances"});
  return s;
}

auto PlaceSketchCommand::declare() -> Schema {
  return Schema("place.sketch", "Place an object along a stroke sketched over the scene (seed §2.3.1)")
      .field("object", &P::object,
             {.required = true, .help = "Id of the object to place; rays see every other visible object"})
      .field("stroke", &P::stroke,
             {.required = true,
              .unit = "pixels",
              .help = "Viewport points in drawing order, (0,0) top-left; at least 2 distinct points"})
      .field(
          "width", &P::width,
          {.required = true,
           .range = ParamRange::above(0),
           .unit = "world units",
           .ui = {"Half-width", 0.002, "%.3f"},
           .help = "d: half-width of the band around the stroke, C(u) ± d N(u), at the median depth under the stroke"})
      .field("height", &P::height,
             {.required = true,
              .range = ParamRange::above(0),
              .unit = "world units",
              .ui = {"Height", 0.002, "%.3f"},
              .help = "h: height of the deformation volume above the contact surface"})
      .choice("fit", &P::fit, {"keep", "stretch"},
              {.write = ParamWrite::UnlessDefault,
               .ui = {"Fit"},
               .help = "keep: the object keeps its proportions along the stroke (its length scaled as its height "
                       "is, at most Extent of the path); stretch: it covers Extent of the path, however long"})
      .field("extent", &P::extent,
             {.write = ParamWrite::UnlessDefault,
              .range = ParamRange{0, 1, true, false},
              .ui = {"Extent", 0.005, "%.3f"},
              .help = "Fraction of the path (u) the object covers (stretch), or at most covers (keep); below 1 it "
                      "leaves room to walk along the path (§2.4.3)"})
      .object("springs", &P::springs, spring_schema(),
              {.help = "Relax the contact surface as a mass-spring net before the volume is built (§2.3.2)"})
      .field("width_profile", &P::width_profile,
             {.write = ParamWrite::UnlessDefault,
              .default_text = "constant",
              .help = "Factors > 0 scaling d along u, piecewise linear (Eq. 2.5)"})
      .custom("height_profile", read_height_profile, write_height_profile,
              {.default_text = "constant",
               .type_text = "[number,…] or [[number,…],…]",
               .help = "Factors > 0 scaling h along u (one list) or over (u, v) (rows over v) (§2.4.1)"})
      .field("samples", &P::samples,
             {.range = ParamRange{2, 4096},
              .ui = {"Rays u x v", 0.2},
              .help = "Contact rays along × across the stroke; each ≥ the control count in that axis"})
      .choice("volume", &P::volume, {"extrude", "offset"},
              {.ui = {"Type"},
               .help = "extrude: F1, contact surface extruded towards the viewer (Eq. 2.3); offset: F2, along its "
                       "normals (Eq. 2.4)"})
      .field("order", &P::order,
             {.range = ParamRange{2, 8},
              .ui = {"Order u v w", 0.05},
              .help = "B-spline order (= degree + 1) per axis; ≤ controls"})
      .field("controls", &P::controls,
             {.range = ParamRange{2, 256},
              .ui = {"Controls", 0.1},
              .help = "Control points per axis: u along the stroke, v across, w up"})
      .choice("length_axis", &P::length_axis, axis_names(),
              {.ui = {"Length axis"}, .help = "The object's axis laid along the stroke (u)"})
      .choice("up_axis", &P::up_axis, axis_names(),
              {.ui = {"Up axis"}, .help = "The object's axis that points away from the surface (w)"})
      .check([](const P& p) {
        if (p.length_axis == p.up_axis)
          params::fail("up_axis", "must differ from length_axis ('" + p.length_axis + "')");
        // Each contact sample is a ray, a mass-spring node and a row of the volume's fit: 2²⁰ (1024 × 1024) is
        // far beyond what the seed's figures use (32 × 8) and bounds the work to about a second.
        const std::int64_t rays = std::int64_t(p.samples.x) * p.samples.y;
        if (rays > kMaxContactSamples)
          params::fail("samples", std::to_string(p.samples.x) + " × " + std::to_string(p.samples.y) + " = " +
                                      std::to_string(rays) + " contact samples: at most " +
                                      std::to_string(kMaxContactSamples) + " (1024 × 1024)");
      })
      .object("camera", &P::camera, camera_schema(),
              {.help = "The view the stroke was drawn in (camera.set's fields); default: the last camera.set"})
      .field("ignore", &P::ignore,
             {.write = ParamWrite::UnlessDefault,
              .default_text = "[]",
              .help = "Ids of objects the rays pass through (the editor lists those hidden in its viewport)"})
      .label([](const P& p) { return "Place '" + p.object + "' along stroke"; });
}

std::optional<SceneObject> PlaceSketchCommand::build(const Scene& scene) {
  const SceneObject* target = &require_object(scene, p_.object);

  const auto t0 = std::chrono::steady_clock::now();
  RayCaster rays;
  add_sketch_ray_meshes(rays, scene, p_);
  const double bvh_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  const SketchPlacementParams sp = sketch_placement_params(scene, p_);
  const TriMesh rest = target->world_rest_mesh();
  SketchPlacementResult r = place_sketch_or_throw(rays, sp, *target, rest);

  // The fraction of the path the object covers (seed Eq. 2.3–2.5 map u ∈ [0, 1] onto the whole contact curve).
  double extent = p_.extent;
  if (p_.fit == "keep")
    extent = keep_fit_extent(rest.positions, r.binding, sp.axes, p_.height, extent, fit_path_length_);
  applied_extent_ = extent;
  if (target->clip || extent != 1.0 || !target->ddm_layers.empty())
    reembed_for_extent(r.binding, *target, rest, sp.axes, extent);
  SceneObject placed = *target;
  placed.ffd = std::make_shared<const FfdBinding>(std::move(r.binding));
  placed.placement = std::make_shared<const PlacementRecord>(std::move(r.record));
  const auto te = std::chrono::steady_clock::now();
  placed.refresh();
  const double eval_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - te).count();

  stats_ =
      place_sketch_report(p_, r.stats, applied_extent_, fit_path_length_, bvh_ms, eval_ms, placed, sp.axes.length_axis);
  return placed;
}

}  // namespace trispline::core
