// ObstacleInterior (core/dffd/obstacle_interior.h): points inside a closed box and a cylinder (welded primitives),
// their depth, points outside and on the surface, a mesh that bounds no volume listed as unchecked, bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "core/dffd/obstacle_interior.h"
#include "core/scene/primitives.h"

namespace trispline::core {
namespace obstacle_interior_test {

TriMesh moved(TriMesh m, const glm::dvec3& scale, const glm::dvec3& shift) {
  for (glm::dvec3& p : m.positions) p = p * scale + shift;
  return m;
}

TEST(ObstacleInterior, PointsInsideAClosedBoxAndCylinderWithTheirDepth) {
  const TriMesh box = moved(make_primitive(PrimitiveKind::Box), {0.5, 1.0, 2.0}, {3.0, 0.0, 0.0});  // x 2.5…3.5
  const TriMesh cylinder = make_primitive(PrimitiveKind::Cylinder);                                 // r 1, y ±1
  const ObstacleInterior interior({"box", "cylinder"}, {&box, &cylinder});
  EXPECT_TRUE(interior.unchecked().empty()) << "the primitives repeat corners per face; welded they are closed";

  const ObstacleIntrusion in = interior.intrusion({{3.0, 0.0, 0.0}, {3.4, 0.5, 1.9}, {0.0, 0.0, 0.0}, {0.5, 0.9, 0.0}});
  EXPECT_EQ(in.inside, 4u);
  // The cylinder's centre: cos(π/64) from its 64-gon's sides (the box's centre: 0.5 from its faces).
  EXPECT_EQ(in.deepest_obstacle, "cylinder");
  EXPECT_NEAR(in.max_depth, std::cos(3.14159265358979323846 / 64.0), 1e-9);
  EXPECT_EQ(in.deepest_point, glm::dvec3(0.0));

  const ObstacleIntrusion out = interior.intrusion({{2.4, 0.0, 0.0},
                                                    {3.0, 1.01, 0.0},
                                                    {0.0, 1.2, 0.0},
                                                    {1.01, 0.0, 0.0},
                                                    {3.5, 0.0, 0.0},
                                                    {0.0, 1.0, 0.0}});  // the last two on a face
  EXPECT_EQ(out.inside, 0u);
  EXPECT_EQ(out.max_depth, 0.0);
  EXPECT_TRUE(out.deepest_obstacle.empty());
}

TEST(ObstacleInterior, AMeshThatBoundsNoVolumeIsUnchecked) {
  const TriMesh plane = make_primitive(PrimitiveKind::Plane);
  TriMesh open_box = make_primitive(PrimitiveKind::Box);
  open_box.triangles.pop_back();  // one face half open
  const ObstacleInterior interior({"plane", "open"}, {&plane, &open_box});
  EXPECT_EQ(interior.unchecked(), (std::vector<std::string>{"plane", "open"}));
  EXPECT_EQ(interior.intrusion({{0.0, 0.0, 0.0}}).inside, 0u);
}

TEST(ObstacleInterior, BadInputIsRefused) {
  TriMesh box = make_primitive(PrimitiveKind::Box);
  EXPECT_THROW(ObstacleInterior({"a", "b"}, {&box}), std::invalid_argument);
  box.positions[0].x = NAN;
  EXPECT_THROW(ObstacleInterior({"nan"}, {&box}), std::invalid_argument);
}

}  // namespace obstacle_interior_test
}  // namespace trispline::core
