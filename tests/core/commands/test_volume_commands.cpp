// volume.load / volume.iso / volume.silhouettes / volume.render / volume.export (core/commands/volume_*.h): a volume is
// added, its iso-level set, silhouettes extracted for the scene camera and exported; undo restores the scene before
// each step; the same lines give the same silhouettes bit for bit; bad fields are named and change nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "core/commands/camera_set.h"
#include "core/commands/volume_export.h"
#include "core/commands/volume_iso.h"
#include "core/commands/volume_load.h"
#include "core/commands/volume_remove.h"
#include "core/commands/volume_render.h"
#include "core/commands/volume_silhouettes.h"
#include "core/scene/scene_export.h"
#include "core/volume/prepared_volume.h"

namespace trispline::core {
namespace {

using nlohmann::json;

template <class C>
CommandPtr parse(const std::string& line, const CommandContext& ctx = {}) {
  return C::parse(json::parse(line), ctx);
}

class VolumeCommands : public ::testing::Test {
 protected:
  // The suite shares the session's prepared volumes: each analytic volume is prepared once per
  // process (~5 s under ASan), as in an editor session; test_prepared_volume.cpp covers preparation and the session
  // cache.
  static void SetUpTestSuite() {
    suite_dir_ = std::filesystem::temp_directory_path() / ("trispline_volume_cmd_" + std::to_string(::getpid()));
    std::filesystem::create_directories(suite_dir_);
    clear_prepared_volumes();
  }
  static void TearDownTestSuite() {
    clear_prepared_volumes();
    std::filesystem::remove_all(suite_dir_);
  }
  // Each test writes under a folder of its own.
  void SetUp() override {
    dir_ = suite_dir_ / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // A torus volume seen obliquely from 160 mm away.
  Scene torus_scene() {
    Scene s;
    parse<CameraSetCommand>(R"({"cmd":"camera.set","eye":[0,-150,60],"target":[0,0,0],"up":[0,0,1],
                                "viewport":[320,240]})")
        ->redo(s);
    parse<VolumeLoadCommand>(R"({"cmd":"volume.load","analytic":"torus","name":"torus","iso":0})")->redo(s);
    return s;
  }
  // Outputs go under dir_ (a replay's --out).
  CommandContext out_ctx() const { return CommandContext{dir_, dir_}; }
  CommandPtr export_line(json line) const {
    line["cmd"] = "volume.export";
    return VolumeExportCommand::parse(line, out_ctx());
  }
  static inline std::filesystem::path suite_dir_;
  std::filesystem::path dir_;
};

TEST_F(VolumeCommands, LoadAddsAVolumeAndUndoRemovesIt) {
  Scene s;
  auto c = parse<VolumeLoadCommand>(R"({"cmd":"volume.load","analytic":"sphere"})");
  c->redo(s);
  ASSERT_EQ(s.volumes().size(), 1u);
  const VolumeObject& v = s.volumes()[0];
  EXPECT_EQ(v.name, "sphere");
  EXPECT_EQ(v.spline->order(), 4);
  EXPECT_EQ(c->stats()["dims"], json({96, 120, 77}));
  EXPECT_TRUE(s.bounds().valid());
  // The logged line keeps the level used (the default) and replays to the same volume.
  const json logged = c->to_json();
  EXPECT_TRUE(logged.contains("iso"));
  EXPECT_EQ(parse<VolumeLoadCommand>(logged.dump())->to_json(), logged);
  c->undo(s);
  EXPECT_TRUE(s.volumes().empty());
  c->redo(s);
  EXPECT_EQ(s.volumes().size(), 1u);
}

// A NIfTI head (RAS+) lies in the Y-up editor with its superior axis along +Y (anterior +Z, right −X): the world is
// the file's turned by that rotation, named in the report; "axes":"file" keeps the file's own world.
TEST_F(VolumeCommands, ANiftiHeadStandsUpUnlessTheFilesAxesAreAsked) {
  const std::string path =
      (std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/KmeansTest_T1UCharRaw.nii.gz").string();
  Scene up, file;
  auto a = VolumeLoadCommand::parse(json{{"cmd", "volume.load"}, {"path", path}, {"name", "up"}}, {});
  a->redo(up);
  auto b =
      VolumeLoadCommand::parse(json{{"cmd", "volume.load"}, {"path", path}, {"name", "file"}, {"axes", "file"}}, {});
  b->redo(file);
  EXPECT_EQ(a->stats()["axes"], "superior_up");
  EXPECT_EQ(a->stats()["frame"], "RAS");
  EXPECT_EQ(b->stats()["axes"], "file");
  EXPECT_EQ(a->to_json()["axes"], "superior_up") << "the log says which axes it used";
  const glm::dmat4& m_up = up.volumes()[0].spline->index_to_world();
  const glm::dmat4& m_file = file.volumes()[0].spline->index_to_world();
  const glm::dmat4 expected = superior_up_rotation("RAS") * m_file;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(m_up[c][r], expected[c][r], 1e-12);
  // RAS superior (world +z of the file) is +Y now; anterior (+y) is +Z; right (+x) is −X.
  const glm::dmat4 rot = superior_up_rotation("RAS");
  EXPECT_EQ(glm::dvec3(rot * glm::dvec4(0, 0, 1, 0)), glm::dvec3(0, 1, 0));
  EXPECT_EQ(glm::dvec3(rot * glm::dvec4(0, 1, 0, 0)), glm::dvec3(0, 0, 1));
  EXPECT_EQ(glm::dvec3(rot * glm::dvec4(1, 0, 0, 0)), glm::dvec3(-1, 0, 0));
  EXPECT_NEAR(glm::determinant(glm::dmat3(rot)), 1.0, 1e-15) << "a rotation: nothing mirrored";
  // DICOM's LPS: superior +Y as well, anterior (−P) +Z.
  const glm::dmat4 lps = superior_up_rotation("LPS");
  EXPECT_EQ(glm::dvec3(lps * glm::dvec4(0, 0, 1, 0)), glm::dvec3(0, 1, 0));
  EXPECT_EQ(glm::dvec3(lps * glm::dvec4(0, -1, 0, 0)), glm::dvec3(0, 0, 1));
  EXPECT_NEAR(glm::determinant(glm::dmat3(lps)), 1.0, 1e-15);
  // A file without a patient frame (an analytic volume, .inv3) keeps its axes.
  Scene analytic;
  auto c = parse<VolumeLoadCommand>(R"({"cmd":"volume.load","analytic":"sphere"})");
  c->redo(analytic);
  EXPECT_EQ(c->stats()["axes"], "file");
}

TEST_F(VolumeCommands, LoadRefusesBadInputAndChangesNothing) {
  Scene s;
  parse<VolumeLoadCommand>(R"({"cmd":"volume.load","analytic":"sphere","name":"a"})")->redo(s);
  auto expect_field = [&](const std::string& line, const std::string& field) {
    try {
      auto c = parse<VolumeLoadCommand>(line);
      c->redo(s);
      ADD_FAILURE() << "accepted " << line;
    } catch (const CommandError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
    }
    EXPECT_EQ(s.volumes().size(), 1u);
  };
  expect_field(R"({"cmd":"volume.load","analytic":"sphere","name":"a"})", "name");  // taken
  expect_field(R"({"cmd":"volume.load","analytic":"sphere","order":5})", "order");
  expect_field(R"({"cmd":"volume.load"})", "path");  // neither
  expect_field(R"({"cmd":"volume.load","analytic":"cube"})", "analytic");
  const auto missing = dir_ / "missing.nii.gz";
  expect_field(json({{"cmd", "volume.load"}, {"path", missing.string()}}).dump(), "path");
  const auto garbage = dir_ / "garbage.nii";
  std::ofstream(garbage) << "not a volume at all";
  expect_field(json({{"cmd", "volume.load"}, {"path", garbage.string()}}).dump(), "path");
}

TEST_F(VolumeCommands, IsoAndSilhouettesAreUndoableAndDeterministic) {
  Scene s = torus_scene();
  auto sil = parse<VolumeSilhouettesCommand>(R"({"cmd":"volume.silhouettes","object":"torus","hidden":"dashed"})");
  sil->redo(s);
  const VolumeObject& v = *s.find_volume("torus");
  ASSERT_TRUE(v.silhouettes);
  EXPECT_GT(v.silhouettes->points, 200u);
  EXPECT_LE(sil->stats()["max_value_residual"].get<double>(), 1e-6);
  EXPECT_LE(sil->stats()["max_dot_residual"].get<double>(), 1e-5);
  const auto first = v.silhouettes;

  auto iso = parse<VolumeIsoCommand>(R"({"cmd":"volume.iso","object":"torus","level":3})");
  iso->redo(s);
  const VolumeObject& w = *s.find_volume("torus");
  EXPECT_EQ(w.iso, 3.0);
  ASSERT_TRUE(w.silhouettes);
  EXPECT_NE(w.silhouettes, first);  // extracted again for the new level (a thinner torus: shorter curves)
  EXPECT_LT(w.silhouettes->length_mm, first->length_mm);
  iso->undo(s);
  EXPECT_EQ(s.find_volume("torus")->iso, 0.0);
  EXPECT_EQ(s.find_volume("torus")->silhouettes, first);
  sil->undo(s);
  EXPECT_FALSE(s.find_volume("torus")->silhouettes);
  EXPECT_FALSE(s.find_volume("torus")->silhouette.enabled);

  // The same lines on a fresh scene give the same polylines bit for bit.
  Scene t = torus_scene();
  parse<VolumeSilhouettesCommand>(sil->to_json().dump())->redo(t);
  const auto& a = first->polylines;
  const auto& b = t.find_volume("torus")->silhouettes->polylines;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].points, b[i].points);
    EXPECT_EQ(a[i].visible, b[i].visible);
  }
}

