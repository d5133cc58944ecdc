// The G / R / S modal (editor/tools/transform_modal.h) driven by key presses as GLFW delivers them: typed values set
// the transform exactly, X/Y/Z constrain (again: clear), minus and backspace edit the number, Esc / right click cancel
// with nothing in the history and the object untouched, Enter / left click confirm with exactly one object.transform
// in the session log; the live preview never changes the document. The Scene panel's Location / Rotation / Scale
// fields (headless ImGui): a typed value is one object.transform when the field is left.
#include <gtest/gtest.h>

#include "core/commands/object_transform.h"
#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/transform_modal.h"
#include "tests/editor/session_test_util.h"
#include "tests/ui/headless_imgui.h"
#include "ui/scene_panel.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

using namespace trispline;

namespace {

std::vector<ui::KeyPress> keys(const std::string& typed) {  // "gx1.5\n": one press per character; \n Enter, \e Esc
  std::vector<ui::KeyPress> out;
  for (char c : typed) {
    int k = 0;
    if (c >= 'a' && c <= 'z')
      k = GLFW_KEY_A + (c - 'a');
    else if (c >= '0' && c <= '9')
      k = GLFW_KEY_0 + (c - '0');
    else if (c == '.')
      k = GLFW_KEY_PERIOD;
    else if (c == '-')
      k = GLFW_KEY_MINUS;
    else if (c == '\b')
      k = GLFW_KEY_BACKSPACE;
    else if (c == '\n')
      k = GLFW_KEY_ENTER;
    else if (c == '\x1b')
      k = GLFW_KEY_ESCAPE;
    out.push_back({k, 0});
  }
  return out;
}

std::vector<nlohmann::json> logged_transforms(const std::filesystem::path& log) {
  std::vector<nlohmann::json> out;
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) {
      auto j = nlohmann::json::parse(line);
      if (j.at("cmd") == "object.transform") out.push_back(j);
    }
  return out;
}

class Modal : public test::StateDirTest {
 protected:
  void SetUp() override {
    StateDirTest::SetUp();
    s.start(false);
    ASSERT_TRUE(s.execute(
        {{"cmd", "scene.primitive"}, {"kind", "box"}, {"name", "b"}, {"translate", {1, 0, 0}}, {"scale", 0.5}}));
    editor::Navigator nav;
    nav.frame(core::mesh_bounds(*object().world_mesh), {800, 600});
    view = nav.camera({800, 600});
  }
  const core::SceneObject& object() const { return *s.scene().find("b"); }

  // Starts with the first key of `typed` (g / r / s) at `mouse`, feeds the rest in the same frame, and runs a
  // confirmed line through the session as the app does.
  editor::TransformModal::Outcome type(const std::string& typed, glm::dvec2 mouse = {400, 300}) {
    const auto k = keys(typed);
    std::size_t first = 0;
    if (!modal.active()) {
      const auto mode = editor::TransformModal::start_key(k.at(0));
      EXPECT_TRUE(mode.has_value());
      modal.begin(*mode, object(), view, mouse);
      first = 1;
    }
    editor::TransformModalInput in;
    in.keys = k;
    in.mouse_px = mouse;
    const auto outcome = modal.update(in, first);
    if (outcome == editor::TransformModal::Outcome::confirmed) {
      EXPECT_TRUE(s.execute(modal.confirmed_line()));
    }
    return outcome;
  }

  ui::MessageLog messages;
  editor::EditorSession s{messages};
  core::Camera view;
  editor::TransformModal modal;
};

TEST_F(Modal, GrabAlongXTypedIsOneExactCommand) {
  const std::size_t before = s.history().applied();
  EXPECT_EQ(type("gx1.5\n"), editor::TransformModal::Outcome::confirmed);
  EXPECT_FALSE(modal.active());
  EXPECT_EQ(object().transform.translate, glm::dvec3(2.5, 0, 0));
  EXPECT_EQ(object().transform.scale, glm::dvec3(0.5));
  EXPECT_EQ(s.history().applied(), before + 1);
  const auto lines = logged_transforms(dir_ / "session.jsonl");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0]["translate"], nlohmann::json::parse("[2.5,0,0]"));
  EXPECT_EQ(lines[0]["object"], "b");
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(object().transform.translate, glm::dvec3(1, 0, 0));
}

