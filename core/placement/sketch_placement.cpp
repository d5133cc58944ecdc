// Sketch placement (seed §2.3.1): stroke → contact surface → FFD volume → deformed object. See sketch_placement.h.
#include "core/placement/sketch_placement.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "core/placement/contact_grid.h"
#include "core/placement/stroke_curve.h"
#include "core/spline/fitting.h"

namespace trispline::core {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point& t) {
  const auto now = Clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - t).count();
  t = now;
  return ms;
}

bool finite(double x) { return std::isfinite(x); }
bool finite(const glm::dvec3& p) { return finite(p.x) && finite(p.y) && finite(p.z); }

constexpr int kMaxSamples = 4096;  // per axis; keeps nu·nv rays and the fit small enough to be interactive
constexpr int kMaxOrder = 8;       // per axis; evaluation costs O(order³) per vertex
constexpr int kMaxControls = 256;  // per axis; l·m·n stays far from int overflow and within memory

constexpr std::size_t kMaxProfileSamples = 4096;

void validate_profile_row(const std::vector<double>& row, const char* field) {
  if (row.size() < 2 || row.size() > kMaxProfileSamples)
    throw PlacementError(field, "needs 2.." + std::to_string(kMaxProfileSamples) + " samples over u (got " +
                                    std::to_string(row.size()) + ")");
  for (std::size_t i = 0; i < row.size(); ++i)
    if (!finite(row[i]) || row[i] <= 0.0)
      throw PlacementError(
          field, "sample " + std::to_string(i) + " must be a finite factor > 0 (got " + std::to_string(row[i]) + ")");
}

// Piecewise-linear interpolation of samples taken uniformly over [0,1] (t clamped).
double profile_at(const std::vector<double>& row, double t) {
  const double x = std::clamp(t, 0.0, 1.0) * static_cast<double>(row.size() - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(x), row.size() - 2);
  const double f = x - static_cast<double>(k);
  return row[k] + f * (row[k + 1] - row[k]);
}

// Bilinear in (u, v): rows over v, samples over u; one row = a function of u only.
double profile_at(const std::vector<std::vector<double>>& rows, double u, double v) {
  if (rows.empty()) return 1.0;
  if (rows.size() == 1) return profile_at(rows[0], u);
  const double y = std::clamp(v, 0.0, 1.0) * static_cast<double>(rows.size() - 1);
  const std::size_t r = std::min(static_cast<std::size_t>(y), rows.size() - 2);
  const double f = y - static_cast<double>(r);
  return (1.0 - f) * profile_at(rows[r], u) + f * profile_at(rows[r + 1], u);
}

