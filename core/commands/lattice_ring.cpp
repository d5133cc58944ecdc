#include "core/commands/lattice_ring.h"

#include "core/commands/codecs.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/mesh/tri_mesh.h"
#include "core/spline/bspline_basis.h"

namespace trispline::core {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;

// Parameter of control point i on a periodic uniform axis: the centre of its basis function's support,
// g_i = (i − (order − 2)/2) / period (mod 1).
double periodic_control_parameter(int i, int order, int period) {
  return (static_cast<double>(i) - 0.5 * (order - 2)) / period;
}

// Radius of the periodic uniform B-spline curve whose control polygon lies on the unit circle, at the parameter of a
// control point: Σ_r N_r(g_0)·cos(2π(g_{first+r} − g_0)). The control circle is scaled by its inverse.
double periodic_circle_shrink(const KnotVector& ku) {
  const int order = ku.order(), period = ku.period();
  const double g0 = periodic_control_parameter(0, order, period);
  const double t = g0 - std::floor(g0);
  const int span = ku.find_span(t);
  std::vector<double> N(static_cast<std::size_t>(order));
  basis_functions(ku, span, t, N.data());
  double r = 0.0;
  for (int k = 0; k < order; ++k) {
    const int i = span - order + 1 + k;  // unwrapped control index; its parameter is periodic too
    r += N[k] * std::cos(kTwoPi * (periodic_control_parameter(i, order, period) - t));
  }
  return r;
}
}  // namespace

TrivariateBSpline<glm::dvec3> ring_lattice(const glm::dvec3& center, double radius, double width, double height,
                                           const glm::ivec3& controls, const glm::ivec3& order) {
  if (!(radius > 0.0) || !(width > 0.0) || !(height > 0.0) || !std::isfinite(radius + width + height))
    throw std::invalid_argument("ring lattice: radius, width and height must be positive and finite");
  if (radius <= 0.5 * width)
    throw std::invalid_argument("ring lattice: radius " + std::to_string(radius) + " must exceed half the width (" +
                                std::to_string(0.5 * width) + ") or the inner edge crosses the ring's axis");
  for (int a = 0; a < 3; ++a)
    if (order[a] < 2 || order[a] > 4)
      throw std::invalid_argument("ring lattice: orders must be 2..4 (degree 1..3), got " + std::to_string(order[a]));
  if (controls.x < order.x)
    throw std::invalid_argument("ring lattice: need at least order (" + std::to_string(order.x) +
                                ") control points around the ring, got " + std::to_string(controls.x));
  KnotVector ku = KnotVector::periodic_uniform(order.x, controls.x);
  KnotVector kv = KnotVector::clamped_uniform(order.y, controls.y);  // throws if controls < order
  KnotVector kw = KnotVector::clamped_uniform(order.z, controls.z);
  const double grow = 1.0 / periodic_circle_shrink(ku);
  const std::vector<double> gv = kv.greville(), gw = kw.greville();
  std::vector<glm::dvec3> cps;
  cps.reserve(static_cast<std::size_t>(controls.x) * controls.y * controls.z);
  for (int k = 0; k < controls.z; ++k)
    for (int j = 0; j < controls.y; ++j)
      for (int i = 0; i < controls.x; ++i) {
        const double theta = kTwoPi * periodic_control_parameter(i, order.x, controls.x);
        const double r = (radius + (gv[j] - 0.5) * width) * grow;
        // θ from +x towards +z (clockwise seen from +y), v outwards, w up: det[∂F/∂u, ∂F/∂v, ∂F/∂w] > 0.
        cps.emplace_back(center.x + r * std::cos(theta), center.y + gw[k] * height, center.z + r * std::sin(theta));
      }
  return TrivariateBSpline<glm::dvec3>(std::move(ku), std::move(kv), std::move(kw), std::move(cps));
}