// Several iso-levels (seed Figs. 7.4–7.6, 7.12): the first is the surface, each further one gets its own silhouettes,
// style and colour; a line without levels keeps them; undo restores; the line round-trips; bad levels name "levels"
// or "level" and change nothing.
TEST_F(VolumeCommands, FurtherLevelsHaveTheirOwnSilhouettesStyleAndColour) {
  Scene s = torus_scene();
  parse<VolumeSilhouettesCommand>(R"({"cmd":"volume.silhouettes","object":"torus"})")->redo(s);
  const auto one_level = s.find_volume("torus")->silhouettes;
  auto iso = parse<VolumeIsoCommand>(
      R"({"cmd":"volume.iso","object":"torus","levels":[0,3,{"level":-2,"style":"width","color":[1,0,0]}]})");
  iso->redo(s);
  const VolumeObject& v = *s.find_volume("torus");
  EXPECT_EQ(v.iso, 0.0);
  ASSERT_EQ(v.more_levels.size(), 2u);
  EXPECT_EQ(v.more_levels[0].iso, 3.0);
  EXPECT_EQ(v.more_levels[0].style, "plain");
  EXPECT_EQ(v.more_levels[1].style, "width");
  EXPECT_EQ(v.more_levels[1].color, glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_NE(v.more_levels[0].color, v.more_levels[1].color);
  ASSERT_TRUE(v.silhouettes && v.more_levels[0].silhouettes && v.more_levels[1].silhouettes);
  // Each level's own curves: the first level's are those of the one-level volume, the thinner torus's shorter, the
  // fatter one's longer.
  EXPECT_EQ(v.silhouettes->points, one_level->points);
  EXPECT_LT(v.more_levels[0].silhouettes->length_mm, v.silhouettes->length_mm);
  EXPECT_GT(v.more_levels[1].silhouettes->length_mm, v.silhouettes->length_mm);
  EXPECT_EQ(iso->stats()["levels"], 3);
  EXPECT_EQ(iso->stats()["points_all_levels"].get<std::size_t>(),
            v.silhouettes->points + v.more_levels[0].silhouettes->points + v.more_levels[1].silhouettes->points);
  EXPECT_EQ(parse<VolumeIsoCommand>(iso->to_json().dump())->to_json(), iso->to_json());
  // A level alone keeps the further levels (extracted again).
  auto level_only = parse<VolumeIsoCommand>(R"({"cmd":"volume.iso","object":"torus","level":1})");
  level_only->redo(s);
  EXPECT_EQ(s.find_volume("torus")->more_levels.size(), 2u);
  level_only->undo(s);
  iso->undo(s);
  EXPECT_TRUE(s.find_volume("torus")->more_levels.empty());
  EXPECT_EQ(s.find_volume("torus")->silhouettes, one_level);
  // Refusals, named.
  auto field_of = [&](const char* line) {
    try {
      parse<VolumeIsoCommand>(line)->redo(s);
    } catch (const CommandError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(field_of(R"({"cmd":"volume.iso","object":"torus"})"), "level");
  EXPECT_EQ(field_of(R"({"cmd":"volume.iso","object":"torus","level":1,"levels":[2]})"), "level");
  EXPECT_EQ(field_of(R"({"cmd":"volume.iso","object":"torus","levels":[]})"), "levels");
  EXPECT_EQ(field_of(R"({"cmd":"volume.iso","object":"torus","levels":[0,1,2,3,4,5,6,7,8]})"), "levels");
  EXPECT_EQ(field_of(R"({"cmd":"volume.iso","object":"torus","levels":[0,{"level":1,"style":"neon"}]})"), "levels");
  EXPECT_EQ(field_of(R"({"cmd":"volume.iso","object":"torus","levels":[0,{"level":1,"color":[2,0,0]}]})"), "levels");
  EXPECT_EQ(field_of(R"({"cmd":"volume.iso","object":"torus","levels":[0,{"style":"plain"}]})"), "levels");
  EXPECT_EQ(field_of(R"({"cmd":"volume.iso","object":"torus","levels":[0,"x"]})"), "levels");
  EXPECT_EQ(field_of(R"({"cmd":"volume.iso","object":"torus","levels":[0,1e40]})"), "levels");
  EXPECT_TRUE(s.find_volume("torus")->more_levels.empty());
}

TEST_F(VolumeCommands, ErrorsNameTheFieldAndChangeNothing) {
  Scene s = torus_scene();
  auto expect_field = [&](CommandPtr c, const std::string& field) {
    try {
      c->redo(s);
      ADD_FAILURE() << "accepted " << c->to_json().dump();
    } catch (const CommandError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
    }
    EXPECT_EQ(s.find_volume("torus")->iso, 0.0);
  };
  expect_field(parse<VolumeIsoCommand>(R"({"cmd":"volume.iso","object":"nope","level":1})"), "object");
  EXPECT_THROW(parse<VolumeIsoCommand>(R"({"cmd":"volume.iso","object":"torus","level":"x"})"), CommandError);
  EXPECT_THROW(parse<VolumeSilhouettesCommand>(R"({"cmd":"volume.silhouettes","object":"torus","style":"neon"})"),
               CommandError);
  EXPECT_THROW(parse<VolumeSilhouettesCommand>(R"({"cmd":"volume.silhouettes","object":"torus","subdivision":9})"),
               CommandError);
  EXPECT_THROW(parse<VolumeExportCommand>(R"({"cmd":"volume.export","object":"torus","path":"a.png"})"), CommandError);
  EXPECT_THROW(parse<VolumeExportCommand>(R"({"cmd":"volume.export","object":"torus","what":"iso","path":"a.svg"})"),
               CommandError);
}

TEST_F(VolumeCommands, RenderSwitchesToDirectVolumeRenderingAndUndoRestores) {
  Scene s = torus_scene();
  const VolumeObject before = *s.find_volume("torus");
  EXPECT_EQ(before.render_mode, VolumeObject::RenderMode::iso);
  EXPECT_TRUE(before.transfer.points.empty());
  // dvr without a transfer function: the default ramp (an analytic volume is not in HU), from the iso-level up.
  auto c = parse<VolumeRenderCommand>(R"({"cmd":"volume.render","object":"torus","mode":"dvr"})");
  c->redo(s);
  const VolumeObject& v = *s.find_volume("torus");
  EXPECT_EQ(v.render_mode, VolumeObject::RenderMode::dvr);
  ASSERT_EQ(v.transfer.points.size(), 3u);
  EXPECT_EQ(v.transfer.points.front().value, 0.0);  // the iso-level
  EXPECT_EQ(v.transfer.points.front().rgba.w, 0.0);
  EXPECT_EQ(transfer_function_error(v.transfer), "");
  EXPECT_EQ(c->stats()["mode"], "dvr");
  EXPECT_EQ(c->stats()["points"], 3);
  EXPECT_EQ(v.dvr_step, 0.5);
  // A transfer function and step given, then the mode back to iso keeps them.
  auto t = parse<VolumeRenderCommand>(
      R"({"cmd":"volume.render","object":"torus","mode":"dvr","transfer":[[-1,0,0,0,0],[2,1,0.5,0,0.4]],"step":0.25})");
  t->redo(s);
  EXPECT_EQ(s.find_volume("torus")->transfer.points.size(), 2u);
  EXPECT_EQ(s.find_volume("torus")->dvr_step, 0.25);
  EXPECT_EQ(t->to_json()["transfer"][1], json::parse("[2.0,1.0,0.5,0.0,0.4]"));
  auto iso = parse<VolumeRenderCommand>(R"({"cmd":"volume.render","object":"torus","mode":"iso"})");
  iso->redo(s);
  EXPECT_EQ(s.find_volume("torus")->render_mode, VolumeObject::RenderMode::iso);
  EXPECT_EQ(s.find_volume("torus")->transfer.points.size(), 2u);
  iso->undo(s);
  t->undo(s);
  c->undo(s);
  EXPECT_EQ(s.find_volume("torus")->render_mode, VolumeObject::RenderMode::iso);
  EXPECT_TRUE(s.find_volume("torus")->transfer.points.empty());
  // The default for a CT (HU) is the CT preset.
  VolumeObject ct = before;
  ct.units = "HU";
  EXPECT_EQ(default_transfer_function(ct), ct_transfer_function());
  // Refusals name the field and change nothing.
  for (const char* bad :
       {R"({"cmd":"volume.render","object":"torus","mode":"dvr","transfer":[[0,1,1,1,1]]})",
        R"({"cmd":"volume.render","object":"torus","mode":"dvr","transfer":[[0,1,1,1,1],[0,1,1,1,1]]})",
        R"({"cmd":"volume.render","object":"torus","mode":"dvr","transfer":[[0,1,1,1,1],[1,2,1,1,1]]})",
        R"({"cmd":"volume.render","object":"torus","mode":"dvr","transfer":[[0,1,1,1],[1,1,1,1,1]]})",
        R"({"cmd":"volume.render","object":"torus","mode":"dvr","transfer":"ct"})"}) {
    try {
      parse<VolumeRenderCommand>(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const CommandError& e) {
      EXPECT_EQ(e.field(), "transfer") << e.what();
    }
  }
  EXPECT_THROW(parse<VolumeRenderCommand>(R"({"cmd":"volume.render","object":"torus","mode":"mip"})"), CommandError);
  EXPECT_THROW(parse<VolumeRenderCommand>(R"({"cmd":"volume.render","object":"torus","step":0})"), CommandError);
  try {
    parse<VolumeRenderCommand>(R"({"cmd":"volume.render","object":"nope","mode":"dvr"})")->redo(s);
    ADD_FAILURE() << "rendered a missing volume";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.field(), "object");
  }
  EXPECT_EQ(s.find_volume("torus")->render_mode, VolumeObject::RenderMode::iso);
}

TEST_F(VolumeCommands, ExportWritesSvgGlbAndIsoMeshAndSceneGlbHoldsThem) {
  Scene s = torus_scene();
  const auto svg = dir_ / "torus.svg", lines = dir_ / "torus_lines.glb";
  auto e1 = export_line({{"object", "torus"}, {"path", "torus.svg"}});
  e1->redo(s);
  std::stringstream text;
  text << std::ifstream(svg).rdbuf();
  EXPECT_NE(text.str().find("<path"), std::string::npos);
  EXPECT_GT(e1->stats()["points"].get<std::size_t>(), 100u);
  export_line({{"object", "torus"}, {"path", "torus_lines.glb"}})->redo(s);
  EXPECT_GT(std::filesystem::file_size(lines), 1000u);
  auto e3 = export_line({{"object", "torus"}, {"what", "iso"}, {"path", "torus.ply"}});
  e3->redo(s);
  EXPECT_GT(e3->stats()["triangles"].get<std::size_t>(), 1000u);
  ASSERT_TRUE(s.find_volume("torus")->iso_mesh);
  // scene.glb: the iso mesh always once extracted; silhouettes when enabled.
  auto names = [&] {
    std::vector<std::string> n;
    for (const auto& node : scene_export_nodes(s).nodes) n.push_back(node.name);
    return n;
  };
  EXPECT_EQ(names(), std::vector<std::string>{"torus/iso"});
  parse<VolumeSilhouettesCommand>(R"({"cmd":"volume.silhouettes","object":"torus"})")->redo(s);
  EXPECT_EQ(names(), (std::vector<std::string>{"torus/iso", "torus/silhouettes"}));
  e3->undo(s);
  EXPECT_FALSE(s.find_volume("torus")->iso_mesh);
}

TEST_F(VolumeCommands, RemoveAndUndoRestoreTheVolumeWhereItWas) {
  Scene s = torus_scene();
  parse<VolumeLoadCommand>(R"({"cmd":"volume.load","analytic":"sphere","name":"ball"})")->redo(s);
  parse<VolumeIsoCommand>(R"({"cmd":"volume.iso","object":"torus","level":2})")->redo(s);
  auto r = parse<VolumeRemoveCommand>(R"({"cmd":"volume.remove","object":"torus"})");
  r->redo(s);
  ASSERT_EQ(s.volumes().size(), 1u);
  EXPECT_EQ(s.volumes()[0].name, "ball");
  r->undo(s);
  ASSERT_EQ(s.volumes().size(), 2u);
  EXPECT_EQ(s.volumes()[0].name, "torus");  // back in its place, with its level
  EXPECT_EQ(s.volumes()[0].iso, 2.0);
  EXPECT_THROW(parse<VolumeRemoveCommand>(R"({"cmd":"volume.remove","object":"nope"})")->redo(s), CommandError);
  EXPECT_EQ(s.volumes().size(), 2u);
}

TEST_F(VolumeCommands, ExportTakesTheViewFromItsCameraField) {
  Scene s = torus_scene();
  const auto a = dir_ / "a.svg", b = dir_ / "b.svg";
  const json cam = {{"eye", {0, -150, 60}}, {"target", {0, 0, 0}}, {"up", {0, 0, 1}}, {"viewport", {320, 240}}};
  // The same view as the scene camera, given in the line: the same drawing.
  export_line({{"object", "torus"}, {"path", "a.svg"}})->redo(s);
  export_line({{"object", "torus"}, {"path", "b.svg"}, {"camera", cam}})->redo(s);
  std::stringstream ta, tb;
  ta << std::ifstream(a).rdbuf();
  tb << std::ifstream(b).rdbuf();
  EXPECT_EQ(ta.str(), tb.str());
  // Another view in the line: another drawing, and the scene camera is unchanged.
  json top = cam;
  top["eye"] = {0, 0, 200};
  top["up"] = {0, 1, 0};
  export_line({{"object", "torus"}, {"path", "b.svg"}, {"camera", top}})->redo(s);
  std::stringstream tc;
  tc << std::ifstream(b).rdbuf();
  EXPECT_NE(ta.str(), tc.str());
  EXPECT_EQ(s.camera.eye, glm::dvec3(0, -150, 60));
}

TEST_F(VolumeCommands, ExportStaysInsideTheOutputFolder) {
  Scene s = torus_scene();
  const std::filesystem::path out = dir_ / "out";
  std::filesystem::create_directories(out / "sub");
  std::filesystem::create_directories(dir_ / "outside");
  std::filesystem::create_directory_symlink(dir_ / "outside", out / "link");
  const CommandContext ctx{dir_ / "log", out};
  const auto refused = [&](const std::string& path) {
    try {
      VolumeExportCommand::parse(json{{"cmd", "volume.export"}, {"object", "torus"}, {"path", path}}, ctx);
      ADD_FAILURE() << "accepted " << path;
    } catch (const CommandError& e) {
      EXPECT_EQ(e.field(), "path") << e.what();
    }
  };
  const std::vector<std::string> bad_paths = {"../../x.svg",
                                              "a/b/c/../../../../x.ply",
                                              "/tmp/x.glb",
                                              (dir_ / "out/x.svg").string(),
                                              "link/x.svg",
                                              "link/../../x.svg",
                                              "sub",
                                              "..",
                                              ".",
                                              "x\nrm.svg",
                                              "../out2/x.svg"};
  for (const std::string& bad : bad_paths) refused(bad);
  // Nothing was written anywhere by the refusals.
  EXPECT_TRUE(std::filesystem::is_empty(dir_ / "outside"));
  // Inside: plain, in a subfolder, with a `..` that stays inside, and a new subfolder.
  for (const std::string good : {"x.svg", "sub/x.svg", "sub/../y.svg", "new/deeper/z.svg"}) {
    auto c = VolumeExportCommand::parse(json{{"cmd", "volume.export"}, {"object", "torus"}, {"path", good}}, ctx);
    c->redo(s);
    EXPECT_TRUE(std::filesystem::is_regular_file(out / good)) << good;
    EXPECT_EQ(c->to_json()["path"], good);  // the line keeps the relative path: a replay writes under its own --out
  }
  // A symlinked file that points outside is refused too (the link would carry the write out).
  std::filesystem::create_symlink(dir_ / "outside" / "victim.svg", out / "victim.svg");
  refused("victim.svg");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "outside" / "victim.svg"));
}

TEST_F(VolumeCommands, ExportOfAnIsoOutsideTheValuesNamesTheLevelAndWritesNothing) {
  Scene s = torus_scene();
  parse<VolumeIsoCommand>(R"({"cmd":"volume.iso","object":"torus","level":1e30})")->redo(s);
  try {
    export_line({{"object", "torus"}, {"what", "iso"}, {"path", "far.ply"}})->redo(s);
    ADD_FAILURE() << "an iso-level of 1e30 was exported";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.field(), "object");
    EXPECT_NE(std::string(e.what()).find("1e30"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "far.ply"));
}

}  // namespace
}  // namespace trispline::core