void validate(const SketchPlacementParams& p, const std::vector<glm::dvec3>& object) {
  if (p.stroke_px.size() < 2)
    throw PlacementError("stroke", "needs at least 2 points (got " + std::to_string(p.stroke_px.size()) + ")");
  for (std::size_t i = 0; i < p.stroke_px.size(); ++i)
    if (!finite(p.stroke_px[i].x) || !finite(p.stroke_px[i].y))
      throw PlacementError("stroke", "point " + std::to_string(i) + " is not finite");
  try {
    p.camera.validate();
  } catch (const std::invalid_argument& e) {
    throw PlacementError("camera", e.what());
  }
  if (!finite(p.half_width) || p.half_width <= 0.0)
    throw PlacementError("width", "half-width must be a finite number > 0 (got " + std::to_string(p.half_width) + ")");
  if (!finite(p.height) || p.height <= 0.0)
    throw PlacementError("height", "height must be a finite number > 0 (got " + std::to_string(p.height) + ")");
  if (!p.width_profile.empty()) validate_profile_row(p.width_profile, "width_profile");
  if (p.height_profile.size() > kMaxProfileSamples)
    throw PlacementError("height_profile", "at most " + std::to_string(kMaxProfileSamples) + " rows over v");
  for (const auto& row : p.height_profile) {
    validate_profile_row(row, "height_profile");
    if (row.size() != p.height_profile[0].size())
      throw PlacementError("height_profile", "every row over v needs the same number of samples over u");
  }
  static const char* axis_name[3] = {"u", "v", "w"};
  for (int a = 0; a < 3; ++a) {
    const std::string ax = axis_name[a];
    if (p.controls[a] < 2 || p.controls[a] > kMaxControls)
      throw PlacementError("controls", "controls in " + ax + " must be in [2, " + std::to_string(kMaxControls) +
                                           "] (got " + std::to_string(p.controls[a]) + ")");
    if (p.order[a] < 2 || p.order[a] > kMaxOrder)
      throw PlacementError("order", "order in " + ax + " must be in [2, " + std::to_string(kMaxOrder) + "] (got " +
                                        std::to_string(p.order[a]) + ")");
    if (p.order[a] > p.controls[a])
      throw PlacementError("order", "order in " + ax + " (" + std::to_string(p.order[a]) +
                                        ") exceeds the control count (" + std::to_string(p.controls[a]) + ")");
  }
  const int s[2] = {p.samples_u, p.samples_v};
  for (int a = 0; a < 2; ++a) {
    const std::string ax = axis_name[a];
    if (s[a] < 2 || s[a] > kMaxSamples)
      throw PlacementError("samples", "samples in " + ax + " must be in [2, " + std::to_string(kMaxSamples) +
                                          "] (got " + std::to_string(s[a]) + ")");
    if (s[a] < p.controls[a])
      throw PlacementError("samples", "samples in " + ax + " (" + std::to_string(s[a]) +
                                          ") are fewer than the controls (" + std::to_string(p.controls[a]) + ")");
  }
  const int la = p.axes.length_axis, ua = p.axes.up_axis;
  if (la < 0 || la > 2 || ua < 0 || ua > 2 || la == ua)
    throw PlacementError("axes", "length_axis and up_axis must be distinct axes among x, y, z");
  if (object.empty()) throw PlacementError("object", "has no vertices");
  for (const auto& q : object)
    if (!finite(q)) throw PlacementError("object", "has a non-finite vertex position");
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The ray grid of step 2: #nu·nv world points (u fastest) and whether each is a hit (1) or filled (0).
struct RayGrid {
  std::vector<glm::dvec3> points;
  std::vector<unsigned char> hit;
};

// 2. rays: depth under the stroke → half-width in pixels; ruled surface R sampled, rays cast, misses filled.
RayGrid cast_ray_grid(const RayCaster& scene_rays, const SketchPlacementParams& p, const CurveSamples& cs,
                      PlacementStats& st) {
  const Camera& cam = p.camera;
  const int nu = p.samples_u, nv = p.samples_v;
  const glm::dvec3 eye = cam.eye, fwd = cam.forward();
  {
    std::vector<glm::dvec3> origins(static_cast<std::size_t>(nu), eye), dirs;
    for (const auto& c : cs.point) dirs.push_back(cam.ray_direction(c));
    const auto hits = scene_rays.intersect_all(origins, dirs);
    std::vector<double> depths;
    for (const auto& h : hits)
      if (h) depths.push_back(glm::dot(h->position - eye, fwd));
    st.stroke_rays = nu;
    st.stroke_rays_hit = static_cast<int>(depths.size());
    st.stroke_depth = depths.empty() ? glm::dot(cam.target - eye, fwd) : median(depths);
  }
  const double tan_half = std::tan(glm::radians(cam.fov_deg) * 0.5);
  st.pixels_per_world = cam.viewport.y / (2.0 * st.stroke_depth * tan_half);
  st.half_width_px = p.half_width * st.pixels_per_world;
  if (!finite(st.half_width_px) || st.half_width_px <= 0.0)
    throw PlacementError("stroke", "the scene under the stroke is behind the camera");

  const int total = nu * nv;
  std::vector<glm::dvec3> dirs(static_cast<std::size_t>(total));
  for (int j = 0; j < nv; ++j) {
    const double v = static_cast<double>(j) / (nv - 1);
    for (int i = 0; i < nu; ++i) {  // R(u,v) = v·C+ + (1−v)·C− = C + (2v − 1)·d(u)·N   (seed Eq. 2.2, 2.5)
      const double d = p.width_profile.empty()
                           ? st.half_width_px
                           : st.half_width_px * profile_at(p.width_profile, static_cast<double>(i) / (nu - 1));
      dirs[i + nu * j] = cam.ray_direction(cs.point[i] + (2.0 * v - 1.0) * d * cs.normal[i]);
    }
  }
  const auto hits = scene_rays.intersect_all(std::vector<glm::dvec3>(dirs.size(), eye), dirs);
  std::vector<double> depth(static_cast<std::size_t>(total), 0.0);
  RayGrid g{std::vector<glm::dvec3>(static_cast<std::size_t>(total)),
            std::vector<unsigned char>(static_cast<std::size_t>(total), 0)};
  for (int k = 0; k < total; ++k)
    if (hits[k]) {
      g.hit[k] = 1;
      depth[k] = glm::dot(hits[k]->position - eye, fwd);
      ++st.rays_hit;
    }
  st.rays_total = total;
  st.rays_filled = total - st.rays_hit;
  if (st.rays_hit == 0)
    throw PlacementError("stroke",
                         "all " + std::to_string(total) + " rays missed the scene (nothing under the stroke)");
  if (2 * st.rays_hit < total)
    throw PlacementError("stroke", "only " + std::to_string(st.rays_hit) + " of " + std::to_string(total) +
                                       " rays hit the scene (need at least 50%)");
  fill_missing_depths(depth, g.hit, nu, nv);
  for (int k = 0; k < total; ++k)  // hits: exact hit point; misses: on their own ray at the filled view depth
    g.points[k] = g.hit[k] ? hits[k]->position : eye + dirs[k] * (depth[k] / glm::dot(dirs[k], fwd));
  return g;
}

// 3. surface: S(u,v) = F(u,v,0) re-fitted through the grid (#nu·nv, u fastest).
BSplineSurface<glm::dvec3> fit_contact_surface(const std::vector<glm::dvec3>& grid, const SketchPlacementParams& p,
                                               PlacementStats& st) {
  const int nu = p.samples_u, nv = p.samples_v;
  const std::vector<double> pu = contact_params_u(grid, nu, nv), pv = contact_params_v(grid, nu, nv);
  std::optional<BSplineSurface<glm::dvec3>> S;
  try {
    S.emplace(fit_surface(grid, nu, nv, pu, pv, p.order[0], p.order[1], p.controls[0], p.controls[1]));
  } catch (const std::invalid_argument& e) {
    throw PlacementError("samples", std::string("contact surface fit failed: ") + e.what());
  }
  double sum2 = 0.0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double e = glm::length(S->eval(pu[i], pv[j]) - grid[i + nu * j]);
      sum2 += e * e;
      st.surface_fit_max = std::max(st.surface_fit_max, e);
    }
  st.surface_fit_rms = std::sqrt(sum2 / (nu * nv));
  return std::move(*S);
}

