// Recording animation sequences (anim.record, editor::Recorder, replay --frames; seed §2.4.3): frames are
// byte-identical whichever range produced them, moving objects change the frames, animation.glb holds one morph
// target per following frame, EXR frames read back, bad requests write nothing, MP4 through ffmpeg or a note,
// cancelling keeps the frames written. GL runs for real (EGL surfaceless; llvmpipe without a GPU).
#include <OpenImageIO/imageio.h>
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "core/image/image_io.h"
#include "core/mesh/gltf_anim_io.h"
#include "editor/commands/history.h"
#include "editor/replay/record.h"
#include "editor/replay/replay.h"
#include "gpu/gl/gl_context.h"
#include "gpu/render/renderer.h"
#include "tests/editor/session_test_util.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

using test::log_path;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / "record" / name;
  fs::remove_all(dir);
  return dir;
}

core::Scene load_scene(const char* log) {
  core::Scene scene;
  EXPECT_TRUE(test::replay_log(scene, log));
  return scene;
}

// `replay LOG --out test_out/record/OUT --frames FIRST-LAST`.
editor::ReplayOptions replay_frames(const char* log, const std::string& out, int first, int last) {
  editor::ReplayOptions ro;
  ro.log = log_path(log);
  ro.out_dir = fresh_dir(out);
  ro.frames_given = true;
  ro.frames.frame_first = first;
  ro.frames.frame_last = last;
  return ro;
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

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(Record, SplitRangesWriteByteIdenticalFrames) {
  const core::Scene scene = load_scene("record_anim.jsonl");
  ASSERT_EQ(scene.timeline.frame_count(), 12);
  const fs::path full = fresh_dir("full"), part = fresh_dir("part");
  const editor::RecordResult a = editor::record_frames(scene, options(full, 1, 12));
  const editor::RecordResult b = editor::record_frames(scene, options(part, 4, 6));
  EXPECT_EQ(a.frames_written, 12);
  EXPECT_EQ(b.frames_written, 3);
  EXPECT_EQ(b.frame_first, 4);
  EXPECT_EQ(b.frame_last, 6);
  EXPECT_EQ(files_in(part),
            (std::vector<std::string>{"animation.glb", "frame_0004.png", "frame_0005.png", "frame_0006.png"}));
  for (int f = 4; f <= 6; ++f) {
    const std::string name = editor::frame_file_name(f, "png");
    EXPECT_TRUE(bytes(full / name) == bytes(part / name)) << name << " differs between ranges 1-12 and 4-6";
  }
  const core::ImageRgba8 img = core::read_image_rgba8(full / "frame_0001.png");
  EXPECT_EQ(img.width, 160);  // the camera.set viewport
  EXPECT_EQ(img.height, 120);
}

TEST(Record, MovingObjectChangesTheFrames) {
  const core::Scene scene = load_scene("record_anim.jsonl");
  const fs::path dir = fresh_dir("moving");
  editor::RecordOptions o = options(dir, 1, 12);
  o.glb = false;
  o.frame_first = 1;
  o.frame_last = 1;
  editor::record_frames(scene, o);
  o.frame_first = o.frame_last = 12;
  editor::record_frames(scene, o);
  const core::ImageRgba8 first = core::read_image_rgba8(dir / "frame_0001.png");
  const core::ImageRgba8 last = core::read_image_rgba8(dir / "frame_0012.png");
  ASSERT_EQ(first.rgba.size(), last.rgba.size());
  std::size_t changed = 0;
  for (std::size_t i = 0; i < first.rgba.size(); i += 4)
    if (first.rgba[i] != last.rgba[i] || first.rgba[i + 1] != last.rgba[i + 1] || first.rgba[i + 2] != last.rgba[i + 2])
      ++changed;
  EXPECT_GT(changed, 100u) << "the teapot moved a quarter turn but only " << changed << " pixels changed";
  EXPECT_FALSE(fs::exists(dir / "animation.glb"));  // glb = false
}

TEST(Record, GlbHasOneMorphTargetPerFollowingFrame) {
  const core::Scene scene = load_scene("record_anim.jsonl");
  const fs::path dir = fresh_dir("glb");
  const editor::RecordResult r = editor::record_frames(scene, options(dir, 3, 9));
  ASSERT_EQ(r.glb, (dir / "animation.glb").string());
  const core::MorphAnimationInfo info = core::read_morph_animation_info(dir / "animation.glb");
  ASSERT_EQ(info.meshes.size(), 2u);
  EXPECT_EQ(info.meshes[0].name, "ground");
  EXPECT_EQ(info.meshes[0].targets, 0);  // never moves
  EXPECT_EQ(info.meshes[1].name, "t1");
  EXPECT_EQ(info.meshes[1].targets, 6);  // 7 frames − 1
  ASSERT_EQ(info.meshes[1].target_names.size(), 6u);
  EXPECT_EQ(info.meshes[1].target_names.front(), "frame_0004");
  EXPECT_EQ(info.meshes[1].target_names.back(), "frame_0009");
  EXPECT_EQ(info.animations, 1);
  EXPECT_EQ(info.weight_channels, 1);
  EXPECT_EQ(info.keyframes, 7);
  EXPECT_EQ(info.interpolation, "STEP");
  EXPECT_NEAR(info.duration_s, 6.0 / 24.0, 1e-6);
  // Frame index 4 of the file is timeline frame 7: base + target 4 is the CPU reference pose at frame 7.
  const core::Scene posed = core::scene_at_time(scene, scene.timeline.time_of_frame(7));
  const auto& expected = posed.find("t1")->world_mesh->positions;
  const std::vector<glm::dvec3> got = core::read_morph_frame_positions(dir / "animation.glb", "t1", 4);
  ASSERT_EQ(got.size(), expected.size());
  double worst = 0;
  for (std::size_t i = 0; i < got.size(); ++i) worst = std::max(worst, glm::length(got[i] - expected[i]));
  EXPECT_LT(worst, 1e-5);
  const std::vector<glm::dvec3> base = core::read_morph_frame_positions(dir / "animation.glb", "t1", 0);
  double moved = 0;
  for (std::size_t i = 0; i < got.size(); ++i) moved = std::max(moved, glm::length(got[i] - base[i]));
  EXPECT_GT(moved, 0.1);  // the target really moves the teapot
}

// The DFFD walk (seed Fig. 6.10): the bunny's mesh is split where a bar passes, so its vertex count changes from
// frame to frame. The recording still writes every frame (byte-identical across ranges), and animation.glb holds one
// child node per run of frames with one topology, switched by STEP scale keys, each posing exactly as the CPU
// reference on its frames.
TEST(Record, TopologyChangingWalkRecordsEveryFrameAndSegmentsTheGlb) {
  const core::Scene scene = load_scene("dffd_walk_bars.jsonl");
  const fs::path full = fresh_dir("dffd_full"), part = fresh_dir("dffd_part");
  const editor::RecordResult a = editor::record_frames(scene, options(full, 40, 45));
  const editor::RecordResult b = editor::record_frames(scene, options(part, 43, 45));
  EXPECT_EQ(a.frames_written, 6);
  EXPECT_EQ(b.frames_written, 3);
  for (int f = 43; f <= 45; ++f) {
    const std::string name = editor::frame_file_name(f, "png");
    EXPECT_TRUE(bytes(full / name) == bytes(part / name)) << name << " differs between ranges 40-45 and 43-45";
  }
  std::set<std::size_t> vertex_counts;
  for (int f = 40; f <= 45; ++f)
    vertex_counts.insert(
        core::scene_at_time(scene, scene.timeline.time_of_frame(f)).find("walker")->world_mesh->vertex_count());
  ASSERT_GT(vertex_counts.size(), 1u) << "frames 40-45 no longer change the walker's topology: pick other frames";

  const core::MorphAnimationInfo info = core::read_morph_animation_info(full / "animation.glb");
  int segments = 0, covered = 0;
  for (const auto& m : info.meshes) {
    if (m.name.rfind("walker/frames_", 0) != 0) continue;
    ++segments;
    const int first = std::stoi(m.name.substr(14, 4)), last = std::stoi(m.name.substr(19, 4));
    ASSERT_LE(first, last) << m.name;
    for (int f = first; f <= last; ++f, ++covered) {
      const core::Scene posed = core::scene_at_time(scene, scene.timeline.time_of_frame(f));
      const auto& expected = posed.find("walker")->world_mesh->positions;
      const auto got = core::read_morph_frame_positions(full / "animation.glb", m.name, f - first);
      ASSERT_EQ(got.size(), expected.size()) << m.name << " frame " << f;
      double worst = 0;
      for (std::size_t i = 0; i < got.size(); ++i) worst = std::max(worst, glm::length(got[i] - expected[i]));
      EXPECT_LT(worst, 1e-5) << m.name << " frame " << f;
    }
  }
  EXPECT_GE(segments, 2);
  EXPECT_EQ(covered, 6) << "every recorded frame belongs to exactly one segment";
  EXPECT_EQ(info.scale_channels, segments);
  EXPECT_EQ(info.interpolation, "STEP");
}

TEST(Record, ExrFramesAreHalfLinearAndReadBack) {
  const core::Scene scene = load_scene("record_anim.jsonl");
  const fs::path dir = fresh_dir("exr");
  editor::RecordOptions o = options(dir, 2, 3);
  o.format = "exr";
  o.width = 96;
  o.height = 64;
  o.glb = false;
  const editor::RecordResult r = editor::record_frames(scene, o);
  ASSERT_EQ(r.frames_written, 2);
  o.format = "png";
  editor::record_frames(scene, o);
  namespace OIIO = OIIO_NAMESPACE;
  auto in = OIIO::ImageInput::open((dir / "frame_0002.exr").string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec spec = in->spec();
  EXPECT_EQ(spec.width, 96);
  EXPECT_EQ(spec.height, 64);
  EXPECT_EQ(spec.nchannels, 4);
  EXPECT_EQ(spec.format, OIIO::TypeDesc::HALF);
  std::vector<float> px(static_cast<std::size_t>(96) * 64 * 4);
  ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, px.data()));
  in->close();
  // Linear: the PNG's sRGB values decoded (half precision ≈ 1e-3 relative).
  const core::ImageRgba8 png = core::read_image_rgba8(dir / "frame_0002.png");
  ASSERT_EQ(png.rgba.size(), px.size());
  double worst = 0;
  for (std::size_t i = 0; i < px.size(); ++i) {
    const double v = png.rgba[i] / 255.0;
    const double lin = i % 4 == 3 ? v : (v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
    worst = std::max(worst, std::abs(px[i] - lin));
  }
  EXPECT_LT(worst, 2e-3);
  // EXR frames carry no time stamp either: frame 3 alone is the same file.
  const fs::path alone = fresh_dir("exr_alone");
  editor::RecordOptions o3 = options(alone, 3, 3);
  o3.format = "exr";
  o3.width = 96;
  o3.height = 64;
  editor::record_frames(scene, o3);
  EXPECT_TRUE(bytes(alone / "frame_0003.exr") == bytes(dir / "frame_0003.exr")) << "frame_0003.exr differs";
}

TEST(Record, BadRequestsThrowAndWriteNothing) {
  const core::Scene scene = load_scene("record_anim.jsonl");
  const fs::path dir = fresh_dir("bad");
  EXPECT_THROW(editor::Recorder(scene, options(dir, 10, 20)), std::invalid_argument);  // past frame_end 12
  EXPECT_THROW(editor::Recorder(scene, options(dir, 0, 3)), std::invalid_argument);    // before frame_start 1
  EXPECT_THROW(editor::Recorder(scene, options(dir, 5, 4)), std::invalid_argument);
  editor::RecordOptions o = options(dir, 1, 2);
  o.format = "tiff";
  EXPECT_THROW(editor::Recorder(scene, o), std::invalid_argument);
  o = options(dir, 1, 2);
  o.width = 100;  // height missing
  EXPECT_THROW(editor::Recorder(scene, o), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir));

  // The bad log stops at the anim.record line with the field named.
  core::Scene bad;
  editor::History bad_history(bad);
  const editor::ReplayResult r = editor::replay_lines(bad_history, log_path("bad_record_range.jsonl"));
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.failed_line, 3);
  EXPECT_NE(r.error.find("field 'frames'"), std::string::npos) << r.error;
  EXPECT_EQ(bad_history.applied(), 2u);

  // replay --frames outside the timeline: exit code 2 and no output folder at all.
  const editor::ReplayOptions ro = replay_frames("record_anim.jsonl", "bad_replay", 10, 13);
  EXPECT_EQ(editor::run_replay(ro), 2);
  EXPECT_FALSE(fs::exists(ro.out_dir));
  EXPECT_EQ(editor::parse_frame_range("3-5"), std::make_pair(3, 5));
  EXPECT_EQ(editor::parse_frame_range("7"), std::make_pair(7, 7));
  EXPECT_FALSE(editor::parse_frame_range("5-3"));
  EXPECT_FALSE(editor::parse_frame_range("-3"));
  EXPECT_FALSE(editor::parse_frame_range("a-b"));
}

