// The editor's timeline and precise-edit UI: the playback clock (whole frames at the timeline's fps,
// looping at the end frame), scrubbing the real Timeline panel in a headless Dear ImGui frame (mouse events, no
// window), the I / Alt+I keys issuing anim.keyframe, the Record dialog's anim.record line and a short recording
// stepped one frame per UI frame, the Sketch tool's profile curves and springs feeding place.sketch, and the Tool
// panel's control point section issuing lattice.set_point (the command:
// tests/core/commands/test_lattice_set_point.cpp).
#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "core/commands/command.h"
#include "editor/animation_ui.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "editor/tools/sketch_tool.h"
#include "headless_imgui.h"
#include "tests/editor/session_test_util.h"
#include "tests/test_paths.h"
#include "ui/curve_editor.h"
#include "ui/placement_panel.h"
#include "ui/tool_panel.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

using test::logs_dir;

using test::HeadlessImGui;

const nlohmann::json kTeapot = {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}};
const nlohmann::json kRing = {
    {"cmd", "lattice.ring"}, {"object", "t"}, {"radius", 1.2}, {"controls", {16, 3, 4}}, {"order", {4, 3, 2}}};

class TimelineUi : public test::StateDirTest {
 protected:
  void SetUp() override {
    StateDirTest::SetUp();
    ASSERT_TRUE(s.execute(kTeapot));
    ASSERT_TRUE(s.execute(kRing));
  }
  const core::SceneObject& teapot() const { return *s.scene().find("t"); }
  nlohmann::json last_cmd() const {  // compared as JSON values: 10 == 10.0
    const editor::History& h = s.history();
    return h.applied() ? h.at(h.applied() - 1).to_json() : nlohmann::json();
  }
  editor::EditorSession s{messages_};
  editor::AnimationUi anim{s, messages_};
};

}  // namespace

TEST(Playback, AdvancesWholeFramesAtFpsAndLoopsAtTheEnd) {
  core::Timeline t;  // 1..120 at 24 fps
  ui::Playback p;
  EXPECT_FALSE(ui::advance_playback(p, t, 1.0)) << "paused: the frame stays";
  EXPECT_EQ(p.frame, 1);
  p.playing = true;
  EXPECT_TRUE(ui::advance_playback(p, t, 0.5));
  EXPECT_EQ(p.frame, 13);                          // 0.5 s × 24 fps = 12 frames
  EXPECT_FALSE(ui::advance_playback(p, t, 0.03));  // 0.72 of a frame: carried, not shown
  EXPECT_TRUE(ui::advance_playback(p, t, 0.03));   // 1.44: one frame shown, 0.44 carried
  EXPECT_EQ(p.frame, 14);
  p.frame = 119;
  p.carry = 0;
  ui::advance_playback(p, t, 3.0 / 24.0);
  EXPECT_EQ(p.frame, 2) << "119 + 3 wraps past 120 to the start (Blender loops)";
  p.scrubbing = true;
  EXPECT_FALSE(ui::advance_playback(p, t, 1.0)) << "scrubbing holds the frame";
  p.scrubbing = false;
  p.frame = 500;  // the range shrank under it
  ui::advance_playback(p, t, 0.0);
  EXPECT_EQ(p.frame, 120);
  ui::advance_playback(p, t, 1e6);  // a huge stall wraps, never loops forever
  EXPECT_GE(p.frame, 1);
  EXPECT_LE(p.frame, 120);
}