// 4. volume: extrude (Eq. 2.3) or offset (Eq. 2.4) layers over S's control mesh; S's control points relaxed first
// when p.springs. `clock` times the springs.
TrivariateBSpline<glm::dvec3> build_volume(BSplineSurface<glm::dvec3>& S, const RayCaster& scene_rays,
                                           const SketchPlacementParams& p, PlacementStats& st,
                                           Clock::time_point& clock) {
  const KnotVector& ku = S.knots(0);
  const KnotVector& kv = S.knots(1);
  const KnotVector kw = KnotVector::clamped_uniform(p.order[2], p.controls[2]);
  const std::vector<double> gu = ku.greville(), gv = kv.greville(), gw = kw.greville();
  const int l = ku.control_count(), m = kv.control_count(), n = kw.control_count();
  const glm::dvec3 V = -p.camera.forward();
  std::vector<glm::dvec3> dir(static_cast<std::size_t>(l * m), V);
  if (p.volume == PlacementVolume::Offset)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < l; ++i) {
        const glm::dvec3 nn = S.normal(gu[i], gv[j]);
        if (glm::length(nn) > 0.5) dir[i + l * j] = nn;
      }
  if (p.springs) {  // seed §2.3.2: relax S's control points along V_P, never below the scene under them
    std::vector<glm::dvec3>& contact = S.control_points();
    try {
      st.springs = relax_contact_surface(contact, l, m, dir, &scene_rays, *p.springs);
    } catch (const std::invalid_argument& e) {
      throw PlacementError("springs", e.what());
    }
    st.ms_springs = ms_since(clock);
  }
  std::vector<glm::dvec3> cps;
  cps.reserve(static_cast<std::size_t>(l * m * n));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < l; ++i) {  // h, or h(u) / h(u,v) at the contact control point's Greville abscissae (§2.4.1)
        const double h = p.height_profile.empty() ? p.height : p.height * profile_at(p.height_profile, gu[i], gv[j]);
        cps.push_back(S.control_point(i, j) + h * gw[k] * dir[i + l * j]);
      }
  TrivariateBSpline<glm::dvec3> lattice(ku, kv, kw, std::move(cps));
  st.min_det_jacobian = 1e300;
  for (int c = 0; c < 3; ++c)
    for (int b = 0; b < 5; ++b)
      for (int a = 0; a < 5; ++a)
        st.min_det_jacobian = std::min(st.min_det_jacobian, jacobian_determinant(lattice, {a / 4.0, b / 4.0, c / 2.0}));
  return lattice;
}

}  // namespace