// PATH replaced for the scope of a test (restored on exit).
class ScopedPath {
 public:
  explicit ScopedPath(const std::string& path) : old_(std::getenv("PATH") ? std::getenv("PATH") : "") {
    ::setenv("PATH", path.c_str(), 1);
  }
  ~ScopedPath() { ::setenv("PATH", old_.c_str(), 1); }

 private:
  std::string old_;
};

void write_script(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
  fs::permissions(p, fs::perms::owner_all);
}

TEST(Record, Mp4ThroughFfmpegOrANote) {
  const core::Scene scene = load_scene("record_anim.jsonl");
  editor::RecordOptions o = options(fresh_dir("mp4"), 1, 3);
  o.mp4 = true;
  o.glb = false;
  // Whatever this machine has: an MP4 when ffmpeg is on PATH, else the note.
  const editor::RecordResult r = editor::record_frames(scene, o);
  if (r.mp4.empty()) {
    EXPECT_EQ(r.mp4_note, "ffmpeg not found on PATH");
  } else {
    EXPECT_GT(fs::file_size(r.mp4), 0u);
    EXPECT_TRUE(r.mp4_note.empty()) << r.mp4_note;
  }
  // No ffmpeg on PATH.
  const fs::path bin = fresh_dir("mp4_bin");
  {
    ScopedPath path(bin.string());
    o.out_dir = fresh_dir("mp4_none");
    const editor::RecordResult none = editor::record_frames(scene, o);
    EXPECT_TRUE(none.mp4.empty());
    EXPECT_EQ(none.mp4_note, "ffmpeg not found on PATH");
    EXPECT_FALSE(fs::exists(o.out_dir / "animation.mp4"));
  }
  // A stand-in ffmpeg that records its arguments and writes the output file: the call is the documented one.
  const fs::path args = bin / "args.txt";
  write_script(bin / "ffmpeg", "#!/bin/sh\nprintf '%s\\n' \"$@\" > '" + args.string() +
                                   "'\nfor a; do last=\"$a\"; done\nprintf 'mp4' > \"$last\"\n");
  {
    ScopedPath path(bin.string() + ":/usr/bin:/bin");
    o.out_dir = fresh_dir("mp4 fake");  // a space in the folder: no shell quoting involved
    o.frame_first = 2;
    const editor::RecordResult fake = editor::record_frames(scene, o);
    EXPECT_EQ(fake.mp4, (o.out_dir / "animation.mp4").string()) << fake.mp4_note;
    const std::string a = bytes(args);
    for (const char* part : {"-framerate\n24\n", "-start_number\n2\n", "frame_%04d.png\n", "-c:v\nlibx264\n",
                             "-pix_fmt\nyuv420p\n", "-y\n"})
      EXPECT_NE(a.find(part), std::string::npos) << part << " missing in:\n" << a;
    EXPECT_NE(a.find((o.out_dir / "frame_").string()), std::string::npos) << a;
  }
  // A failing ffmpeg: its error text is reported and no MP4 is left.
  write_script(bin / "ffmpeg", "#!/bin/sh\necho \"Unknown encoder 'libx264'\" >&2\nexit 1\n");
  {
    ScopedPath path(bin.string() + ":/usr/bin:/bin");
    o.out_dir = fresh_dir("mp4_fail");
    const editor::RecordResult fail = editor::record_frames(scene, o);
    EXPECT_TRUE(fail.mp4.empty());
    EXPECT_NE(fail.mp4_note.find("exit 1"), std::string::npos) << fail.mp4_note;
    EXPECT_NE(fail.mp4_note.find("Unknown encoder 'libx264'"), std::string::npos) << fail.mp4_note;
    EXPECT_FALSE(fs::exists(o.out_dir / "animation.mp4"));
    EXPECT_FALSE(fs::exists(o.out_dir / "animation.mp4.log"));
  }
}

