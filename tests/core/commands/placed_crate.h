// A crate placed over a plane by place.sketch, seen from above: the scene the animation and placement command tests
// start from, and the checks they share.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/commands/anim_clip.h"
#include "core/commands/anim_keyframe.h"
#include "core/commands/anim_keys.h"
#include "core/commands/anim_timeline.h"
#include "core/commands/camera_set.h"
#include "core/commands/place_array.h"
#include "core/commands/place_sketch.h"
#include "core/commands/scene_load.h"
#include "core/commands/scene_primitive.h"
#include "tests/core/commands/command_test_util.h"

namespace trispline::test {

using core::Scene;
using core::TriMesh;
using nlohmann::json;

// Runs a line of any command the crate tests use.
inline core::CommandPtr run_crate_line(Scene& scene, const json& line) {
  using namespace core;
  return run_line<ScenePrimitiveCommand, CameraSetCommand, PlaceSketchCommand, AnimTimelineCommand, AnimKeyframeCommand,
                  PlaceArrayCommand, AnimClipCommand>(scene, line);
}

// The crate along a curved stroke, covering `extent` of it ("fit":"stretch": the extent as given).
inline json place_line(double extent) {
  json j = json::parse(R"({"cmd":"place.sketch","stroke":[[250,380],[330,340],[400,330],[470,340],[550,380]],
    "object":"crate","width":0.3,"height":0.2,"samples":[24,8],"order":[4,4,3],"controls":[8,4,3],"fit":"stretch"})");
  if (extent != 1.0) j["extent"] = extent;
  return j;
}

// A plane "ground" (scale 3) and a box "crate" of `crate_scale` placed over it along place_line(extent), seen from
// (0, 3, 3).
inline Scene placed_crate(double extent = 1.0, const glm::dvec3& crate_scale = {0.5, 0.2, 0.2}) {
  Scene s;
  run_crate_line(s, json::parse(R"({"cmd":"scene.primitive","kind":"plane","name":"ground","scale":3})"));
  run_crate_line(s, {{"cmd", "scene.primitive"},
                     {"kind", "box"},
                     {"name", "crate"},
                     {"scale", {crate_scale.x, crate_scale.y, crate_scale.z}}});
  run_crate_line(s, json::parse(R"({"cmd":"camera.set","eye":[0,3,3],"target":[0,0,0],"up":[0,1,0],"fov_deg":45,
                         "viewport":[800,600]})"));
  run_crate_line(s, place_line(extent));
  return s;
}

inline glm::dvec3 centroid(const TriMesh& m) {
  glm::dvec3 c(0.0);
  for (const auto& p : m.positions) c += p;
  return c / static_cast<double>(m.positions.size());
}

}  // namespace trispline::test