SketchPlacementResult place_along_stroke(const RayCaster& scene_rays, const SketchPlacementParams& p,
                                         const std::vector<glm::dvec3>& object) {
  validate(p, object);
  const std::vector<glm::dvec2> stroke = remove_duplicate_points(p.stroke_px);
  if (stroke.size() < 2 || !(polyline_length(stroke) > 1e-9))
    throw PlacementError("stroke", "has zero length (all points coincide)");

  PlacementStats st;
  const int nu = p.samples_u, nv = p.samples_v;
  auto clock = Clock::now();

  // 1. fit: C(u) in pixels, sampled uniformly in its arc length.
  StrokeCurve sc = [&] {
    try {
      return fit_stroke_curve(stroke);
    } catch (const std::invalid_argument& e) {
      throw PlacementError("stroke", std::string("curve fit failed: ") + e.what());
    }
  }();
  st.curve_order = sc.curve.order();
  st.curve_controls = static_cast<int>(sc.curve.control_points().size());
  st.curve_fit_rms_px = sc.rms_px;
  st.curve_fit_max_px = sc.max_px;
  const CurveSamples cs = sample_by_arc_length(sc.curve, nu);
  st.ms_fit = ms_since(clock);

  RayGrid grid = cast_ray_grid(scene_rays, p, cs, st);  // 2.
  st.ms_rays = ms_since(clock);
  BSplineSurface<glm::dvec3> S = fit_contact_surface(grid.points, p, st);  // 3.
  st.ms_surface = ms_since(clock);
  TrivariateBSpline<glm::dvec3> lattice = build_volume(S, scene_rays, p, st, clock);  // 4.
  st.ms_volume = ms_since(clock);

  // 5. embed: bounding box → [0,1]³ (length axis → u, up axis → w, bottom at w = 0).
  Embedding emb;
  try {
    emb = embed_bounding_box(object, p.axes);
  } catch (const std::invalid_argument& e) {
    throw PlacementError("object", e.what());
  }
  std::vector<glm::dvec3> params = embed_points(emb, object);
  st.ms_embed = ms_since(clock);

  // 6. evaluate.
  std::vector<glm::dvec3> positions;
  if (p.evaluate_positions) ffd_evaluate(lattice, params, positions);
  st.ms_evaluate = ms_since(clock);

  PlacementRecord record{p.stroke_px, nu, nv, std::move(grid.points), std::move(grid.hit)};
  return SketchPlacementResult{FfdBinding{std::move(lattice), emb, std::move(params)}, std::move(record),
                               std::move(positions), st};
}

}  // namespace trispline::core
