#include "core/commands/lattice_press.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/commands/json_fields.h"

namespace trispline::core {
namespace jf = json_fields;

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

CommandPtr LatticePressCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<LatticePressCommand>();
  c->object_ = jf::get_string(j, "object");
  const nlohmann::json& path = jf::require(j, "path");
  if (!path.is_array() || path.empty())
    throw CommandError("field 'path': expected a non-empty array of [x,y,z] sphere centres", "path");
  for (std::size_t i = 0; i < path.size(); ++i) {
    try {
      c->path_.push_back(jf::get_vec3(nlohmann::json{{"path", path[i]}}, "path"));
    } catch (const CommandError& e) {
      const std::string what = e.what(), prefix = "field 'path': ";
      throw CommandError(prefix + "point " + std::to_string(i) + ": " +
                             (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what),
                         "path");
    }
  }
  c->radius_ = jf::get_number(j, "radius");
  if (!(c->radius_ > 0.0)) throw CommandError("field 'radius': must be positive (world units)", "radius");
  c->strength_ = jf::get_number(j, "strength");
  const std::string name = jf::get_string(j, "falloff", "smooth");
  const auto f = parse_falloff(name);
  if (!f) {
    std::string list;
    for (auto n : kFalloffNames) list += (list.empty() ? "" : ", ") + std::string(n);
    throw CommandError("field 'falloff': unknown falloff '" + name + "' (use " + list + ")", "falloff");
  }
  c->falloff_ = *f;
  return c;
}

nlohmann::json LatticePressCommand::to_json() const {
  nlohmann::json path = nlohmann::json::array();
  for (const glm::dvec3& p : path_) path.push_back(jf::to_json(p));
  return {{"cmd", id()},       {"object", object_},     {"path", path}, {"radius", radius_},
          {"strength", strength_}, {"falloff", to_string(falloff_)}};
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
  const SceneObject& object = require_deformed_object(scene, object_);
  PressResult r;
  TrivariateBSpline<glm::dvec3> after = [&] {
    try {
      return press_lattice(object.ffd->lattice, path_, radius_, strength_, falloff_, &r);
    } catch (const std::invalid_argument& e) {
      throw CommandError("field 'object': " + std::string(e.what()), "object");
    }
  }();
  stats_ = {{"moved", r.moved}, {"max_displacement", r.max_displacement}};
  return with_lattice(object, std::move(after), stats_);
}

CommandPtr LatticePullColumnCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<LatticePullColumnCommand>();
  c->object_ = jf::get_string(j, "object");
  c->column_ = jf::get_ivec2(j, "column");
  c->distance_ = jf::get_number(j, "distance");
  return c;
}

nlohmann::json LatticePullColumnCommand::to_json() const {
  return {{"cmd", id()}, {"object", object_}, {"column", jf::to_json(column_)}, {"distance", distance_}};
}

std::optional<SceneObject> LatticePullColumnCommand::build(const Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, object_);
  TrivariateBSpline<glm::dvec3> after = object.ffd->lattice;
  const glm::dvec3 vp = [&] {
    try {
      return column_direction(after, column_.x, column_.y);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      const char* field = what.find("outside") != std::string::npos ? "column" : "object";
      throw CommandError("field '" + std::string(field) + "': " + what, field);
    }
  }();
  const int n = after.control_counts().z;
  for (int k = 0; k < n; ++k) after.control_point(column_.x, column_.y, k) += distance_ * vp;
  stats_ = {{"moved", n}, {"max_displacement", std::abs(distance_)}};
  return with_lattice(object, std::move(after), stats_);
}

}  // namespace trispline::core