TEST(Record, CancelAfterTwoFramesKeepsThemAndWritesNoGlb) {
  const core::Scene scene = load_scene("record_anim.jsonl");
  const fs::path dir = fresh_dir("cancel");
  editor::RecordOptions o = options(dir, 1, 12);
  o.mp4 = true;
  editor::Recorder recorder(scene, o);
  EXPECT_EQ(recorder.frames_total(), 12);
  EXPECT_LT(recorder.seconds_left(), 0);
  EXPECT_TRUE(recorder.step());
  EXPECT_TRUE(recorder.step());
  EXPECT_EQ(recorder.current_frame(), 3);
  EXPECT_GE(recorder.seconds_left(), 0);
  recorder.cancel();
  EXPECT_FALSE(recorder.step());
  const editor::RecordResult r = recorder.finish();
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(r.frames_written, 2);
  EXPECT_TRUE(r.glb.empty());
  EXPECT_TRUE(r.mp4.empty());
  EXPECT_EQ(files_in(dir), (std::vector<std::string>{"frame_0001.png", "frame_0002.png"}));
  const nlohmann::json j = r.to_json();
  EXPECT_TRUE(j.at("cancelled").get<bool>());
  EXPECT_TRUE(j.at("glb").is_null());
  // record_frames' progress callback cancels the same way.
  const fs::path dir2 = fresh_dir("cancel_cb");
  const editor::RecordResult r2 =
      editor::record_frames(scene, options(dir2, 1, 12), [](int done, int total) { return done < 2 && total == 12; });
  EXPECT_TRUE(r2.cancelled);
  EXPECT_EQ(files_in(dir2), (std::vector<std::string>{"frame_0001.png", "frame_0002.png"}));
}

