// camera.set (core/commands/camera_set.h): the line's camera becomes the scene's, optional fields keep the defaults,
// undo restores the camera before (and whether one was set), bad fields are named and change nothing.
#include <gtest/gtest.h>

#include "core/commands/camera_set.h"
#include "tests/core/commands/placed_crate.h"

namespace trispline::core {
namespace camera_set_test {

using nlohmann::json;

CommandPtr parse(const std::string& line) { return CameraSetCommand::parse(json::parse(line), {}); }

void expect_same_camera(const Camera& a, const Camera& b) {
  EXPECT_EQ(a.eye, b.eye);
  EXPECT_EQ(a.target, b.target);
  EXPECT_EQ(a.up, b.up);
  EXPECT_EQ(a.fov_deg, b.fov_deg);
  EXPECT_EQ(a.viewport, b.viewport);
}

TEST(CameraSet, SetsTheCameraAndUndoRestoresTheOneBefore) {
  Scene s = test::placed_crate();  // its camera: eye (0, 3, 3), 800 × 600
  const Scene before = s;
  auto c = parse(R"({"cmd":"camera.set","eye":[1,2,5],"target":[0,0.5,0],"up":[0,0,1],"fov_deg":30,
                     "viewport":[640,480]})");
  c->redo(s);
  EXPECT_EQ(s.camera.eye, glm::dvec3(1, 2, 5));
  EXPECT_EQ(s.camera.target, glm::dvec3(0, 0.5, 0));
  EXPECT_EQ(s.camera.up, glm::dvec3(0, 0, 1));
  EXPECT_EQ(s.camera.fov_deg, 30.0);
  EXPECT_EQ(s.camera.viewport, glm::ivec2(640, 480));
  EXPECT_TRUE(s.camera_set);
  EXPECT_EQ(parse(c->to_json().dump())->to_json(), c->to_json());
  c->undo(s);
  expect_same_camera(s.camera, before.camera);
  EXPECT_TRUE(s.camera_set);
  test::expect_same_meshes(s, before);  // a camera moves no object
}

TEST(CameraSet, OptionalFieldsKeepTheDefaultsAndUndoUnsetsAFirstCamera) {
  Scene s;
  ASSERT_FALSE(s.camera_set);
  auto c = parse(R"({"cmd":"camera.set","eye":[0,0,4],"target":[0,0,0]})");
  c->redo(s);
  const Camera defaults;
  EXPECT_EQ(s.camera.eye, glm::dvec3(0, 0, 4));
  EXPECT_EQ(s.camera.up, defaults.up);
  EXPECT_EQ(s.camera.fov_deg, defaults.fov_deg);
  EXPECT_EQ(s.camera.viewport, defaults.viewport);
  EXPECT_TRUE(s.camera_set);
  c->undo(s);
  EXPECT_FALSE(s.camera_set);
  expect_same_camera(s.camera, defaults);
}

TEST(CameraSet, BadFieldsAreNamedAndTheCameraIsUntouched) {
  Scene s = test::placed_crate();
  const Camera before = s.camera;
  const auto field_of = [&](const char* line) {
    return test::command_field_of<CameraSetCommand>(s, json::parse(line));
  };
  EXPECT_EQ(field_of(R"({"cmd":"camera.set","target":[0,0,0]})"), "eye");
  EXPECT_EQ(field_of(R"({"cmd":"camera.set","eye":[0,0,4]})"), "target");
  EXPECT_EQ(field_of(R"({"cmd":"camera.set","eye":[0,0,4],"target":[0,0,4]})"), "target");
  EXPECT_EQ(field_of(R"({"cmd":"camera.set","eye":[0,0,4],"target":[0,0,0],"up":[0,0,1]})"), "up");
  EXPECT_EQ(field_of(R"({"cmd":"camera.set","eye":[0,0,4],"target":[0,0,0],"fov_deg":180})"), "fov_deg");
  EXPECT_EQ(field_of(R"({"cmd":"camera.set","eye":[0,0,4],"target":[0,0,0],"fov_deg":0})"), "fov_deg");
  EXPECT_EQ(field_of(R"({"cmd":"camera.set","eye":[0,0,4],"target":[0,0,0],"viewport":[0,600]})"), "viewport");
  EXPECT_EQ(field_of(R"({"cmd":"camera.set","eye":[0,"a",4],"target":[0,0,0]})"), "eye");
  EXPECT_TRUE(test::throws_command_error([&] { parse(R"({"cmd":"camera.set","eye":[1,1,1],"target":[1,1,1]})"); },
                                         "target", "eye and target coincide"));
  expect_same_camera(s.camera, before);
}

}  // namespace camera_set_test
}  // namespace trispline::core
