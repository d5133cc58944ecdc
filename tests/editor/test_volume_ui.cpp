// The editor's volumes without a window (editor/volume_ui.h): a real MRI (assets/data, fetched by
// scripts/fetch_assets.sh) prepared on a worker thread with progress, then one volume.load; a second load refused
// while one runs; a cancelled and a truncated load leave the scene untouched and say so; live silhouettes extracted on
// a worker for the current view, the stale ones drawn until the new ones arrive; an export of the view's silhouettes
// (camera.set first) and of the iso-surface. And headless rendering (editor/replay/render_scene.h through `replay`): a
// volume and its silhouettes in final.png, extracted again for the render camera when the stored ones are for another
// view.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/commands/volume_load.h"
#include "core/image/image_io.h"
#include "core/volume/prepared_volume.h"
#include "editor/volume_ui.h"
#include "session_test_util.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

fs::path mri_file() { return fs::path(TRISPLINE_SOURCE_DIR) / "assets" / "data" / "KmeansTest_T1UCharRaw.nii.gz"; }

// Session tests with a fresh singleton cache (every load preprocesses) and no prepared volume kept in memory.
class VolumeUiTest : public test::StateDirTest {
 protected:
  void SetUp() override {
    StateDirTest::SetUp();
    core::clear_prepared_volumes();
  }
  void TearDown() override { StateDirTest::TearDown(); }
  // Deferred work runs at once.
  static editor::VolumeUi::Defer now() {
    return [](std::string, std::function<void()> work) { work(); };
  }
  // Polls finish_load() until the load is over; the name it returned (or "") and the highest progress seen.
  static std::string wait_load(editor::VolumeUi& ui, double* max_progress = nullptr) {
    std::string name;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (ui.loading() && std::chrono::steady_clock::now() < end) {
      if (max_progress) *max_progress = std::max(*max_progress, ui.load_progress());
      name = ui.finish_load();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    EXPECT_FALSE(ui.loading()) << "the load did not end in 2 minutes";
    return name;
  }
  static void wait_extraction(editor::VolumeUi& ui, const core::Scene& scene, const core::Camera& view) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    do {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      ui.update(scene, view);
    } while (ui.extracting() && std::chrono::steady_clock::now() < end);
    ASSERT_FALSE(ui.extracting());
  }
  static nlohmann::json torus_lines(const std::string& style = "plain") {
    return nlohmann::json::array(
        {{{"cmd", "volume.load"}, {"analytic", "torus"}, {"name", "torus"}, {"iso", 0.0}},
         {{"cmd", "volume.silhouettes"}, {"object", "torus"}, {"style", style}, {"hidden", "remove"}}});
  }
  static core::Camera view_from(const glm::dvec3& eye) {
    core::Camera c;
    c.eye = eye;
    c.target = {0.0, 0.0, 0.0};
    c.up = {0.0, 0.0, 1.0};
    c.fov_deg = 40.0;
    c.viewport = {320, 240};
    return c;
  }
};

TEST_F(VolumeUiTest, LoadPreparesOnAWorkerThenRunsVolumeLoad) {
  ASSERT_TRUE(fs::exists(mri_file())) << mri_file() << " is missing (scripts/fetch_assets.sh fetches it)";
  editor::EditorSession session(messages_);
  session.start(false);
  editor::VolumeUi ui(session, messages_, now());
  ASSERT_TRUE(ui.start_load(mri_file()));
  EXPECT_TRUE(ui.loading());
  EXPECT_FALSE(ui.start_load(mri_file())) << "one load at a time";
  EXPECT_TRUE(logged("a volume is loading already"));
  double progress = 0.0;
  const std::string name = wait_load(ui, &progress);
  EXPECT_EQ(name, "KmeansTest_T1UCharRaw");
  EXPECT_GT(progress, 0.5) << "the singleton table reported its progress";
  const core::VolumeObject* v = session.scene().find_volume(name);
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->spline->dims(), (std::array<int, 3>{128, 128, 62}));
  ASSERT_EQ(session.history().applied(), 1u);
  EXPECT_EQ(session.history().at(0).id(), "volume.load");
  EXPECT_LT(session.last_ms(), 100.0) << "volume.load found the prepared volume in the session cache";
  // A second file of the same name gets a unique one.
  ASSERT_TRUE(ui.start_load(mri_file()));
  EXPECT_EQ(wait_load(ui), "KmeansTest_T1UCharRaw.001");
}