TEST_F(TimelineUi, ScrubbingThePanelSetsTheFrameAndTheSceneTime) {
  ASSERT_TRUE(s.execute(ui::timeline_line(25, 0, 100)));
  HeadlessImGui gui;
  const float h = ui::timeline_panel_height();
  const ui::Rect rect{{0, 720 - h}, {1280, h}};
  const ImGuiStyle& st = ImGui::GetStyle();
  // The scrub bar: second row of the panel, full content width, 8 px inner margin (ui/timeline_panel.cpp).
  const float y =
      rect.pos.y + st.WindowPadding.y + ImGui::GetFrameHeight() + st.ItemSpacing.y + ImGui::GetFrameHeight() * 0.8f;
  const float x0 = st.WindowPadding.x + 8.0f, x1 = 1280 - st.WindowPadding.x - 8.0f;
  auto x_of = [&](double f) { return x0 + float(f / 100.0) * (x1 - x0); };
  auto draw = [&] {
    anim.begin_frame("t", false);
    anim.draw_timeline(rect, {1280, 720});
  };
  gui.step({x_of(40), y}, false, draw);
  EXPECT_EQ(anim.playback().frame, 1) << "the frame stays where it was when it is inside the range";
  EXPECT_DOUBLE_EQ(anim.time_s(), 1 / 25.0);
  gui.step({x_of(40), y}, true, draw);
  gui.step({x_of(40), y}, true, draw);
  EXPECT_EQ(anim.playback().frame, 40);
  EXPECT_TRUE(anim.playback().scrubbing);
  EXPECT_DOUBLE_EQ(anim.time_s(), 40 / 25.0) << "scene time = (frame - start) / fps";
  gui.step({x_of(73), y}, true, draw);  // drag
  EXPECT_EQ(anim.playback().frame, 73);
  gui.step({x_of(150), y}, true, draw);  // past the end: clamped
  EXPECT_EQ(anim.playback().frame, 100);
  gui.step({x_of(60), y}, false, draw);  // released: the frame stays where it was
  gui.step({x_of(60), y}, false, draw);
  EXPECT_EQ(anim.playback().frame, 100);
  EXPECT_FALSE(anim.playback().scrubbing);
  EXPECT_EQ(s.history().applied(), 3u) << "scrubbing is view state: no command";
}

TEST_F(TimelineUi, PlayAdvancesTheDrawnTime) {
  anim.begin_frame("t", true);
  const double t0 = anim.time_s();
  anim.advance(0.25);
  anim.begin_frame("t", true);
  EXPECT_EQ(anim.playback().frame, 7);  // 1 + 0.25 × 24
  EXPECT_GT(anim.time_s(), t0);
  anim.begin_frame("t", false);
  anim.advance(0.25);
  EXPECT_EQ(anim.playback().frame, 7) << "paused";
}

TEST_F(TimelineUi, InsertKeyIssuesAnimKeyframeAndAltIDeletesIt) {
  const glm::ivec2 vp(800, 600);
  // Frame 10, offset u = 0.25 typed into the panel's field, I.
  anim.begin_frame("t", false);
  anim.playback().frame = 10;
  anim.begin_frame("t", false);
  anim.panel_state() = {24, 1, 120, {0.25, 0, 0}, "t", 10, 0};
  ASSERT_TRUE(anim.handle_action(ui::MenuAction::InsertKeyframe, vp));
  EXPECT_EQ(last_cmd(), ui::keyframe_line("t", 10, {0.25, 0, 0}, "linear"));
  ASSERT_EQ(teapot().offset_keys.size(), 1u);
  EXPECT_DOUBLE_EQ(teapot().offset_keys[0].time_s, 9 / 24.0);
  // I again at the same frame with the same offset: no second history entry.
  const std::size_t keyed = s.history().size();
  ASSERT_TRUE(anim.handle_action(ui::MenuAction::InsertKeyframe, vp));
  EXPECT_EQ(s.history().size(), keyed) << "the same key again is not a new step";
  EXPECT_TRUE(logged("already has this key"));
  // Frame 30, u = 0.75, smooth; then the object's offset in between follows the keys.
  ASSERT_TRUE(anim.handle_action(ui::MenuAction::FrameNext, vp));
  EXPECT_EQ(anim.playback().frame, 11);
  anim.playback().frame = 30;
  anim.begin_frame("t", false);
  anim.panel_state() = {24, 1, 120, {0.75, 0, 0}, "t", 30, 2};
  ASSERT_TRUE(anim.handle_action(ui::MenuAction::InsertKeyframe, vp));
  ASSERT_EQ(teapot().offset_keys.size(), 2u);
  ASSERT_EQ(anim.timeline_object().key_frames.size(), 2u);
  EXPECT_NEAR(anim.timeline_object().key_frames[0], 10, 1e-9);
  EXPECT_NEAR(anim.timeline_object().key_frames[1], 30, 1e-9);
  EXPECT_NEAR(teapot().offset_at(19 / 24.0).x, 0.5, 1e-12) << "linear from the key at frame 10";
  // Without a typed value, I keys the object's current (keyed) offset.
  anim.playback().frame = 20;
  anim.begin_frame("t", false);
  EXPECT_NEAR(anim.timeline_object().offset.x, 0.5, 1e-12);
  // Alt+I at a frame without a key does nothing; at frame 30 it deletes the key (undoable).
  const std::size_t applied = s.history().applied();
  ASSERT_TRUE(anim.handle_action(ui::MenuAction::DeleteKeyframe, vp));
  EXPECT_EQ(s.history().applied(), applied);
  ASSERT_TRUE(anim.handle_action(ui::MenuAction::FrameEnd, vp));
  EXPECT_EQ(anim.playback().frame, 120);
  anim.playback().frame = 30;
  anim.begin_frame("t", false);
  ASSERT_TRUE(anim.handle_action(ui::MenuAction::DeleteKeyframe, vp));
  EXPECT_EQ(last_cmd(), ui::remove_keyframe_line("t", 30));
  EXPECT_EQ(teapot().offset_keys.size(), 1u);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(teapot().offset_keys.size(), 2u);
  EXPECT_FALSE(anim.handle_action(ui::MenuAction::Undo, vp)) << "not a timeline action";
}

