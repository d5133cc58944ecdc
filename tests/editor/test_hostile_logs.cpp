// Hostile command logs (tests/logs/hostile/ and generated ones): every case ends with a clear LOG:LINE error and a
// scene holding exactly the lines before the bad one — no crash, no runaway memory, no non-finite geometry, no
// half-applied command. The limits are those of editor::LogLimits and core::SceneGuard (docs/decisions.md).
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "core/scene/scene_check.h"
#include "editor/commands/command_log.h"
#include "editor/commands/history.h"
#include "editor/replay/replay.h"
#include "tests/editor/session_test_util.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

fs::path hostile_dir() { return test::logs_dir() / "hostile"; }
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / "hostile";
  fs::create_directories(dir);
  return dir / name;
}

using HostileCase = test::BadLogCase;

void expect_failure(const fs::path& log, const HostileCase& c) {
  core::Scene scene;
  editor::History history(scene);
  editor::ReplayResult r;
  ASSERT_NO_FATAL_FAILURE(test::expect_stops_at(history, log, c, r));
  EXPECT_EQ(history.applied(), r.records.empty() ? 0u : r.records.size() - 1);
  EXPECT_EQ(core::scene_value_error(scene), "") << "the scene holds a non-finite value after " << log;
}

class HostileLog : public ::testing::TestWithParam<HostileCase> {};

TEST_P(HostileLog, EndsWithAClearErrorAndAFiniteScene) { expect_failure(hostile_dir() / GetParam().file, GetParam()); }

INSTANTIATE_TEST_SUITE_P(
    Corpus, HostileLog,
    ::testing::Values(HostileCase{"utf8.jsonl", 2, "", "invalid UTF-8 at byte"},
                      HostileCase{"scale_huge.jsonl", 1, "", "not finite or out of range"},
                      HostileCase{"translate_huge.jsonl", 1, "", "not finite or out of range"},
                      HostileCase{"sketch_samples.jsonl", 4, "samples", "contact samples: at most 1048576"},
                      HostileCase{"press_huge.jsonl", 3, "", "not finite or out of range"},
                      HostileCase{"pull_huge.jsonl", 3, "", "not finite or out of range"},
                      HostileCase{"sketch_height.jsonl", 4, "", "height"},
                      HostileCase{"name_nul.jsonl", 1, "name", "control characters"},
                      HostileCase{"name_slash.jsonl", 1, "name", "'/'"},
                      HostileCase{"fps_tiny.jsonl", 1, "fps", "[0.01, 240]"},
                      HostileCase{"paint_radius.jsonl", 3, "radius_px", "(0, 16384]"},
                      HostileCase{"refine_tol.jsonl", 3, "max_triangles", "[1, 8e6]"},
                      HostileCase{"record_big.jsonl", 4, "width", "megapixels"},
                      HostileCase{"export_escape.jsonl", 2, "path", "leaves the output folder"},
                      HostileCase{"export_absolute.jsonl", 2, "path", "is absolute"},
                      HostileCase{"ddm_export_escape.jsonl", 3, "path", "leaves the output folder"},
                      HostileCase{"refine_tiny.jsonl", 3, "tolerance", "float32"},
                      HostileCase{"fill_counts.jsonl", 2, "counts", "cells on one chart"},
                      HostileCase{"fill_tile_size.jsonl", 2, "tile_size", "tile vertices"},
                      HostileCase{"paint_counts.jsonl", 3, "counts", "painting budget"}),
    [](const auto& info) {
      const std::string n = info.param.file;
      return n.substr(0, n.size() - 6);
    });

TEST(HostileLogText, ExportsThatLeaveTheOutputFolderWriteNothing) {
  const fs::path escaped = fs::weakly_canonical(test::logs_dir() / ".." / "escaped_by_log.svg");
  const fs::path absolute = "/tmp/trispline_escaped_by_log.glb";
  fs::remove(escaped);
  fs::remove(absolute);
  for (const char* file : {"export_escape.jsonl", "export_absolute.jsonl"}) {
    core::Scene scene;
    editor::History history(scene);
    EXPECT_FALSE(editor::replay_lines(history, hostile_dir() / file).ok) << file;
    // Replayed with an --out folder too: the output folder moves, the refusal does not.
    core::Scene again;
    editor::History history2(again);
    EXPECT_FALSE(editor::replay_lines(history2, hostile_dir() / file, {}, scratch("export_out")).ok) << file;
  }
  EXPECT_FALSE(fs::exists(escaped)) << escaped;
  EXPECT_FALSE(fs::exists(absolute)) << absolute;
}

