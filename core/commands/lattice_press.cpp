#include "core/commands/lattice_press.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace trispline::core {

namespace {

// Rebuilds `object` with `lattice` (same embedding and parameters) and evaluates it; fills ms_evaluate.
SceneObject with_lattice(const SceneObject& object, TrivariateBSpline<glm::dvec3> lattice, nlohmann::json& stats) {
  SceneObject out = object;
  out.ffd = std::make_shared<FfdBinding>(FfdBinding{std::move(lattice), object.ffd->embedding, object.ffd->params});
  const auto t0 = std::chrono::steady_clock::now();
  out.refresh();
  stats["ms_evaluate"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

glm::dvec3 raw_column(const TrivariateBSpline<glm::dvec3>& F, int i, int j) {
  const int n = F.control_counts().z;
  return F.control_point(i, j, n - 1) - F.control_point(i, j, 0);
}

}  // namespace

glm::dvec3 column_direction(const TrivariateBSpline<glm::dvec3>& F, int i, int j) {
  const glm::ivec3 c = F.control_counts();
  if (i < 0 || j < 0 || i >= c.x || j >= c.y)
    throw std::invalid_argument("column (" + std::to_string(i) + ", " + std::to_string(j) + ") is outside the " +
                                std::to_string(c.x) + " x " + std::to_string(c.y) + " columns of the lattice");
  glm::dvec3 d = raw_column(F, i, j);
  if (glm::length(d) > 0.0) return glm::normalize(d);
  d = glm::dvec3(0.0);
  for (int jj = 0; jj < c.y; ++jj)
    for (int ii = 0; ii < c.x; ++ii) {
      const glm::dvec3 e = raw_column(F, ii, jj);
      if (glm::length(e) > 0.0) d += glm::normalize(e);
    }
  if (!(glm::length(d) > 0.0)) throw std::invalid_argument("the lattice's columns have zero length");
  return glm::normalize(d);
}

const ParamSchema<LatticePressParams>& LatticePressCommand::schema() {
  using P = LatticePressParams;
  static const std::vector<std::string> falloffs(kFalloffNames.begin(), kFalloffNames.end());
  static const ParamSchema<P> s =
      ParamSchema<P>("lattice.press",
                     "Press a placed object's lattice with a sphere swept along a path (seed §2.4.1, Fig. 2.7)")
          .field("object", &P::object).required().help("A deformed object (with an FFD)")
          .field("path", &P::path).required().unit("world units").help("Sphere centres along the sweep, ≥ 1")
          .check([](const P& p) {
            if (p.path.empty()) params::fail("path", "expected a non-empty array of [x,y,z] sphere centres");
          })
          .field("radius", &P::radius).required().above(0).unit("world units").help("Sphere radius")
          .field("strength", &P::strength).required().unit("world units")
          .help("How far the contact points under the centre move along their columns; < 0 pulls")
          .choice("falloff", &P::falloff, falloffs).help("Weight over the distance from the path, 1 at 0, 0 at radius");
  return s;
}

TrivariateBSpline<glm::dvec3> press_lattice(const TrivariateBSpline<glm::dvec3>& before,
                                            const std::vector<glm::dvec3>& path, double radius, double strength,
                                            Falloff falloff, PressResult* result) {
  TrivariateBSpline<glm::dvec3> after = before;
  const glm::ivec3 c = before.control_counts();
  PressResult r;
  for (int j = 0; j < c.y; ++j)
    for (int i = 0; i < c.x; ++i) {
      const glm::dvec3 vp = column_direction(before, i, j);
      for (int k = 0; k < c.z; ++k) {
        const glm::dvec3& p = before.control_point(i, j, k);
        double w = 0.0;
        for (const glm::dvec3& centre : path) w = std::max(w, falloff_weight(falloff, glm::length(p - centre) / radius));
        if (w <= 0.0) continue;
        after.control_point(i, j, k) = p - strength * w * vp;
        ++r.moved;
        r.max_displacement = std::max(r.max_displacement, std::abs(strength) * w);
      }
    }
  if (result) *result = r;
  return after;
}

std::optional<SceneObject> LatticePressCommand::build(const Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, p_.object);
  PressResult r;
  TrivariateBSpline<glm::dvec3> after = [&] {
    try {
      return press_lattice(object.ffd->lattice, p_.path, p_.radius, p_.strength, *parse_falloff(p_.falloff), &r);
    } catch (const std::invalid_argument& e) {
      throw CommandError("field 'object': " + std::string(e.what()), "object");
    }
  }();
  stats_ = {{"moved", r.moved}, {"max_displacement", r.max_displacement}};
  return with_lattice(object, std::move(after), stats_);
}

const ParamSchema<LatticePullColumnParams>& LatticePullColumnCommand::schema() {
  using P = LatticePullColumnParams;
  static const ParamSchema<P> s =
      ParamSchema<P>("lattice.pull_column",
                     "Pull or push one contact control point and its column along V_P (seed §2.4.1)")
          .field("object", &P::object).required().help("A deformed object (with an FFD)")
          .field("column", &P::column).required().help("(i, j) of the contact control point")
          .field("distance", &P::distance).required().unit("world units").help("Move along V_P; < 0 pushes");
  return s;
}

std::optional<SceneObject> LatticePullColumnCommand::build(const Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, p_.object);
  TrivariateBSpline<glm::dvec3> after = object.ffd->lattice;
  const glm::dvec3 vp = [&] {
    try {
      return column_direction(after, p_.column.x, p_.column.y);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      const char* field = what.find("outside") != std::string::npos ? "column" : "object";
      throw CommandError("field '" + std::string(field) + "': " + what, field);
    }
  }();
  const int n = after.control_counts().z;
  for (int k = 0; k < n; ++k) after.control_point(p_.column.x, p_.column.y, k) += p_.distance * vp;
  stats_ = {{"moved", n}, {"max_displacement", std::abs(p_.distance)}};
  return with_lattice(object, std::move(after), stats_);
}

}  // namespace trispline::core
