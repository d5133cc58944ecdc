#include "core/commands/lattice_ring.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/mesh/tri_mesh.h"
#include "core/params/codecs.h"
#include "core/spline/bspline_basis.h"

namespace trispline::core {

auto LatticeRingCommand::declare() -> Schema {
  return Schema("lattice.ring",
                "Bind an object to a ring-shaped lattice, periodic along u, optionally twisted into a Möbius band "
                "(seed §4.5, Fig. 4.5, 4.6)")
      .field("object", &P::object, {.required = true, .help = "Object to bind; any previous FFD is replaced"})
      .field("center", &P::center,
             {.unit = "world units",
              .ui = {"Centre", 0.01, "%.3f"},
              .help = "Centre of the ring, in the plane y = center.y"})
      .field(
          "radius", &P::radius,
          {.required = true,
           .range = ParamRange::above(0),
           .unit = "world units",
           .ui = {"Radius", 0.01, "%.4g"},
           .help = "Radius of the ring's centre line; more than half the width (twisted: than hypot(width/2, height))"})
      .field("width", &P::width,
             {.range = ParamRange::at_least(0),
              .unit = "world units",
              .help = "Lattice size across the ring; 0 = the object's extent"})
      .field(
          "height", &P::height,
          {.range = ParamRange::at_least(0), .unit = "world units", .help = "Lattice size up; 0 = the object's extent"})
      .field("span", &P::span,
             {.range = ParamRange{0, 1, false, true},
              .help = "Fraction of the u period (laps turns) the object covers; 0 = its length / (2π·radius·laps)"})
      .field("phase", &P::phase,
             {.unit = "parameter units",
              .ui = {"Phase", 0.005, "%.3f"},
              .help = "u where the object starts (one period = 1 = laps turns: 1 untwisted, 2 with a half twist)"})
      .field("twist_deg", &P::twist_deg,
             {.range = ParamRange{-720, 720},
              .unit = "degrees",
              .ui = {"Twist", 1.0, "%.0f deg"},
              .help = "Turn of the cross-section about the ring's centre line (v = ½, w = 0) per turn of the ring, "
                      "from outwards towards up; a multiple of 90. 180 = a Möbius band: u's period spans 2 turns, "
                      "the second upside down beneath the first (seed Fig. 4.6); ±90 spans 4 turns, 360 one. "
                      "Twisted rings want ≥ 12 control points per turn"})
      .field("controls", &P::controls,
             {.range = ParamRange{2, 256},
              .ui = {"Controls"},
              .help = "Control points per axis; u periodic, ≥ order; twisted: a multiple of the laps, ≥ 3 (better "
                      "12) per turn"})
      .field("order", &P::order, {.range = ParamRange{2, 4}, .help = "Order (= degree + 1) per axis"})
      .choice("length_axis", &P::length_axis, axis_names(), {.help = "The object's axis laid along the ring (u)"})
      .choice("up_axis", &P::up_axis, axis_names(), {.help = "The object's axis that points up (w)"})
      .check([](const P& p) {
        if (p.length_axis == p.up_axis)
          params::fail("up_axis", "must differ from length_axis ('" + p.length_axis + "')");
        for (int a = 0; a < 3; ++a)
          if (p.controls[a] < p.order[a]) params::fail("controls", "need order ≤ controls ≤ 256 per axis");
        if (std::fmod(p.twist_deg, 90.0) != 0.0)
          params::fail("twist_deg",
                       "must be a multiple of 90 degrees (the lattice closes after 1, 2 or 4 turns), got " +
                           params::format_number(p.twist_deg));
        if (p.twist_deg != 0.0) {
          const int laps = ring_twist_laps(p.twist_deg);
          if (p.controls.x % laps != 0 || p.controls.x < 3 * laps)
            params::fail("controls", "a twist of " + params::format_number(p.twist_deg) + " degrees spans " +
                                         std::to_string(laps) + " turns: controls[0] must be a multiple of " +
                                         std::to_string(laps) + ", at least 3 (better 12) per turn");
        }
      })
      .label([](const P& p) { return "Ring lattice for '" + p.object + "'"; });
}

std::optional<SceneObject> LatticeRingCommand::build(const Scene& scene) {
  const SceneObject* target = &require_object(scene, p_.object);
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  const auto t0 = Clock::now();
  const TriMesh rest = target->world_rest_mesh();
  EmbeddingAxes axes;
  axes.length_axis = axis_index(p_.length_axis);
  axes.up_axis = axis_index(p_.up_axis);
  // With tile layers the box holds the tiles too (ddm_follow.h: they ride on the ring after the DDM).
  const std::vector<glm::dvec3> held =
      target->ddm_layers.empty() ? rest.positions : positions_with_tile_layers(*target, rest);
  Embedding e = embed_bounding_box(held, axes);
  const int across_axis = 3 - axes.length_axis - axes.up_axis;
  Aabb box;
  for (const glm::dvec3& q : held) box.extend(q);
  const glm::dvec3 lo = box.lo, hi = box.hi;
  const double length = hi[axes.length_axis] - lo[axes.length_axis];
  const double width = p_.width > 0.0 ? p_.width : std::max(hi[across_axis] - lo[across_axis], 1e-6);
  const double height = p_.height > 0.0 ? p_.height : std::max(hi[axes.up_axis] - lo[axes.up_axis], 1e-6);
  const int laps = [&] {
    try {
      return ring_twist_laps(p_.twist_deg);  // the schema checked it; params built in code may not have been
    } catch (const std::invalid_argument& ex) {
      throw CommandError("field 'twist_deg': " + std::string(ex.what()), "twist_deg");
    }
  }();
  // One period of u is `laps` turns, 2π·radius·laps long.
  const double span = p_.span > 0.0 ? p_.span : length / (6.283185307179586 * p_.radius * laps);
  if (!(span > 0.0) || span >= 1.0)
    throw CommandError("field 'radius': the object (length " + std::to_string(length) +
                           ") does not fit around a ring of radius " + std::to_string(p_.radius) +
                           (laps > 1 ? " in " + std::to_string(laps) + " turns" : std::string()),
                       "radius");
  // u' = phase + span·u: scale the u row of the embedding.
  for (int c = 0; c < 3; ++c) e.linear[c][0] *= span;
  e.offset.x = p_.phase + span * e.offset.x;

  // The one condition of ring_lattice the schema cannot see (the width may come from the object).
  if (p_.radius <= 0.5 * width)
    throw CommandError("field 'radius': " + std::to_string(p_.radius) + " must exceed half the width (" +
                           std::to_string(0.5 * width) + ") or the inner edge crosses the ring's axis",
                       "radius");
  if (p_.twist_deg != 0.0 && p_.radius <= std::hypot(0.5 * width, height))
    throw CommandError("field 'radius': " + std::to_string(p_.radius) + " must exceed hypot(width / 2, height) = " +
                           std::to_string(std::hypot(0.5 * width, height)) +
                           " on a twisted ring, or the turning cross-section crosses the ring's axis",
                       "radius");
  TrivariateBSpline<glm::dvec3> lattice = [&] {
    try {
      return ring_lattice(p_.center, p_.radius, width, height, p_.controls, p_.order, p_.twist_deg);
    } catch (const std::invalid_argument& ex) {
      throw CommandError("field 'object': " + std::string(ex.what()), "object");
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
            {"laps", laps},
            {"width", width},
            {"height", height},
            {"ms_volume", ms(t0, t1)},  // rest mesh, bounding box, ring lattice
            {"ms_embed", ms(t1, t2)},
            {"ms_evaluate", ms(t2, t3)}};  // F at every vertex, CPU double reference, with normals
  return out;
}

}  // namespace trispline::core