const ParamSchema<LatticeRingParams>& LatticeRingCommand::schema() {
  using P = LatticeRingParams;
  static const ParamSchema<P> s =
      ParamSchema<P>("lattice.ring", "Bind an object to a ring-shaped lattice, periodic along u (seed §4.5, Fig. 4.5)")
          .field("object", &P::object).required().help("Object to bind; any previous FFD is replaced")
          .field("center", &P::center).unit("world units").help("Centre of the ring, in the plane y = center.y")
          .field("radius", &P::radius).required().above(0).unit("world units")
          .help("Radius of the ring's centre line; more than half the width")
          .field("width", &P::width).at_least(0).unit("world units")
          .help("Lattice size across the ring; 0 = the object's extent")
          .field("height", &P::height).at_least(0).unit("world units").help("Lattice size up; 0 = the object's extent")
          .field("span", &P::span).range(0, 1, false, true)
          .help("Fraction of the turn the object covers; 0 = its length / (2π·radius)")
          .field("phase", &P::phase).unit("parameter units").help("u where the object starts (one turn = 1)")
          .field("controls", &P::controls).range(2, 256).help("Control points per axis; u periodic, ≥ order")
          .field("order", &P::order).range(2, 4).help("Order (= degree + 1) per axis")
          .choice("length_axis", &P::length_axis, axis_names()).help("The object's axis laid along the ring (u)")
          .choice("up_axis", &P::up_axis, axis_names()).help("The object's axis that points up (w)")
          .check([](const P& p) {
            if (p.length_axis == p.up_axis)
              params::fail("up_axis", "must differ from length_axis ('" + p.length_axis + "')");
            for (int a = 0; a < 3; ++a)
              if (p.controls[a] < p.order[a]) params::fail("controls", "need order ≤ controls ≤ 256 per axis");
          });
  return s;
}

std::optional<SceneObject> LatticeRingCommand::build(const Scene& scene) {
  const SceneObject* target = scene.find(p_.object);
  if (!target) throw CommandError("field 'object': no object named '" + p_.object + "'", "object");
  require_no_tile_layers(*target, "a ring lattice");
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  const auto t0 = Clock::now();
  const TriMesh rest = target->world_rest_mesh();
  EmbeddingAxes axes;
  axes.length_axis = axis_index(p_.length_axis);
  axes.up_axis = axis_index(p_.up_axis);
  Embedding e = embed_bounding_box(rest.positions, axes);
  const int across_axis = 3 - axes.length_axis - axes.up_axis;
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::dvec3& q : rest.positions) {
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  const double length = hi[axes.length_axis] - lo[axes.length_axis];
  const double width = p_.width > 0.0 ? p_.width : std::max(hi[across_axis] - lo[across_axis], 1e-6);
  const double height = p_.height > 0.0 ? p_.height : std::max(hi[axes.up_axis] - lo[axes.up_axis], 1e-6);
  const double span = p_.span > 0.0 ? p_.span : length / (6.283185307179586 * p_.radius);
  if (!(span > 0.0) || span >= 1.0)
    throw CommandError("field 'radius': the object (length " + std::to_string(length) +
                           ") does not fit around a ring of radius " + std::to_string(p_.radius),
                       "radius");
  // u' = phase + span·u: scale the u row of the embedding.
  for (int c = 0; c < 3; ++c) e.linear[c][0] *= span;
  e.offset.x = p_.phase + span * e.offset.x;

  TrivariateBSpline<glm::dvec3> lattice = [&] {
    try {
      return ring_lattice(p_.center, p_.radius, width, height, p_.controls, p_.order);
    } catch (const std::invalid_argument& ex) {
      const std::string what = ex.what();
      const char* field = what.find("radius") != std::string::npos ? "radius" : "controls";
      throw CommandError("field '" + std::string(field) + "': " + what, field);
    }
  }();
  const auto t1 = Clock::now();
  auto binding = std::make_shared<FfdBinding>(FfdBinding{std::move(lattice), e, embed_points(e, rest.positions)});
  const auto t2 = Clock::now();
  SceneObject out = *target;
  out.ffd = std::move(binding);
  out.placement.reset();
  out.param_offset = glm::dvec3(0.0);
  out.offset_velocity = glm::dvec3(0.0);
  out.refresh();
  const auto t3 = Clock::now();
  stats_ = {{"vertices", rest.positions.size()},
            {"span", span},
            {"width", width},
            {"height", height},
            {"ms_volume", ms(t0, t1)},  // rest mesh, bounding box, ring lattice
            {"ms_embed", ms(t1, t2)},
            {"ms_evaluate", ms(t2, t3)}};  // F at every vertex, CPU double reference, with normals
  return out;
}

}  // namespace trispline::core
