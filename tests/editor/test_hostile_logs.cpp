// Hostile command logs (tests/logs/hostile/ and generated ones): every case ends with a clear LOG:LINE error and a
// scene holding exactly the lines before the bad one — no crash, no runaway memory, no non-finite geometry, no
// half-applied command. The limits are those of editor::LogLimits and core::SceneGuard (docs/decisions.md).
#include "editor/command_log.h"
#include "editor/history.h"
#include "editor/replay.h"
#include "core/scene/scene_check.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace trispline;

namespace {

fs::path hostile_dir() { return fs::path(TRISPLINE_SOURCE_DIR) / "tests" / "logs" / "hostile"; }
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / "hostile";
  fs::create_directories(dir);
  return dir / name;
}

struct HostileCase {
  const char* file;
  int line;           // the line that must fail
  const char* field;  // field named in the message ("" = none required)
  const char* words;  // substring of the message
};
void PrintTo(const HostileCase& c, std::ostream* os) { *os << c.file; }

editor::ReplayResult replay(const fs::path& log, core::Scene& scene, editor::History& history) {
  return editor::replay_lines(history, log);
}

void expect_failure(const fs::path& log, const HostileCase& c) {
  core::Scene scene;
  editor::History history(scene);
  const editor::ReplayResult r = replay(log, scene, history);
  ASSERT_FALSE(r.ok) << log << " replayed without error";
  EXPECT_EQ(r.failed_line, c.line) << r.error;
  EXPECT_NE(r.error.find(log.string() + ":" + std::to_string(c.line) + ":"), std::string::npos) << r.error;
  if (*c.field) {
    EXPECT_NE(r.error.find(std::string("field '") + c.field + "'"), std::string::npos) << r.error;
  }
  EXPECT_NE(r.error.find(c.words), std::string::npos) << r.error;
  EXPECT_EQ(history.applied(), r.records.empty() ? 0u : r.records.size() - 1);
  EXPECT_EQ(core::scene_value_error(scene), "") << "the scene holds a non-finite value after " << log;
}

class HostileLog : public ::testing::TestWithParam<HostileCase> {};

TEST_P(HostileLog, EndsWithAClearErrorAndAFiniteScene) {
  expect_failure(hostile_dir() / GetParam().file, GetParam());
}

INSTANTIATE_TEST_SUITE_P(
    Corpus, HostileLog,
    ::testing::Values(HostileCase{"utf8.jsonl", 2, "", "invalid UTF-8 at byte"},
                      HostileCase{"scale_huge.jsonl", 1, "", "not finite or out of range"},
                      HostileCase{"translate_huge.jsonl", 1, "", "not finite or out of range"},
                      HostileCase{"press_huge.jsonl", 3, "", "not finite or out of range"},
                      HostileCase{"pull_huge.jsonl", 3, "", "not finite or out of range"},
                      HostileCase{"sketch_height.jsonl", 4, "", "height"},
                      HostileCase{"name_nul.jsonl", 1, "name", "control characters"},
                      HostileCase{"name_slash.jsonl", 1, "name", "'/'"},
                      HostileCase{"fps_tiny.jsonl", 1, "fps", "[0.01, 240]"},
                      HostileCase{"paint_radius.jsonl", 3, "radius_px", "(0, 16384]"},
                      HostileCase{"refine_tol.jsonl", 3, "max_triangles", "1..8000000"},
                      HostileCase{"record_big.jsonl", 4, "width", "megapixels"}),
    [](const auto& info) {
      const std::string n = info.param.file;
      return n.substr(0, n.size() - 6);
    });

TEST(HostileLogText, DeepNestingIsRefusedBeforeParsing) {
  const fs::path log = scratch("deep.jsonl");
  {
    std::ofstream out(log);
    out << R"({"cmd":"scene.primitive","kind":"sphere","name":"a"})" << "\n";
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
    out << R"({"cmd":"scene.primitive","kind":"sphere","name":"a"})" << "\n";
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
  EXPECT_NE(editor::utf8_error("a\xc3"), "");                  // truncated
  EXPECT_NE(editor::utf8_error("\xc0\xaf"), "");               // overlong '/'
  EXPECT_NE(editor::utf8_error("\xed\xa0\x80"), "");           // a UTF-16 surrogate
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

}  // namespace