TEST_F(Modal, EscAndRightClickCancelWithNothingInTheHistory) {
  const auto mesh = object().world_mesh;
  const std::size_t before = s.history().applied();
  EXPECT_EQ(type("gx3"), editor::TransformModal::Outcome::running);
  EXPECT_TRUE(modal.active());
  // The live preview shows the move; the document does not have it.
  EXPECT_EQ(modal.preview_object().transform.translate, glm::dvec3(4, 0, 0));
  EXPECT_NE(modal.preview_object().world_mesh, mesh);
  EXPECT_EQ(object().world_mesh, mesh);
  EXPECT_NE(modal.header().find("Grab"), std::string::npos);
  EXPECT_EQ(modal.header(), "Grab  [3|]  X: 3.000  (Esc cancel, Enter confirm)");
  EXPECT_EQ(type("\x1b"), editor::TransformModal::Outcome::cancelled);
  EXPECT_FALSE(modal.active());

  // Right click, after moving the mouse (no typed value).
  EXPECT_EQ(type("g", {400, 300}), editor::TransformModal::Outcome::running);
  editor::TransformModalInput in;
  in.mouse_px = {520, 260};
  EXPECT_EQ(modal.update(in), editor::TransformModal::Outcome::running);
  EXPECT_NE(modal.current().translate, glm::dvec3(1, 0, 0));
  in.right_clicked = true;
  EXPECT_EQ(modal.update(in), editor::TransformModal::Outcome::cancelled);

  EXPECT_EQ(s.history().applied(), before);
  EXPECT_EQ(object().world_mesh, mesh);
  EXPECT_EQ(object().transform.translate, glm::dvec3(1, 0, 0));
  EXPECT_TRUE(logged_transforms(dir_ / "session.jsonl").empty());
}

TEST_F(Modal, MouseGrabMovesInTheViewPlaneAndLeftClickConfirms) {
  type("g", {400, 300});
  editor::TransformModalInput in;
  in.mouse_px = {460, 300};  // 60 px to the right
  modal.update(in);
  const glm::dvec3 d = modal.current().translate - glm::dvec3(1, 0, 0);
  EXPECT_GT(glm::dot(d, view.right()), 0.0);
  EXPECT_NEAR(glm::dot(d, view.forward()), 0.0, 1e-12);  // in the view plane
  EXPECT_NEAR(glm::dot(d, view.true_up()), 0.0, 1e-12);
  // The pivot (the object's origin) follows the cursor: 60 px on screen.
  const glm::dvec3 p = view.project(modal.current().translate), p0 = view.project(glm::dvec3(1, 0, 0));
  EXPECT_NEAR(p.x - p0.x, 60.0, 0.5);
  in.left_clicked = true;
  ASSERT_EQ(modal.update(in), editor::TransformModal::Outcome::confirmed);
  ASSERT_TRUE(s.execute(modal.confirmed_line()));
  EXPECT_EQ(logged_transforms(dir_ / "session.jsonl").size(), 1u);
}

TEST_F(Modal, ScaleRotateTypedMinusBackspaceAndAxisToggle) {
  EXPECT_EQ(type("s2\n"), editor::TransformModal::Outcome::confirmed);
  EXPECT_EQ(object().transform.scale, glm::dvec3(1.0));
  EXPECT_EQ(object().transform.translate, glm::dvec3(1, 0, 0));  // about the object's origin

  EXPECT_EQ(type("rz90\n"), editor::TransformModal::Outcome::confirmed);
  EXPECT_EQ(object().transform.rotate_deg, glm::dvec3(0, 0, 90));
  EXPECT_EQ(type("rz-45\n"), editor::TransformModal::Outcome::confirmed);
  EXPECT_EQ(object().transform.rotate_deg, glm::dvec3(0, 0, 45));

  // Backspace removes the last digit; X twice clears the axis (a uniform scale again).
  EXPECT_EQ(type("sxx1.55\b\n"), editor::TransformModal::Outcome::confirmed);
  EXPECT_EQ(object().transform.scale, glm::dvec3(1.5));
  EXPECT_EQ(type("sy2\n"), editor::TransformModal::Outcome::confirmed);
  EXPECT_EQ(object().transform.scale, glm::dvec3(1.5, 3.0, 1.5));
  // G, then S: the mode switches and starts again from the original transform.
  EXPECT_EQ(type("gx5s3\n"), editor::TransformModal::Outcome::confirmed);
  EXPECT_EQ(object().transform.translate, glm::dvec3(1, 0, 0));
  EXPECT_EQ(object().transform.scale, glm::dvec3(4.5, 9.0, 4.5));
  EXPECT_EQ(logged_transforms(dir_ / "session.jsonl").size(), 6u);
  EXPECT_EQ(s.history().applied(), 7u);  // the primitive + six transforms, one step each
}