// The editor records with its window's context current: the recorder then draws with that context into its own
// target, restores the caller's framebuffer binding and viewport, and writes the same bytes as with a private one.
TEST(Record, CurrentContextIsUsedAndItsStateRestored) {
  const core::Scene scene = load_scene("record_anim.jsonl");
  const fs::path own = fresh_dir("ctx_own"), shared = fresh_dir("ctx_shared");
  editor::record_frames(scene, options(own, 3, 4));
  gpu::HeadlessContext context;
  gpu::OffscreenTarget callers(64, 48, 1);
  callers.bind();
  GLint fbo_before = 0, viewport_before[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo_before);
  glGetIntegerv(GL_VIEWPORT, viewport_before);
  {
    editor::Recorder recorder(scene, options(shared, 3, 4));
    while (recorder.step()) {
      GLint fbo = 0, viewport[4] = {0, 0, 0, 0};
      glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
      glGetIntegerv(GL_VIEWPORT, viewport);
      EXPECT_EQ(fbo, fbo_before);
      EXPECT_EQ(viewport[2], viewport_before[2]);
      EXPECT_EQ(viewport[3], viewport_before[3]);
    }
    recorder.finish();
  }
  EXPECT_EQ(eglGetCurrentContext() != EGL_NO_CONTEXT, true);  // the caller's context is still current
  for (int f = 3; f <= 4; ++f) {
    const std::string name = editor::frame_file_name(f, "png");
    EXPECT_TRUE(bytes(own / name) == bytes(shared / name)) << name << " differs between contexts";
  }
}