// The Animate popup's lines run as commands: a row of copies along the path, and a clip error names the field.
TEST_F(TimelineUi, AnimatePopupLinesAddCopiesAndReportClipErrors) {
  ASSERT_TRUE(s.execute(ui::array_line("t", 2, 0.3)));
  ASSERT_NE(s.scene().find("t.001"), nullptr);
  ASSERT_NE(s.scene().find("t.002"), nullptr);
  EXPECT_DOUBLE_EQ(s.scene().find("t.002")->param_offset.x, teapot().param_offset.x - 0.6);
  const std::size_t applied = s.history().applied();
  EXPECT_FALSE(s.execute(ui::clip_line("t", "/nonexistent/walk.glb", "", 1.0)));  // error in the log, nothing applied
  EXPECT_EQ(s.history().applied(), applied);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.scene().find("t.001"), nullptr);
}

TEST_F(TimelineUi, ClipObjectsAreDrawnPosedAtTheFrameAndCachedPerFrame) {
  EXPECT_EQ(&anim.drawn_scene(), &s.scene()) << "no clip: the document itself";
  ASSERT_TRUE(s.open(logs_dir() / "clip_walk.jsonl"));
  anim.begin_frame("cube", false);
  const core::Scene& a = anim.drawn_scene();
  EXPECT_EQ(anim.poses_computed(), 1u);
  const std::vector<glm::dvec3> rest_1 = a.find("cube")->rest_mesh->positions;
  anim.drawn_scene();
  EXPECT_EQ(anim.poses_computed(), 1u) << "same frame, same document: the cached pose";
  anim.playback().frame = 13;
  anim.begin_frame("cube", false);
  const core::Scene& b = anim.drawn_scene();
  EXPECT_EQ(anim.poses_computed(), 2u);
  EXPECT_NE(b.find("cube")->rest_mesh->positions, rest_1) << "the clip poses the rest mesh at the frame's time";
  const core::Scene expected = core::scene_with_posed_clips(s.scene(), s.scene().timeline.time_of_frame(13));
  EXPECT_EQ(b.find("cube")->rest_mesh->positions, expected.find("cube")->rest_mesh->positions);
  EXPECT_FALSE(b.find("cube")->offset_keys.empty()) << "offset keys stay for the renderer to play";
  ASSERT_TRUE(s.execute({{"cmd", "object.visibility"}, {"object", "teapot"}, {"viewport", false}}));
  EXPECT_FALSE(anim.drawn_scene().find("teapot")->visible);
  EXPECT_EQ(anim.poses_computed(), 3u) << "the document changed (the teapot hidden)";
  ASSERT_TRUE(s.execute({{"cmd", "object.visibility"}, {"object", "cube"}, {"viewport", false}}));
  EXPECT_EQ(&anim.drawn_scene(), &s.scene()) << "the clip object hidden in the viewport: nothing posed";
  EXPECT_EQ(anim.poses_computed(), 3u);
  ASSERT_TRUE(s.undo());
  anim.drawn_scene();
  EXPECT_EQ(anim.poses_computed(), 4u) << "the document changed";
}