TEST_F(Modal, RotateAboutXOfATurnedObjectGoesThroughTheMatrix) {
  type("rz90\n");
  type("rx90\n");  // about world x after a turn about z: not one Euler angle any more
  const glm::dvec3 r = object().transform.rotate_deg;
  core::Transform want;
  want.rotate_deg = {90, 0, 0};
  const glm::dmat3 expect = glm::dmat3(want.matrix()) * glm::dmat3([] {
                              core::Transform t;
                              t.rotate_deg = {0, 0, 90};
                              return t.matrix();
                            }());
  core::Transform got;
  got.rotate_deg = r;
  const glm::dmat3 m(got.matrix());
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m[c][k], expect[c][k], 1e-9) << r.x << " " << r.y << " " << r.z;
}

TEST_F(Modal, MouseScaleIsTheDistanceRatioAndMouseRotateTurnsAboutTheViewAxis) {
  const glm::dvec3 p = view.project(glm::dvec3(1, 0, 0));  // the pivot: the box's origin
  const glm::dvec2 c(p.x, p.y);
  type("s", c + glm::dvec2(40, 0));
  editor::TransformModalInput in;
  in.mouse_px = c + glm::dvec2(0, -100);  // 2.5 times as far from the pivot
  modal.update(in);
  EXPECT_NEAR(modal.current().scale.x, 0.5 * 2.5, 1e-12);
  EXPECT_EQ(modal.header(), "Scale  2.500  (Esc cancel, Enter confirm)");
  EXPECT_EQ(modal.current().translate, glm::dvec3(1, 0, 0));
  in.keys = keys("\x1b");
  modal.update(in);

  // A quarter turn counter-clockwise on screen = +90 degrees about the axis pointing at the viewer.
  type("r", c + glm::dvec2(50, 0));
  in.keys.clear();
  in.mouse_px = c + glm::dvec2(0, -50);
  modal.update(in);
  core::Transform t;
  t.rotate_deg = modal.current().rotate_deg;
  const glm::dmat3 got(t.matrix());
  const glm::dmat3 want(glm::rotate(glm::dmat4(1.0), glm::radians(90.0), -view.forward()));
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(got[a][b], want[a][b], 1e-9);
  EXPECT_EQ(modal.header(), "Rotate  View: 90.00 deg  (Esc cancel, Enter confirm)");
  EXPECT_EQ(modal.current().translate, glm::dvec3(1, 0, 0));
  in.right_clicked = true;
  EXPECT_EQ(modal.update(in), editor::TransformModal::Outcome::cancelled);
}

TEST(EulerXyz, RoundTripsRotationMatrices) {
  for (double x : {-170.0, -45.0, 0.0, 30.0, 120.0})
    for (double y : {-89.0, -30.0, 0.0, 10.0, 60.0, 89.5})
      for (double z : {-135.0, 0.0, 45.0, 179.0}) {
        core::Transform t;
        t.rotate_deg = {x, y, z};
        const glm::dmat3 m(t.matrix());
        core::Transform back;
        back.rotate_deg = editor::euler_xyz_deg(m);
        const glm::dmat3 m2(back.matrix());
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) ASSERT_NEAR(m[a][b], m2[a][b], 1e-12) << x << " " << y << " " << z;
        EXPECT_NEAR(back.rotate_deg.x, x, 1e-9);
        EXPECT_NEAR(back.rotate_deg.y, y, 1e-9);
        EXPECT_NEAR(back.rotate_deg.z, z, 1e-9);
      }
  // Gimbal lock (y = 90): only x − z is defined; the matrix still round-trips.
  core::Transform t;
  t.rotate_deg = {30, 90, 10};
  core::Transform back;
  back.rotate_deg = editor::euler_xyz_deg(glm::dmat3(t.matrix()));
  const glm::dmat3 m(t.matrix()), m2(back.matrix());
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(m[a][b], m2[a][b], 1e-9);
}

TEST_F(Modal, InvalidTypedScaleIsRefusedByTheCommandAndChangesNothing) {
  const auto mesh = object().world_mesh;
  EXPECT_EQ(type("s0"), editor::TransformModal::Outcome::running);
  EXPECT_EQ(modal.preview_object().world_mesh, mesh);  // the preview shows the object as it is
  editor::TransformModalInput in;
  in.keys = keys("\n");
  ASSERT_EQ(modal.update(in), editor::TransformModal::Outcome::confirmed);
  EXPECT_FALSE(s.execute(modal.confirmed_line()));
  EXPECT_EQ(object().world_mesh, mesh);
  bool reported = false;
  for (const auto& m : messages.messages()) reported = reported || m.text.find("field 'scale'") != std::string::npos;
  EXPECT_TRUE(reported);
}