TEST(HostileLogText, DeepNestingIsRefusedBeforeParsing) {
  const fs::path log = scratch("deep.jsonl");
  {
    std::ofstream out(log);
    out << R"({"cmd":"scene.primitive","kind":"sphere","name":"a"})"
        << "\n";
    out << R"({"cmd":"scene.primitive","kind":"sphere","name":"b","x":)" << std::string(100000, '[')
        << std::string(100000, ']') << "}\n";
  }
  expect_failure(log, {"deep.jsonl", 2, "", "nested 100001 levels deep (the limit is 32)"});
}

TEST(HostileLogText, BracketsInsideStringsDoNotCount) {
  EXPECT_EQ(editor::json_nesting_depth(R"({"a":"[[[[{{{{\"[[["})"), 1);
  EXPECT_EQ(editor::json_nesting_depth(R"({"a":[[1,2],[3]]})"), 3);
}

TEST(HostileLogText, AnOverlongLineIsRefusedWithoutHoldingIt) {
  const fs::path log = scratch("long.jsonl");
  {
    std::ofstream out(log);
    out << R"({"cmd":"scene.primitive","kind":"sphere","name":"a"})"
        << "\n";
    out << R"({"cmd":"scene.primitive","kind":"sphere","name":"b","pad":")"
        << std::string(editor::log_limits().max_line_bytes + 10, 'x') << "\"}\n";
  }
  // The reader refuses the whole file at the long line (nothing is replayed from a file that cannot be read).
  try {
    editor::read_log_text(log);
    ADD_FAILURE() << "an overlong line was read";
  } catch (const editor::LogError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("longer than"), std::string::npos) << e.what();
  }
  core::Scene scene;
  editor::History history(scene);
  const editor::ReplayResult r = editor::replay_lines(history, log);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.failed_line, 2);
  EXPECT_EQ(scene.objects().size(), 0u);
}

TEST(HostileLogText, InvalidUtf8IsFoundAtItsByte) {
  EXPECT_EQ(editor::utf8_error("plain ascii"), "");
  EXPECT_EQ(editor::utf8_error("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), "");
  EXPECT_EQ(editor::utf8_error("ab\xff"), "invalid UTF-8 at byte 3");
  EXPECT_NE(editor::utf8_error("a\xc3"), "");         // truncated
  EXPECT_NE(editor::utf8_error("\xc0\xaf"), "");      // overlong '/'
  EXPECT_NE(editor::utf8_error("\xed\xa0\x80"), "");  // a UTF-16 surrogate
  EXPECT_EQ(editor::utf8_error("a\xc3"), "invalid UTF-8 at byte 2 (truncated sequence)");
  EXPECT_EQ(editor::utf8_error("\xc0\xaf"), "invalid UTF-8 at byte 1 (overlong or not a character)");
  EXPECT_EQ(editor::utf8_error("x\xed\xa0\x80"), "invalid UTF-8 at byte 2 (overlong or not a character)");
  EXPECT_EQ(editor::utf8_error("\xf4\x90\x80\x80"), "invalid UTF-8 at byte 1 (overlong or not a character)");
  EXPECT_EQ(editor::utf8_error("\xe2\x28\xa1"), "invalid UTF-8 at byte 1");  // not a continuation byte
}

TEST(HostileLogText, PathsThatAreNotRegularFilesAreNamed) {
  const fs::path fifo = scratch("fifo.jsonl");
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const fs::path zero = scratch("zero.jsonl");
  fs::remove(zero);
  fs::create_symlink("/dev/zero", zero);
  const fs::path dir = scratch("folder.jsonl");
  fs::create_directories(dir);
  for (const auto& [path, words] : {std::pair{fifo, "FIFO"}, {zero, "character device"}, {dir, "directory"}}) {
    try {
      editor::read_log_text(path);
      ADD_FAILURE() << path << " was read";
    } catch (const editor::LogError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
}

TEST(HostileLogText, NonFiniteResultsAreTakenBackNotKept) {
  core::Scene scene;
  editor::History history(scene);
  const fs::path log = hostile_dir() / "pull_huge.jsonl";
  const editor::ReplayResult r = editor::replay_lines(history, log);
  ASSERT_FALSE(r.ok);
  ASSERT_EQ(history.applied(), 2u);
  // The object is exactly as the ring lattice left it: the pull was undone.
  const core::SceneObject* t = scene.find("t");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(core::scene_value_error(scene), "");
}

// Mesh files a log points at: refused at their line with a clear error, before they cost memory, and the scene
// keeps the lines before. (The loaders' own tests are in tests/core/mesh/; this is the path replay, Open and crash
// recovery take.)
long max_rss_mb() {
  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024;
}

void write_glb(const fs::path& path, std::string json, const std::string& bin) {
  while (json.size() % 4) json += ' ';
  auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const std::uint32_t total =
      12 + 8 + static_cast<std::uint32_t>(json.size()) + 8 + static_cast<std::uint32_t>(bin.size());
  std::ofstream(path, std::ios::binary) << "glTF" << u32(2) << u32(total)
                                        << u32(static_cast<std::uint32_t>(json.size())) << "JSON" << json
                                        << u32(static_cast<std::uint32_t>(bin.size())) << "BIN" << std::string(1, '\0')
                                        << bin;
}

TEST(HostileMeshFiles, EndAtTheirLineWithAClearErrorAndLittleMemory) {
  const fs::path dir = scratch("meshes");
  fs::remove_all(dir);
  fs::create_directories(dir);
  // A 128-byte GLB whose accessor claims 3e8 vertices (7 GB before its bounds error, as found).
  write_glb(
      dir / "claims.glb",
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":8}],"bufferViews":[{"buffer":0,"byteLength":8}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":300000000,"type":"VEC3"}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})",
      std::string(8, '\0'));
  // 2 GB sparse files (read whole, or hanging, before).
  std::ofstream(dir / "sparse.ply") << "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                                       "property float y\nproperty float z\nend_header\n";
  fs::resize_file(dir / "sparse.ply", 2'000'000'000ull);
  std::ofstream(dir / "sparse.obj") << "v 0 0 0\n";
  fs::resize_file(dir / "sparse.obj", 2'000'000'000ull);
  // A glTF whose buffer is a file outside its folder.
  std::ofstream(dir / "escape.gltf")
      << R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"../../../../../../../../etc/passwd"}],)"
         R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
  fs::remove(dir / "zero.obj");
  fs::create_symlink("/dev/zero", dir / "zero.obj");

  struct Case {
    const char* line;
    const char* words;
  };
  const Case cases[] = {
      {R"({"cmd":"scene.load","path":"claims.glb"})", "claims.glb"},
      {R"({"cmd":"scene.load","path":"sparse.ply"})", "longer than its header can describe"},
      {R"({"cmd":"scene.load","path":"sparse.obj"})", "memory budget"},
      {R"({"cmd":"scene.load","path":"escape.gltf"})", "outside"},
      {R"({"cmd":"scene.load","path":"zero.obj"})", "is a character device"},
      {R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"l","tile":"zero.obj","layout":"rect","counts":[1,1],"height":0.05})",
       "is a character device"},
  };
  const long rss_before = max_rss_mb();
  for (const Case& c : cases) {
    const fs::path log = dir / "case.jsonl";
    std::ofstream(log) << R"({"cmd":"scene.primitive","kind":"sphere","name":"ball"})"
                       << "\n"
                       << c.line << "\n";
    SCOPED_TRACE(c.line);
    core::Scene scene;
    editor::History history(scene);
    const editor::ReplayResult r = editor::replay_lines(history, log);
    ASSERT_FALSE(r.ok);
    EXPECT_EQ(r.failed_line, 2) << r.error;
    EXPECT_NE(r.error.find(log.string() + ":2:"), std::string::npos) << r.error;
    EXPECT_NE(r.error.find(c.words), std::string::npos) << r.error;
    EXPECT_EQ(r.error.find("root:"), std::string::npos)
        << "the bytes of a file outside the folder were read: " << r.error;
    EXPECT_EQ(history.applied(), 1u);
    EXPECT_EQ(scene.objects().size(), 1u);
    EXPECT_LT(max_rss_mb() - rss_before, 256) << "refusing the file cost more than 256 MB: " << r.error;
  }
  EXPECT_LT(max_rss_mb() - rss_before, 256) << "refusing the files cost more than 256 MB";
}

}  // namespace