TEST_F(TimelineUi, InsertKeyWithoutALatticeIssuesNothing) {
  ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "box"}, {"name", "b"}}));
  const std::size_t applied = s.history().applied();
  anim.begin_frame("b", false);
  EXPECT_FALSE(anim.timeline_object().keyable);
  anim.handle_action(ui::MenuAction::InsertKeyframe, {800, 600});
  EXPECT_EQ(s.history().applied(), applied);
  EXPECT_TRUE(logged("select an object with a lattice"));
}

TEST_F(TimelineUi, ADffdSplitObjectIsKeyedLikeAPlacedOne) {
  ASSERT_TRUE(s.execute(nlohmann::json::parse(R"({"cmd":"scene.primitive","kind":"sphere","name":"ball"})")));
  ASSERT_TRUE(s.execute(nlohmann::json::parse(R"({"cmd":"scene.primitive","kind":"cylinder","name":"tool",
      "scale":[0.3,1.6,0.3],"translate":[0.013,0,0.017]})")));
  ASSERT_TRUE(s.execute(nlohmann::json::parse(R"({"cmd":"dffd.split","object":"ball","obstacles":["tool"],
      "controls":[16,12,12],"kernel_width":0.7})")));
  const std::size_t applied = s.history().applied();
  anim.begin_frame("ball", false);
  EXPECT_TRUE(anim.timeline_object().keyable) << "the Timeline keys a split object's walk (anim.keyframe)";
  anim.handle_action(ui::MenuAction::InsertKeyframe, {800, 600});
  EXPECT_EQ(s.history().applied(), applied + 1);
  EXPECT_EQ(s.scene().find("ball")->offset_keys.size(), 1u);
}

TEST_F(TimelineUi, RecordDialogDefaultsAndShortRecordingStepsOncePerUiFrame) {
  anim.begin_frame("t", false);
  ASSERT_TRUE(anim.handle_action(ui::MenuAction::RecordAnimation, {640, 360}));
  const ui::RecordDialogState& d = anim.record_dialog();
  EXPECT_TRUE(d.open);
  EXPECT_EQ(fs::path(d.out_dir), fs::current_path() / "frames") << "untitled: ./frames, never the state folder";
  EXPECT_EQ(d.frames[0], 1);
  EXPECT_EQ(d.frames[1], 120);
  EXPECT_EQ(d.size[0], 640);
  EXPECT_EQ(d.size[1], 360);
  // No camera.set in this scene: the dialog presets the current view, which the line carries as its camera.
  EXPECT_FALSE(d.scene_camera_set);
  EXPECT_EQ(d.camera, ui::kCurrentView);
  nlohmann::json line = ui::record_line(d);
  ASSERT_TRUE(line.contains("camera"));
  EXPECT_EQ(line["camera"]["viewport"], nlohmann::json({d.view.viewport.x, d.view.viewport.y}));
  line.erase("camera");
  EXPECT_EQ(line.dump(), nlohmann::json({{"cmd", "anim.record"},
                                         {"out", d.out_dir},
                                         {"format", "png"},
                                         {"frames", {1, 120}},
                                         {"glb", true},
                                         {"mp4", true},
                                         {"width", 640},
                                         {"height", 360}})
                             .dump());

  ui::RecordDialogState small;
  small.out_dir = (dir_ / "rec").string();
  small.frames[0] = 1;
  small.frames[1] = 3;
  small.size[0] = 48;
  small.size[1] = 32;
  small.glb = small.mp4 = false;
  const std::size_t applied = s.history().applied();
  ASSERT_TRUE(anim.start_recording(ui::record_line(small)))
      << (messages_.messages().empty() ? "" : messages_.messages().back().text);
  EXPECT_EQ(s.history().applied(), applied) << "anim.record is logged for replays but never an undo step";
  EXPECT_EQ(s.history().size(), applied);
  HeadlessImGui gui;
  int ui_frames = 0;
  while (anim.recording() && ui_frames < 10) {
    gui.step({0, 0}, false, [&] { anim.draw_record_ui({}); });
    ++ui_frames;
  }
  EXPECT_FALSE(anim.recording());
  EXPECT_EQ(ui_frames, 3) << "one recorded frame per UI frame";
  for (const char* f : {"frame_0001.png", "frame_0002.png", "frame_0003.png"})
    EXPECT_TRUE(fs::exists(dir_ / "rec" / f)) << f;
  EXPECT_TRUE(logged("recorded 3 frames"));
}

TEST(CurveEditor, ProfilesAreExactUniformSamples) {
  std::vector<ui::CurvePoint> c = ui::flat_curve();
  EXPECT_TRUE(ui::profile_samples(c).empty()) << "flat: the field is left out";
  c = {{0, 1}, {0.5, 2}, {1, 0.5}};
  EXPECT_EQ(ui::profile_samples(c), (std::vector<double>{1, 2, 0.5}));
  c = {{0, 1}, {0.25, 3}, {1, 1}};
  EXPECT_EQ(ui::profile_samples(c), (std::vector<double>{1, 3, 7.0 / 3.0, 5.0 / 3.0, 1}));
  // Off-grid and unsorted points, out-of-range factors: normalised onto the 1/32 grid and clamped.
  c = {{1, 9}, {0.3, -1}, {0, 1}};
  ui::normalise_curve(c);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[1].u, 10.0 / 32.0);
  EXPECT_EQ(c[1].f, ui::kCurveMinFactor);
  EXPECT_EQ(c[2].f, ui::kCurveMaxFactor);
  const std::vector<double> s = ui::profile_samples(c);
  ASSERT_EQ(s.size(), 17u);  // 10/32 = 5/16: 16 intervals
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_DOUBLE_EQ(s[i], ui::curve_value(c, i / 16.0));
  const std::vector<ui::CurvePoint> back = ui::curve_from_samples({1, 2, 0.5});
  EXPECT_EQ(ui::profile_samples(back), (std::vector<double>{1, 2, 0.5}));
}

TEST(CurveEditor, DoubleClickAddsDragMovesRightClickRemovesOneEditEach) {
  HeadlessImGui gui;
  std::vector<ui::CurvePoint> c = ui::flat_curve();
  ImVec2 lo, hi;
  int edits = 0;
  auto draw = [&] {
    ImGui::SetNextWindowPos({0, 0});
    ImGui::SetNextWindowSize({400, 300});
    ImGui::Begin("Tool");
    const ImVec2 pos = ImGui::GetCursorScreenPos();
    const float w = ImGui::GetContentRegionAvail().x;
    lo = ImVec2(pos.x + 6, pos.y + 6);  // the plot's 6 px inner margin, 90 px tall
    hi = ImVec2(pos.x + w - 6, pos.y + 90 - 6);
    edits += ui::curve_editor("width", c, "test");
    ImGui::End();
  };
  auto px = [&](double u, double f) {
    return ImVec2(lo.x + float(u) * (hi.x - lo.x), hi.y - float(f / 3.0) * (hi.y - lo.y));
  };
  gui.step({0, 299}, false, draw);
  gui.step({0, 299}, false, draw);
  // Double-click at u = 0.5, factor 2: a point (on the 1/32 grid, factor to 0.01).
  for (bool down : {true, false, true, false}) gui.step(px(0.5, 2.0), down, draw);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[1].u, 0.5);
  EXPECT_NEAR(c[1].f, 2.0, 0.015);
  EXPECT_EQ(edits, 1) << "adding is one edit";
  // Drag it down to factor 0.5: one edit when released.
  gui.step({0, 299}, false, draw);
  gui.step(px(0.5, c[1].f), true, draw);
  gui.step(px(0.5, 0.5), true, draw);
  EXPECT_EQ(edits, 1) << "no edit while dragging";
  gui.step(px(0.5, 0.5), false, draw);
  EXPECT_EQ(edits, 2);
  EXPECT_NEAR(c[1].f, 0.5, 0.015);
  EXPECT_EQ(ui::profile_samples(c).size(), 3u);
  // An end point cannot be removed; the inner one can.
  gui.step(px(0.0, 1.0), true, draw, 1);
  gui.step(px(0.0, 1.0), false, draw, 1);
  EXPECT_EQ(c.size(), 3u);
  gui.step(px(0.5, c[1].f), true, draw, 1);
  gui.step(px(0.5, c[1].f), false, draw, 1);
  EXPECT_EQ(c.size(), 2u);
  EXPECT_TRUE(ui::is_flat(c));
  EXPECT_EQ(edits, 3);
}