TEST_F(Modal, PlacedObjectTurnsAboutItsShapeAndItsLatticeFollows) {
  ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "plane"}, {"name", "ground"}, {"scale", 3}}));
  ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "box"}, {"name", "crate"}, {"scale", {0.5, 0.2, 0.2}}}));
  ASSERT_TRUE(s.execute(nlohmann::json::parse(
      R"({"cmd":"camera.set","eye":[0,3,3],"target":[0,0,0],"up":[0,1,0],"fov_deg":45,"viewport":[800,600]})")));
  ASSERT_TRUE(s.execute(nlohmann::json::parse(R"({"cmd":"place.sketch","stroke":[[250,380],[400,330],[550,380]],
      "object":"crate","width":0.3,"height":0.2,"samples":[24,8],"controls":[8,4,3]})")));
  const core::SceneObject before = *s.scene().find("crate");
  const glm::dvec3 centre = core::mesh_bounds(*before.world_mesh).center();
  modal.begin(editor::TransformMode::rotate, before, view, {400, 300});
  editor::TransformModalInput in;
  in.keys = keys("y90");
  modal.update(in);
  const core::SceneObject preview = modal.preview_object();
  in.keys = keys("\n");
  ASSERT_EQ(modal.update(in), editor::TransformModal::Outcome::confirmed);
  ASSERT_TRUE(s.execute(modal.confirmed_line()));
  const core::SceneObject& after = *s.scene().find("crate");
  // The shape turned about its own centre (it stays there) and the preview was what the command made.
  EXPECT_LT(glm::length(core::mesh_bounds(*after.world_mesh).center() - centre), 1e-6);
  ASSERT_EQ(preview.world_mesh->positions.size(), after.world_mesh->positions.size());
  for (std::size_t v = 0; v < after.world_mesh->positions.size(); ++v)
    ASSERT_LT(glm::length(preview.world_mesh->positions[v] - after.world_mesh->positions[v]), 1e-9);
}

// The Scene panel's transform fields in a headless ImGui frame.
class PanelFields : public Modal {
 protected:
  ui::SceneRequest frame(test::HeadlessImGui& gui, ImVec2 mouse, bool down) {
    ui::SceneRequest req;
    gui.step(mouse, down, [&] {
      ui::ScenePanelState st{"b", true, &fields};
      const ui::SceneRequest r = ui::draw_scene_panel({{0, 0}, {400, 600}}, s.scene(), st);
      if (r.kind != ui::SceneRequest::Kind::None) req = r;
    });
    return req;
  }
  ui::TransformFields fields;
};

TEST_F(PanelFields, TypedLocationIsOneCommandWhenTheFieldIsLeft) {
  test::HeadlessImGui gui;
  ImGuiIO& io = ImGui::GetIO();
  io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
  io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
  io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
  frame(gui, {-1, -1}, false);
  frame(gui, {-1, -1}, false);
  EXPECT_EQ(fields.values[0][0], 1.0);
  EXPECT_EQ(fields.values[2][1], 0.5);
  ASSERT_GT(fields.row_max[0].x, fields.row_min[0].x);
  // One click in the Location row's x component enters text (InputScalar is a text field).
  const ImVec2 x_field(fields.row_min[0].x + 10, (fields.row_min[0].y + fields.row_max[0].y) * 0.5f);
  frame(gui, x_field, true);
  frame(gui, x_field, false);
  EXPECT_TRUE(io.WantTextInput);
  // The click selected the whole text (InputScalar's AutoSelectAll): type 2.25 and Enter within one frame, as at 2 fps.
  gui.render();  // ends the frame first: ending it later would drop the queued characters
  for (char c : std::string("2.25")) io.AddInputCharacter(c);
  io.KeysDown[GLFW_KEY_ENTER] = true;
  ui::SceneRequest r = frame(gui, x_field, false);
  io.KeysDown[GLFW_KEY_ENTER] = false;
  for (int i = 0; i < 3 && r.kind == ui::SceneRequest::Kind::None; ++i) r = frame(gui, {-1, -1}, false);
  ASSERT_EQ(r.kind, ui::SceneRequest::Kind::Transform);
  EXPECT_EQ(r.name, "b");
  EXPECT_EQ(r.field, "translate");
  EXPECT_EQ(r.value, glm::dvec3(2.25, 0, 0));
  // Nothing was requested per keystroke; the editor runs exactly this one line.
  ASSERT_TRUE(
      s.execute({{"cmd", "object.transform"}, {"object", r.name}, {r.field, {r.value.x, r.value.y, r.value.z}}}));
  EXPECT_EQ(object().transform.translate, glm::dvec3(2.25, 0, 0));
  frame(gui, {-1, -1}, false);
  EXPECT_EQ(fields.values[0][0], 2.25);  // refreshed from the scene once the field is left
  EXPECT_EQ(logged_transforms(dir_ / "session.jsonl").size(), 1u);
}

}  // namespace
