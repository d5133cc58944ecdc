// Every bad input of place_along_stroke throws PlacementError naming the field; rays that miss are reported.
#include <gtest/gtest.h>

#include "core/placement/contact_grid.h"
#include "placement_test_util.h"

using namespace trispline::core;
using namespace trispline::core::test;

namespace {

// Runs the placement and returns the PlacementError's field and message ("" if nothing was thrown).
std::pair<std::string, std::string> error_of(const SketchPlacementParams& p, const std::vector<glm::dvec3>& object,
                                             const TriMesh& scene) {
  const RayCaster rc = caster_for(scene);
  try {
    place_along_stroke(rc, p, object);
  } catch (const PlacementError& e) {
    return {e.field(), e.what()};
  }
  return {"", ""};
}

TriMesh plane(double half) {
  return height_field(half, 4, [](double, double) { return 0.0; });
}

}  // namespace

TEST(PlacementErrors, EachBadInputNamesItsField) {
  const auto obj = tessellated_box({2.0, 0.5, 0.6}, {0.0, 0.0, 0.0}, 2).positions;
  const TriMesh scene = plane(5.0);
  struct Case {
    const char* field;
    std::function<void(SketchPlacementParams&)> edit;
  };
  const std::vector<Case> cases{
      {"stroke",
       [](auto& p) {
         p.stroke_px = {{100, 100}};
       }},
      {"stroke", [](auto& p) { p.stroke_px = {}; }},
      {"stroke",
       [](auto& p) {
         p.stroke_px = {{100, 100}, {100, 100}, {100, 100}};
       }},
      {"stroke", [](auto& p) { p.stroke_px[1].x = std::nan(""); }},
      {"stroke", [](auto& p) { p.stroke_px[2].y = INFINITY; }},
      {"camera", [](auto& p) { p.camera.target = p.camera.eye; }},
      {"width", [](auto& p) { p.half_width = 0.0; }},
      {"width", [](auto& p) { p.half_width = -1.0; }},
      {"width", [](auto& p) { p.half_width = std::nan(""); }},
      {"height", [](auto& p) { p.height = 0.0; }},
      {"height", [](auto& p) { p.height = -0.2; }},
      {"samples", [](auto& p) { p.samples_u = 1; }},
      {"samples", [](auto& p) { p.samples_v = 0; }},
      {"samples", [](auto& p) { p.samples_u = 6; }},  // < controls[0] = 10
      {"samples", [](auto& p) { p.samples_v = 4; }},  // < controls[1] = 5
      {"order", [](auto& p) { p.order[0] = 11; }},    // > controls[0]
      {"order", [](auto& p) { p.order[2] = 3; }},     // > controls[2] = 2
      {"order", [](auto& p) { p.order[1] = 1; }},
      {"controls", [](auto& p) { p.controls[2] = 1; }},
      {"axes",
       [](auto& p) {
         p.axes = {1, 1};
       }},
      {"axes",
       [](auto& p) {
         p.axes = {0, 5};
       }},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SketchPlacementParams p = default_params(straight_stroke());
    cases[i].edit(p);
    const auto [field, msg] = error_of(p, obj, scene);
    EXPECT_EQ(field, cases[i].field) << "case " << i << ": " << msg;
    EXPECT_NE(msg.find(cases[i].field), std::string::npos) << msg;
  }
  const SketchPlacementParams ok = default_params(straight_stroke());
  EXPECT_EQ(error_of(ok, {}, scene).first, "object");
  EXPECT_EQ(error_of(ok, {{0, 0, 0}, {1, std::nan(""), 0}}, scene).first, "object");
  EXPECT_EQ(error_of(ok, obj, scene).first, "");  // the unedited parameters are valid
}

TEST(PlacementErrors, AllRaysMissingIsAClearError) {
  const auto obj = tessellated_box({2.0, 0.5, 0.6}, {0.0, 0.0, 0.0}, 2).positions;
  SketchPlacementParams p = default_params({{20, 20}, {300, 40}});  // far off the small plane
  const auto [field, msg] = error_of(p, obj, plane(1.0));
  EXPECT_EQ(field, "stroke");
  EXPECT_NE(msg.find("all 360 rays missed"), std::string::npos) << msg;
  EXPECT_EQ(error_of(p, obj, TriMesh{}).first, "stroke");  // empty scene
}

TEST(PlacementErrors, TooFewHitsReportsCounts) {
  const auto obj = tessellated_box({2.0, 0.5, 0.6}, {0.0, 0.0, 0.0}, 2).positions;
  // Plane of half-size 1 spans pixels ~495..785 at depth 6; the stroke runs mostly beyond it.
  SketchPlacementParams p = default_params({{700, 360}, {1250, 360}});
  const auto [field, msg] = error_of(p, obj, plane(1.0));
  EXPECT_EQ(field, "stroke");
  EXPECT_NE(msg.find("only"), std::string::npos) << msg;
  EXPECT_NE(msg.find("of 360 rays hit"), std::string::npos) << msg;
}

TEST(ContactGrid, FillIsOrderIndependentMeanOfNeighbours) {
  // 3×3 grid, only the corners known: edges take their two 4-neighbours, the centre its 4 filled edges.
  std::vector<double> d{1, 0, 3, 0, 0, 0, 5, 0, 7};
  const std::vector<unsigned char> known{1, 0, 1, 0, 0, 0, 1, 0, 1};
  EXPECT_EQ(fill_missing_depths(d, known, 3, 3), 2);
  EXPECT_DOUBLE_EQ(d[1], 2.0);
  EXPECT_DOUBLE_EQ(d[3], 3.0);
  EXPECT_DOUBLE_EQ(d[5], 5.0);
  EXPECT_DOUBLE_EQ(d[7], 6.0);
  EXPECT_DOUBLE_EQ(d[4], 4.0);
  std::vector<double> e{0, 0};
  EXPECT_EQ(fill_missing_depths(e, {0, 0}, 2, 1), -1);
}