TEST(PlacementPanel, ProfilesSpringsAndExtentFeedPlaceSketch) {
  core::PlaceSketchParams p;
  p.object = "crate";
  const std::vector<glm::dvec2> stroke = {{300, 350}, {500, 350}};
  const core::Camera view;
  const nlohmann::json plain = editor::place_sketch_line(p, stroke, view);
  for (const char* f : {"width_profile", "height_profile", "springs", "extent", "ignore"})
    EXPECT_FALSE(plain.contains(f)) << f << ": defaults add nothing";
  // The panel's curves and springs switch, as an artist leaves them.
  ui::PlacementPanelState st;
  st.width_curve = {{0, 1}, {0.5, 2}, {1, 1}};
  st.height_curve = {{0, 0.5}, {1, 1.5}};
  p.width_profile = ui::profile_samples(st.width_curve);
  p.height_profile = {ui::profile_samples(st.height_curve)};
  core::SpringParams springs;
  springs.stiffness = 50;
  springs.rest_length_initial = true;
  p.springs = springs;
  p.extent = 0.4;
  const nlohmann::json line = editor::place_sketch_line(p, stroke, view);
  EXPECT_EQ(line["width_profile"], nlohmann::json({1, 2, 1}));
  EXPECT_EQ(line["height_profile"], nlohmann::json({0.5, 1.5}));
  EXPECT_EQ(line["springs"]["stiffness"], 50);
  EXPECT_EQ(line["springs"]["rest_length"], "initial");
  EXPECT_EQ(line["springs"]["max_steps"], 20000);
  EXPECT_EQ(line["extent"], 0.4);
  // The command accepts them, and a logged line shows again in the panel (re-placement of an adopted line).
  core::CommandContext ctx;
  const core::CommandPtr cmd = editor::CommandRegistry::builtin().parse(line, ctx);
  const auto& q = dynamic_cast<const core::PlaceSketchCommand&>(*cmd).params();
  const ui::PlacementPanelState shown = ui::PlacementPanelState::from(q);
  EXPECT_EQ(ui::profile_samples(shown.width_curve), p.width_profile);
  EXPECT_EQ(ui::profile_samples(shown.height_curve), p.height_profile[0]);
  EXPECT_EQ(shown.springs.stiffness, 50);
  EXPECT_EQ(editor::place_sketch_line(q, stroke, view), line);
}

