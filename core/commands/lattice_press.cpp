#include "core/commands/lattice_press.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace trispline::core {

auto LatticePressCommand::declare() -> Schema {
  static const std::vector<std::string> falloffs(kFalloffNames.begin(), kFalloffNames.end());
  return Schema("lattice.press",
                "Press a placed object's lattice with a sphere swept along a path (seed §2.4.1, Fig. 2.7)")
      .field("object", &P::object, {.required = true, .help = "A deformed object (with an FFD)"})
      .field("path", &P::path, {.required = true, .unit = "world units", .help = "Sphere centres along the sweep, ≥ 1"})
      .check([](const P& p) {
        if (p.path.empty()) params::fail("path", "expected a non-empty array of [x,y,z] sphere centres");
      })
      .field("radius", &P::radius, Schema::object_length("Radius", {0.1, 0.005, 0.5, 0.01}, "Sphere radius", true))
      .field("strength", &P::strength,
             {.required = true,
              .unit = "world units",
              .ui = {"Strength", 0.0, "%.4g"},
              .object_size = ParamObjectSize{0.0, 0.0, 1.0},
              .help = "How far the contact points under the centre move along their columns; < 0 pulls"})
      .choice("falloff", &P::falloff, falloffs, {.help = "Weight over the distance from the path, 1 at 0, 0 at radius"})
      .field(
          "keep_fold_free", &P::keep_fold_free,
          {.help = "Limit the strength (bisection) so that the pressed lattice stays certified fold-free (det J > 0)"});
}

std::string LatticePressCommand::label() const {
  std::string l = (p_.strength < 0 ? "Pull '" : "Press '") + p_.object + "' (" + p_.falloff + ")";
  if (stats_.is_object() && stats_.value("limited", false)) {
    char used[64];
    std::snprintf(used, sizeof used, ", limited to %.3g to stay fold-free", stats_.at("strength_used").get<double>());
    l += used;
  }
  return l;
}

std::optional<SceneObject> LatticePressCommand::build(const Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, p_.object);
  const Falloff falloff = *parse_falloff(p_.falloff);
  if (p_.keep_fold_free) {
    const auto t0 = std::chrono::steady_clock::now();
    FoldFreePress press = [&] {
      try {
        return press_lattice_fold_free(object.ffd->lattice, p_.path, p_.radius, p_.strength, falloff);
      } catch (const std::invalid_argument& e) {
        throw CommandError("field 'keep_fold_free': " + std::string(e.what()), "keep_fold_free");
      }
    }();
    stats_ = {{"moved", press.result.moved},
              {"max_displacement", press.result.max_displacement},
              {"strength_used", press.strength},
              {"limited", press.limited},
              {"certificates", press.certificates},
              {"ms_certify", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
    return with_lattice(object, std::move(press.lattice), stats_);
  }
  PressResult r;
  TrivariateBSpline<glm::dvec3> after = [&] {
    try {
      return press_lattice(object.ffd->lattice, p_.path, p_.radius, p_.strength, falloff, &r);
    } catch (const std::invalid_argument& e) {
      throw CommandError("field 'object': " + std::string(e.what()), "object");
    }
  }();
  stats_ = {{"moved", r.moved}, {"max_displacement", r.max_displacement}};
  return with_lattice(object, std::move(after), stats_);
}

}  // namespace trispline::core
