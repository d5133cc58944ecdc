// core::SceneGuard / scene_value_error: what every command's result must satisfy, and object names.
#include <gtest/gtest.h>

#include <limits>

#include "core/scene/primitives.h"
#include "core/scene/scene_check.h"

using namespace trispline::core;

namespace {

SceneObject sphere(const std::string& name) {
  SceneObject o;
  o.name = name;
  o.source = "primitive:sphere";
  o.rest_mesh = std::make_shared<const TriMesh>(make_primitive(PrimitiveKind::Sphere));
  o.refresh();
  return o;
}

// Sets coordinate `axis` of vertex `v` of the world mesh of `name` to `value`, in a new mesh (the object changed, as
// a command changes it).
void set_world_coordinate(Scene& scene, const std::string& name, std::size_t v, int axis, double value) {
  SceneObject o = *scene.find(name);
  TriMesh m = *o.world_mesh;
  m.positions[v][axis] = value;
  o.world_mesh = std::make_shared<const TriMesh>(m);
  scene.replace(o);
}

TEST(SceneCheck, AFiniteSceneIsAccepted) {
  Scene scene;
  scene.insert(sphere("ball"));
  EXPECT_EQ(scene_value_error(scene), "");
}

TEST(SceneCheck, NonFiniteAndHugeValuesAreNamed) {
  Scene scene;
  scene.insert(sphere("ball"));
  set_world_coordinate(scene, "ball", 7, 1, std::numeric_limits<double>::infinity());
  const std::string e = scene_value_error(scene);
  EXPECT_NE(e.find("object 'ball'"), std::string::npos) << e;
  EXPECT_NE(e.find("vertex 7"), std::string::npos) << e;

  set_world_coordinate(scene, "ball", 7, 1, 2e12);  // finite, but beyond what float32 export keeps meaningful
  EXPECT_NE(scene_value_error(scene).find("beyond"), std::string::npos);

  Scene cam;
  cam.camera.eye.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(scene_value_error(cam).find("camera"), std::string::npos);
}

TEST(SceneCheck, GuardSkipsWhatDidNotChange) {
  Scene scene;
  scene.insert(sphere("ball"));
  // A mesh that was already there (same pointer) is not scanned again; a new one is.
  set_world_coordinate(scene, "ball", 0, 0, std::numeric_limits<double>::quiet_NaN());
  const SceneGuard guard(scene);
  EXPECT_EQ(guard.error(scene), "");
  scene.insert(sphere("other"));
  EXPECT_EQ(guard.error(scene), "");
  SceneObject other = *scene.find("other");
  other.transform.scale = glm::dvec3(1e308);
  scene.replace(other);
  EXPECT_NE(guard.error(scene).find("transform"), std::string::npos);
}

TEST(SceneCheck, ObjectNames) {
  EXPECT_EQ(object_name_error("bunny.001"), "");
  EXPECT_EQ(object_name_error("ünïcode ok"), "");
  EXPECT_NE(object_name_error(""), "");
  EXPECT_NE(object_name_error(std::string("a\0b", 3)), "");
  EXPECT_NE(object_name_error("s/l"), "");
  EXPECT_NE(object_name_error("tab\there"), "");
  EXPECT_NE(object_name_error(".."), "");
  EXPECT_NE(object_name_error(std::string(257, 'x')), "");
  EXPECT_EQ(sanitized_object_name("a/b\nc"), "a_b_c");
  EXPECT_EQ(sanitized_object_name(""), "object");
  EXPECT_EQ(sanitized_object_name(std::string(300, 'x')).size(), 256u);
  Scene scene;
  SceneObject o = sphere("ok");
  o.name = std::string("a\0b", 3);
  EXPECT_THROW(scene.insert(o), std::invalid_argument);
}

}  // namespace
