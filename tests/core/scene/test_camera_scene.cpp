// Camera pixel conventions and the Scene container.
#include <gtest/gtest.h>

#include "core/scene/camera.h"
#include "core/scene/primitives.h"
#include "core/scene/scene.h"

namespace trispline::core {
namespace {

TEST(Camera, ProjectInvertsRayDirection) {
  Camera c;
  c.eye = {1.0, 2.0, 3.0};
  c.target = {0.0, 0.3, -0.2};
  c.viewport = {800, 600};
  c.fov_deg = 50;
  for (const glm::dvec2 px : {glm::dvec2(0, 0), glm::dvec2(400, 300), glm::dvec2(799, 17), glm::dvec2(123.5, 555)}) {
    const glm::dvec3 p = c.eye + 4.0 * c.ray_direction(px);
    const glm::dvec3 q = c.project(p);
    EXPECT_NEAR(q.x, px.x, 1e-9);
    EXPECT_NEAR(q.y, px.y, 1e-9);
    EXPECT_GT(q.z, 0.0);
  }
}

TEST(Camera, TopLeftPixelOrigin) {
  Camera c;
  c.eye = {0, 0, 5};
  c.target = {0, 0, 0};
  c.viewport = {200, 100};
  // A point above the target projects into the upper half (smaller y); one to the right into the right half.
  EXPECT_LT(c.project({0, 1, 0}).y, 50.0);
  EXPECT_GT(c.project({1, 0, 0}).x, 100.0);
  EXPECT_NEAR(c.project({0, 0, 0}).x, 100.0, 1e-12);
}

TEST(Camera, ValidateRejectsBadCameras) {
  Camera c;
  c.target = c.eye;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = Camera{};
  c.up = c.forward();
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = Camera{};
  c.fov_deg = 180;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = Camera{};
  c.viewport = {0, 10};
  EXPECT_THROW(c.validate(), std::invalid_argument);
  EXPECT_NO_THROW(Camera{}.validate());
}

TEST(Scene, InsertFindRemoveAndUniqueNames) {
  Scene s;
  SceneObject o;
  o.name = "cube";
  o.rest_mesh = std::make_shared<const TriMesh>(make_primitive(PrimitiveKind::Box));
  o.refresh();
  s.insert(o);
  EXPECT_THROW(s.insert(o), std::invalid_argument);
  EXPECT_EQ(s.unique_name("cube"), "cube.001");
  EXPECT_EQ(s.unique_name("ball"), "ball");
  o.name = "cube.001";
  s.insert(o, 0);
  EXPECT_EQ(s.objects()[0].name, "cube.001");
  EXPECT_EQ(s.remove("cube").name, "cube");
  EXPECT_THROW(s.remove("cube"), std::out_of_range);
  EXPECT_NEAR(s.bounds().size().x, 2.0, 1e-12);
}

TEST(Transform, ScaleThenRotateThenTranslate) {
  Transform t;
  t.scale = glm::dvec3(2.0);
  t.rotate_deg = {0, 90, 0};
  t.translate = {1, 0, 0};
  const glm::dvec3 p = glm::dvec3(t.matrix() * glm::dvec4(1, 0, 0, 1));
  // (1,0,0) → scale (2,0,0) → 90° about y: (0,0,-2) → translate (1,0,-2).
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 0.0, 1e-12);
  EXPECT_NEAR(p.z, -2.0, 1e-12);
}

TEST(Transform, MirroringKeepsOutwardWinding) {
  const TriMesh box = make_primitive(PrimitiveKind::Box);
  Transform mirror;
  mirror.scale = {-1, 1, 1};
  const TriMesh m = transformed(box, mirror);
  // Signed volume stays positive: the winding is flipped along with the mirror.
  double vol = 0;
  for (const auto& f : m.triangles)
    vol += glm::dot(m.positions[f.x], glm::cross(m.positions[f.y], m.positions[f.z])) / 6.0;
  EXPECT_GT(vol, 0.0);
}

}  // namespace
}  // namespace trispline::core