nlohmann::json read_report(const fs::path& dir) {
  std::ifstream in(dir / "report.json");
  EXPECT_TRUE(in.good());
  return nlohmann::json::parse(in);
}

TEST(Record, ReplayFramesRendersTheRangeLikeTheRecorder) {
  const editor::ReplayOptions ro = replay_frames("record_anim.jsonl", "replay_frames", 5, 7);
  ASSERT_EQ(editor::run_replay(ro), 0);
  for (int f = 5; f <= 7; ++f) EXPECT_TRUE(fs::exists(ro.out_dir / editor::frame_file_name(f, "png"))) << f;
  EXPECT_FALSE(fs::exists(ro.out_dir / "frame_0004.png"));
  EXPECT_FALSE(fs::exists(ro.out_dir / "animation.mp4"));
  EXPECT_EQ(core::read_morph_animation_info(ro.out_dir / "animation.glb").keyframes, 3);
  const nlohmann::json report = read_report(ro.out_dir);
  EXPECT_EQ(report.at("record").at("frames_written"), 3);
  EXPECT_TRUE(report.contains("final_png"));  // the existing outputs stay
  // The same bytes as a direct recording of frame 6.
  const core::Scene scene = load_scene("record_anim.jsonl");
  const fs::path direct = fresh_dir("replay_frames_direct");
  editor::RecordOptions o = options(direct, 6, 6);
  editor::record_frames(scene, o);
  EXPECT_TRUE(bytes(direct / "frame_0006.png") == bytes(ro.out_dir / "frame_0006.png")) << "frame_0006.png differs";
}