TEST_F(TimelineUi, ControlPointSectionIssuesOneSetPointPerDrag) {
  HeadlessImGui gui;
  ui::ControlPointState state;
  state.object = "t";
  state.index[0] = 2;
  state.index[1] = 1;
  state.index[2] = 3;
  std::optional<nlohmann::json> line;
  auto draw = [&] {
    ImGui::SetNextWindowPos({0, 0});
    ImGui::SetNextWindowSize({400, 400});
    ImGui::Begin("Tool");
    if (auto l = ui::draw_control_point_section(teapot(), state)) line = l;
    ImGui::End();
  };
  gui.step({0, 0}, false, draw);
  const glm::dvec3 before = teapot().ffd->lattice.control_point(2, 1, 3);
  // Find the position field: press and drag 50 px right down the rows until a drag yields a line.
  // Below the section's header (a click there would fold it).
  for (float y = 58; y < 300 && !line; y += 4) {
    gui.step({140, y}, false, draw);
    gui.step({140, y}, true, draw);
    gui.step({190, y}, true, draw);
    gui.step({190, y}, false, draw);
    gui.step({0, 390}, false, draw);
  }
  ASSERT_TRUE(line) << "no drag on the position field produced a lattice.set_point";
  EXPECT_EQ((*line)["cmd"], "lattice.set_point");
  EXPECT_EQ((*line)["index"], nlohmann::json({2, 1, 3}));
  const glm::dvec3 p((*line)["position"][0], (*line)["position"][1], (*line)["position"][2]);
  EXPECT_NEAR(p.x, before.x + 0.1, 1e-4) << "50 px at 0.002 per px on x (rounded to the %.4f shown)";
  EXPECT_EQ(p.y, before.y);
  const std::size_t applied = s.history().applied();
  ASSERT_TRUE(s.execute(*line));
  EXPECT_EQ(s.history().applied(), applied + 1);
  EXPECT_EQ(teapot().ffd->lattice.control_point(2, 1, 3), p);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(teapot().ffd->lattice.control_point(2, 1, 3), before);
}

