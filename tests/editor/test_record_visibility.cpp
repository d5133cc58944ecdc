// What object.visibility's `render` flag leaves out of recordings (editor::Recorder, replay --frames — a render farm's
// chunk — and scene.glb): a render-hidden object is absent from the frames and animation.glb, byte for byte as if it
// were removed; a viewport-hidden one is still recorded; a render-hidden volume is neither ray cast nor given
// silhouettes (its frame is the empty scene's). GL runs for real (EGL surfaceless; llvmpipe without a GPU).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/commands/camera_set.h"
#include "core/commands/object_visibility.h"
#include "core/commands/volume_load.h"
#include "core/commands/volume_silhouettes.h"
#include "core/mesh/gltf_anim_io.h"
#include "editor/replay/record.h"
#include "editor/replay/replay.h"
#include "tests/editor/session_test_util.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / "record_visibility" / name;
  fs::remove_all(dir);
  return dir;
}

core::Scene load_scene(const char* log) {
  core::Scene scene;
  EXPECT_TRUE(test::replay_log(scene, log));
  return scene;
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  EXPECT_TRUE(in.good()) << p;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

editor::RecordOptions options(const fs::path& dir, int first, int last) {
  editor::RecordOptions o;
  o.out_dir = dir;
  o.frame_first = first;
  o.frame_last = last;
  o.mp4 = false;
  return o;
}

std::vector<std::string> mesh_names(const fs::path& glb) {
  std::vector<std::string> out;
  for (const auto& m : core::read_morph_animation_info(glb).meshes) out.push_back(m.name);
  return out;
}

TEST(RecordVisibility, RenderHiddenObjectIsAbsentFromFramesAndGlb) {
  const core::Scene scene = load_scene("object_visibility.jsonl");
  ASSERT_FALSE(scene.find("t1")->render_visible);
  ASSERT_TRUE(scene.find("t1")->visible);
  ASSERT_FALSE(scene.find("ground")->visible);
  ASSERT_TRUE(scene.find("ground")->render_visible);
  ASSERT_FALSE(scene.find("veil")->visible) << "the last undo restores the state before 'viewport': true";
  ASSERT_FALSE(scene.find("veil")->render_visible);
  core::Scene without = load_scene("record_anim.jsonl");
  const core::Scene with_teapot = without;
  without.remove("t1");

  const fs::path hidden = fresh_dir("hidden"), removed = fresh_dir("removed"), full = fresh_dir("full");
  editor::record_frames(scene, options(hidden, 1, 3));
  editor::record_frames(without, options(removed, 1, 3));
  editor::record_frames(with_teapot, options(full, 1, 1));
  for (int f = 1; f <= 3; ++f) {
    const std::string name = editor::frame_file_name(f, "png");
    EXPECT_TRUE(bytes(hidden / name) == bytes(removed / name)) << name << ": the render-hidden teapot shows";
  }
  EXPECT_TRUE(bytes(full / "frame_0001.png") != bytes(hidden / "frame_0001.png")) << "the teapot is in the frame";
  EXPECT_EQ(mesh_names(hidden / "animation.glb"), std::vector<std::string>{"ground"})
      << "the viewport-hidden ground is recorded, the render-hidden teapot and box are not";

  // replay --frames (a farm chunk) and scene.glb of the same log.
  editor::ReplayOptions ro;
  ro.log = test::log_path("object_visibility.jsonl");
  ro.out_dir = fresh_dir("replay");
  ro.frames_given = true;
  ro.frames.frame_first = ro.frames.frame_last = 2;
  ASSERT_EQ(editor::run_replay(ro), 0);
  EXPECT_TRUE(bytes(ro.out_dir / "frame_0002.png") == bytes(removed / "frame_0002.png"));
  EXPECT_EQ(mesh_names(ro.out_dir / "animation.glb"), std::vector<std::string>{"ground"});
  EXPECT_EQ(mesh_names(ro.out_dir / "scene.glb"), std::vector<std::string>{"ground"});
}

TEST(RecordVolumeVisibility, RenderHiddenVolumeIsNeitherCastNorExtracted) {
  using nlohmann::json;
  core::Scene empty;
  core::CameraSetCommand::parse(json::parse(R"({"cmd":"camera.set","eye":[0,-150,60],"target":[0,0,0],"up":[0,0,1],
                                                "viewport":[96,72]})"),
                                {})
      ->redo(empty);
  core::Scene vol = empty;
  core::VolumeLoadCommand::parse(json::parse(R"({"cmd":"volume.load","analytic":"torus","name":"torus","iso":0})"), {})
      ->redo(vol);
  core::VolumeSilhouettesCommand::parse(json::parse(R"({"cmd":"volume.silhouettes","object":"torus"})"), {})->redo(vol);
  ASSERT_TRUE(vol.volumes()[0].silhouette.enabled);
  const fs::path shown = fresh_dir("volume_shown"), hidden = fresh_dir("volume_hidden"), none = fresh_dir("no_volume");
  editor::record_frames(vol, options(shown, 1, 1));
  core::ObjectVisibilityCommand::parse(json::parse(R"({"cmd":"object.visibility","object":"torus","render":false})"),
                                       {})
      ->redo(vol);
  editor::record_frames(vol, options(hidden, 1, 1));
  editor::record_frames(empty, options(none, 1, 1));
  EXPECT_TRUE(bytes(shown / "frame_0001.png") != bytes(none / "frame_0001.png")) << "the volume is drawn when shown";
  EXPECT_TRUE(bytes(hidden / "frame_0001.png") == bytes(none / "frame_0001.png")) << "the hidden volume shows";
  EXPECT_TRUE(mesh_names(hidden / "animation.glb").empty());
}

}  // namespace