TEST_F(VolumeUiTest, CancelledAndRefusedLoadsLeaveTheSceneUntouched) {
  ASSERT_TRUE(fs::exists(mri_file())) << mri_file() << " is missing (scripts/fetch_assets.sh fetches it)";
  editor::EditorSession session(messages_);
  session.start(false);
  editor::VolumeUi ui(session, messages_, now());
  ASSERT_TRUE(ui.start_load(mri_file()));
  ui.cancel_load();
  EXPECT_EQ(wait_load(ui), "");
  EXPECT_TRUE(logged("Loading KmeansTest_T1UCharRaw.nii.gz cancelled: the scene is unchanged"));
  // A truncated gzip'd NIfTI.
  const fs::path bad = dir_ / "truncated.nii.gz";
  {
    std::ifstream in(mri_file(), std::ios::binary);
    std::string head(3000, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    std::ofstream(bad, std::ios::binary).write(head.data(), std::streamsize(head.size()));
  }
  ASSERT_TRUE(ui.start_load(bad));
  EXPECT_EQ(wait_load(ui), "");
  EXPECT_TRUE(logged("cannot load truncated.nii.gz: "));
  EXPECT_TRUE(logged("(the scene is unchanged)"));
  // Not a volume at all.
  ASSERT_TRUE(ui.start_load(dir_ / "missing.nii"));
  EXPECT_EQ(wait_load(ui), "");
  EXPECT_TRUE(session.scene().volumes().empty());
  EXPECT_EQ(session.history().applied(), 0u);
}

TEST_F(VolumeUiTest, LiveSilhouettesFollowTheViewOnAWorker) {
  editor::EditorSession session(messages_);
  session.start(false);
  for (const auto& line : torus_lines()) ASSERT_TRUE(session.execute(line));
  editor::VolumeUi ui(session, messages_, now());
  const core::Camera a = view_from({0.0, -110.0, 70.0});
  ui.update(session.scene(), a);
  EXPECT_TRUE(ui.extracting()) << "the scene camera is another view: extracted for this one";
  EXPECT_TRUE(ui.busy());
  wait_extraction(ui, session.scene(), a);
  const ui::VolumeLiveInfo info = ui.live_info("torus");
  EXPECT_TRUE(info.current);
  EXPECT_GT(info.points, 50u);
  EXPECT_GT(ui.last_extract_ms(), 0.0);
  gpu::ViewOptions o;
  ui.decorate(o);
  ASSERT_EQ(o.overlays.volumes_in_place.size(), 1u);
  const auto first = o.overlays.volumes_in_place[0].silhouettes;
  ASSERT_NE(first, nullptr);
  const core::VolumeObject& v = *session.scene().find_volume("torus");
  // The live view's extraction: a run of views at the screen's density, hidden lines removed (hidden cells seed
  // nothing) — the same as a sequence of its own over the same views.
  core::SilhouetteParams live;
  live.seed_hidden = v.silhouette.hidden != "remove";
  EXPECT_FALSE(live.seed_hidden);
  EXPECT_GT(v.screen_silhouette_view(a).pixel_size, 0.0);
  core::SilhouetteSequence sequence(v.spline, v.table);
  const core::SilhouetteResult direct = sequence.next(v.iso, v.screen_silhouette_view(a), live);
  EXPECT_EQ(first->points, direct.points) << "the same extraction as a sequence's, for this view";
  EXPECT_EQ(first->polylines.size(), direct.polylines.size());
  // Orbit: a new extraction starts; the previous silhouettes are drawn until it is done.
  const core::Camera b = view_from({80.0, -80.0, 70.0});
  ui.update(session.scene(), b);
  EXPECT_TRUE(ui.extracting());
  EXPECT_FALSE(ui.live_info("torus").current);
  gpu::ViewOptions stale;
  ui.decorate(stale);
  ASSERT_EQ(stale.overlays.volumes_in_place.size(), 1u);
  EXPECT_EQ(stale.overlays.volumes_in_place[0].silhouettes, first);
  wait_extraction(ui, session.scene(), b);
  EXPECT_TRUE(ui.live_info("torus").current);
  gpu::ViewOptions fresh;
  ui.decorate(fresh);
  EXPECT_NE(fresh.overlays.volumes_in_place.at(0).silhouettes, first);
  // Seeded from view a's curves, as the sequence's second view is.
  const core::SilhouetteResult then = sequence.next(v.iso, v.screen_silhouette_view(b), live);
  EXPECT_GT(then.traced_from_previous, 0u);
  EXPECT_EQ(fresh.overlays.volumes_in_place.at(0).silhouettes->points, then.points);
  EXPECT_EQ(fresh.overlays.volumes_in_place.at(0).silhouettes->traced_from_previous, then.traced_from_previous);
  // The same view again: nothing to do. Silhouettes off: nothing drawn, nothing extracted.
  ui.update(session.scene(), b);
  EXPECT_FALSE(ui.extracting());
  ASSERT_TRUE(session.execute({{"cmd", "volume.silhouettes"}, {"object", "torus"}, {"enabled", false}}));
  ui.update(session.scene(), a);
  EXPECT_FALSE(ui.extracting());
  gpu::ViewOptions off;
  ui.decorate(off);
  EXPECT_TRUE(off.overlays.volumes_in_place.empty());
}

TEST_F(VolumeUiTest, ExportWritesTheViewsSilhouettesAndTheIsoSurface) {
  editor::EditorSession session(messages_);
  session.start(false);
  for (const auto& line : torus_lines()) ASSERT_TRUE(session.execute(line));
  editor::VolumeUi ui(session, messages_, now());
  const core::Camera view = view_from({60.0, -100.0, 50.0});
  ASSERT_FALSE(core::same_view(session.scene().camera, view));
  ASSERT_TRUE(ui.export_volume("torus", ui::kVolumeExports[0], dir_ / "torus.svg", view));
  const std::size_t n = session.history().applied();
  ASSERT_GE(n, 2u);
  EXPECT_EQ(session.history().at(n - 1).id(), "volume.export");  // one step: the view travels in its camera field
  EXPECT_NE(session.history().at(n - 2).id(), "camera.set");
  // The user chose the file in a dialog: its folder is the output folder and the logged line names the file in it,
  // so a replay of the session writes under its own output folder, never at this absolute path.
  EXPECT_EQ(session.history().at(n - 1).to_json()["path"], "torus.svg");
  EXPECT_FALSE(core::same_view(session.scene().camera, view)) << "the scene camera is left alone";
  std::ifstream svg(dir_ / "torus.svg");
  std::stringstream text;
  text << svg.rdbuf();
  EXPECT_NE(text.str().find("<path"), std::string::npos);
  // The stored silhouettes are now this view's: the live view uses them without extracting.
  ui.update(session.scene(), view);
  EXPECT_FALSE(ui.extracting());
  EXPECT_TRUE(ui.live_info("torus").current);
  // The iso-surface as OBJ, its extension added; no camera.set for a mesh.
  const ui::VolumeExportKind& obj = ui::kVolumeExports[3];
  ASSERT_STREQ(obj.extension, ".obj");
  ASSERT_TRUE(ui.export_volume("torus", obj, dir_ / "torus_iso", view_from({0.0, -120.0, 10.0})));
  EXPECT_TRUE(fs::exists(dir_ / "torus_iso.obj"));
  EXPECT_EQ(session.history().applied(), n + 1);
  // A refused export (its folder is a file) says why and leaves the history.
  EXPECT_FALSE(ui.export_volume("torus", ui::kVolumeExports[0], dir_ / "torus.svg" / "inside.svg", view));
  EXPECT_EQ(session.history().applied(), n + 1);
  EXPECT_TRUE(logged("volume.export: "));
}

// final.png of a torus volume and its silhouettes: surface pixels and black line pixels; the report's render timings
// name the volume pass. `before_camera`: volume.silhouettes runs before camera.set, so the stored silhouettes are for
// the default camera and the render extracts them again for its own.
nlohmann::json replay_torus(const fs::path& dir, bool before_camera, core::ImageRgba8* image) {
  const nlohmann::json camera = {{"cmd", "camera.set"}, {"eye", {0.0, -110.0, 70.0}},
                                 {"target", {0, 0, 0}}, {"up", {0, 0, 1}},
                                 {"fov_deg", 40.0},     {"viewport", {160, 120}}};
  nlohmann::json lines =
      nlohmann::json::array({{{"cmd", "volume.load"}, {"analytic", "torus"}, {"name", "torus"}, {"iso", 0.0}}});
  const nlohmann::json sil = {{"cmd", "volume.silhouettes"}, {"object", "torus"}, {"style", "plain"}};
  lines.push_back(before_camera ? sil : camera);
  lines.push_back(before_camera ? camera : sil);
  fs::create_directories(dir);
  {
    std::ofstream log(dir / "torus.jsonl");
    for (const auto& l : lines) log << l.dump() << "\n";
  }
  editor::ReplayOptions opt;
  opt.log = dir / "torus.jsonl";
  opt.out_dir = dir / "out";
  EXPECT_EQ(editor::run_replay(opt), 0);
  *image = core::read_image_rgba8(dir / "out" / "final.png");
  std::ifstream in(dir / "out" / "report.json");
  return nlohmann::json::parse(in);
}

TEST_F(VolumeUiTest, ReplayDrawsTheVolumeAndItsSilhouettes) {
  core::ImageRgba8 img;
  const nlohmann::json report = replay_torus(dir_ / "after", false, &img);
  ASSERT_EQ(img.width, 160);
  const nlohmann::json& render = report.at("timings").at("render");
  EXPECT_EQ(render.at("volumes").get<int>(), 1);
  EXPECT_GT(render.at("silhouette_points").get<int>(), 50);
  EXPECT_EQ(render.at("silhouette_ms").get<double>(), 0.0) << "the stored silhouettes are the render camera's";
  EXPECT_TRUE(render.at("volume_ms").is_number());
  std::size_t bright = 0, black = 0;
  for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4) {
    const int r = img.rgba[i], g = img.rgba[i + 1], b = img.rgba[i + 2];
    bright += r > 150 && g > 140 && b > 110;  // the lit bone-white surface
    black += r < 30 && g < 30 && b < 30;      // plain strokes (the background is a lighter grey)
  }
  EXPECT_GT(bright, 160u * 120u / 20);
  EXPECT_GT(black, 100u);
  // The stored silhouettes are for another camera: extracted again, and the same image.
  core::ImageRgba8 again;
  const nlohmann::json other = replay_torus(dir_ / "before", true, &again);
  EXPECT_GT(other.at("timings").at("render").at("silhouette_ms").get<double>(), 0.0);
  EXPECT_EQ(again.rgba, img.rgba);
}

}  // namespace