namespace {

// The scene a shipped log builds (every line through the registry), or the test fails.
core::Scene replay_scene(const std::string& log) {
  core::Scene scene;
  core::CommandContext ctx;
  ctx.base_dir = fs::path(TRISPLINE_SOURCE_DIR) / "assets" / "scenes" / "seed";
  std::ifstream in(ctx.base_dir / log);
  std::string text;
  while (std::getline(in, text)) {
    if (text.empty() || text[0] == '#') continue;
    const nlohmann::json line = nlohmann::json::parse(text);
    if (line.value("cmd", "") == "anim.record") continue;
    editor::CommandRegistry::builtin().parse(line, ctx)->redo(scene);
  }
  return scene;
}

}  // namespace

// Every kind of key shows on the Timeline: an incision's opening, a DFFD seam and a tile layer's offset and morph
// keys are diamonds of their own beside the offset keys.
TEST(TimelineChannels, IncisionSeamAndTileKeysAreDiamonds) {
  const ui::TimelineObject venus = ui::timeline_object(replay_scene("incision_opening.jsonl"), "venus", 1);
  ASSERT_EQ(venus.channel_keys.size(), 2u);
  EXPECT_NEAR(venus.channel_keys[0].first, 1.0, 1e-9);
  EXPECT_NEAR(venus.channel_keys[1].first, 24.0, 1e-9);
  EXPECT_EQ(venus.channel_keys[0].second, "incision opening");
  EXPECT_TRUE(venus.key_frames.empty()) << "not offset keys: Insert / Delete key leave them alone";
  const ui::TimelineObject bunny = ui::timeline_object(replay_scene("seam_stitch.jsonl"), "bunny", 1);
  ASSERT_EQ(bunny.channel_keys.size(), 2u);
  EXPECT_EQ(bunny.channel_keys[1].second, "seam");
  EXPECT_NEAR(bunny.channel_keys[1].first, 24.0, 1e-9);
  const ui::TimelineObject pot = ui::timeline_object(replay_scene("teapot_morph.jsonl"), "pot", 1);
  ASSERT_EQ(pot.channel_keys.size(), 4u);
  EXPECT_NEAR(pot.channel_keys.back().first, 96.0, 1e-9);
  EXPECT_EQ(pot.channel_keys.back().second, "tiles 'thorns' offset");
}