TEST(Record, ReplayRecordsTheLogsAnimRecordLinesFromTheSceneAtThatLine) {
  editor::ReplayOptions ro;
  ro.log = log_path("record_command.jsonl");
  ro.out_dir = fresh_dir("replay_command");
  ro.render = false;
  ASSERT_EQ(editor::run_replay(ro), 0);
  const nlohmann::json report = read_report(ro.out_dir);
  const nlohmann::json& rec = report.at("record");
  EXPECT_EQ(rec.at("frames_written"), 3);
  EXPECT_EQ(rec.at("frame_first"), 2);
  EXPECT_EQ(rec.at("line"), 8);
  EXPECT_TRUE(rec.at("mp4").is_null());  // "mp4": false in the line
  // Recorded before line 9 stopped the teapot: it still moves between frames 2 and 4.
  EXPECT_TRUE(bytes(ro.out_dir / "frame_0002.png") != bytes(ro.out_dir / "frame_0004.png"));
  EXPECT_EQ(core::read_morph_animation_info(ro.out_dir / "animation.glb").meshes.at(1).targets, 2);
  EXPECT_FALSE(fs::exists(ro.out_dir / "record_command_frames"));  // the editor's folder is not used headless
}

}  // namespace

// A tile layer's metamorphosis and offset (ddm.animate) record into animation.glb as the node "pot/thorns" with one
// morph target per following frame, each the CPU reference (scene_at_time) of its frame.
TEST(Record, TileLayerAnimationRecordsIntoTheGlb) {
  const core::Scene scene = load_scene("ddm_morph_walk.jsonl");
  const fs::path dir = fresh_dir("ddm");
  const editor::RecordResult r = editor::record_frames(scene, options(dir, 1, 4));
  const core::MorphAnimationInfo info = core::read_morph_animation_info(dir / "animation.glb");
  ASSERT_EQ(info.meshes.size(), 2u);
  EXPECT_EQ(info.meshes[0].name, "pot");
  EXPECT_EQ(info.meshes[0].targets, 0);
  EXPECT_EQ(info.meshes[1].name, "pot/thorns");
  EXPECT_EQ(info.meshes[1].targets, 3);
  const core::Scene posed = core::scene_at_time(scene, scene.timeline.time_of_frame(4));
  const core::SceneObject& pot = *posed.find("pot");
  const core::TriMesh expected = core::transformed(*pot.ddm_layers.at(0)->mesh, pot.transform);
  const std::vector<glm::dvec3> got = core::read_morph_frame_positions(dir / "animation.glb", "pot/thorns", 3);
  ASSERT_EQ(got.size(), expected.vertex_count());
  double worst = 0, moved = 0;
  const std::vector<glm::dvec3> first = core::read_morph_frame_positions(dir / "animation.glb", "pot/thorns", 0);
  for (std::size_t i = 0; i < got.size(); ++i) {
    worst = std::max(worst, glm::length(got[i] - expected.positions[i]));
    moved = std::max(moved, glm::length(got[i] - first[i]));
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(moved, 0.01);  // the thorns walk round the pot and start to open
  EXPECT_EQ(r.frames_written, 4);
}
