// Shared fixture of the editor-session tests: a fresh TRISPLINE_STATE_DIR per test and the Log panel's messages;
// sessions started with a few commands, crashed sessions, and scenes replayed from tests/logs/.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "editor/commands/history.h"
#include "editor/replay/replay.h"
#include "editor/session/session.h"
#include "tests/test_paths.h"
#include "ui/message_log.h"

namespace trispline::test {

// TRISPLINE_STATE_DIR is <temp>/trispline_<suite>_<test>.
class StateDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("trispline_") + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(dir_);
    ::setenv("TRISPLINE_STATE_DIR", dir_.c_str(), 1);
  }
  void TearDown() override {
    std::error_code ec;  // tests may make the folder read-only
    std::filesystem::permissions(dir_, std::filesystem::perms::owner_all, std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(dir_, ec);
  }
  // True if some Log panel message contains `part`.
  bool logged(const std::string& part) const {
    for (const auto& m : messages_.messages())
      if (m.text.find(part) != std::string::npos) return true;
    return false;
  }
  std::filesystem::path dir_;
  ui::MessageLog messages_;
};

// Two objects the session tests load: the teapot primitive, and a small crate above it.
inline const nlohmann::json kTeapot = {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "teapot"}};
inline const nlohmann::json kBox = {{"cmd", "scene.primitive"},
                                    {"kind", "box"},
                                    {"name", "crate"},
                                    {"scale", {0.2, 0.05, 0.05}},
                                    {"translate", {0, 2, 0}}};

// Non-empty lines of a file.
inline std::size_t line_count(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::size_t n = 0;
  for (std::string s; std::getline(in, s);) n += !s.empty();
  return n;
}

// Starts `s` without offering recovery and executes `lines`; a failure names the line that did not run.
inline ::testing::AssertionResult start_with(editor::EditorSession& s, std::initializer_list<nlohmann::json> lines) {
  s.start(false);
  for (const nlohmann::json& l : lines)
    if (!s.execute(l)) return ::testing::AssertionFailure() << "refused: " << l.dump();
  return ::testing::AssertionSuccess();
}

// A session that runs `lines` and dies without finish(), as after a crash or a kill: its lock and log stay.
inline void crash_with(const std::vector<nlohmann::json>& lines) {
  ui::MessageLog m;
  editor::EditorSession crashed(m);
  crashed.start(true);
  for (const auto& l : lines) ASSERT_TRUE(crashed.execute(l));
}

// A log that must stop at a bad line.
struct BadLogCase {
  const char* file;
  int line;           // the line that must fail
  const char* field;  // field named in the message ("" = none required)
  const char* words;  // substring of the message
};
// ctest shows the log's name instead of the bytes of the struct.
inline void PrintTo(const BadLogCase& c, std::ostream* os) { *os << c.file; }

// Replays `log` (c.file's path) into `history` into `r`: it must stop at line c.line with an error naming
// "LOG:LINE:", field c.field (unless "") and holding c.words. Fatal when the log replays without error.
inline void expect_stops_at(editor::History& history, const std::filesystem::path& log, const BadLogCase& c,
                            editor::ReplayResult& r) {
  r = editor::replay_lines(history, log);
  ASSERT_FALSE(r.ok) << log << " replayed without error";
  EXPECT_EQ(r.failed_line, c.line) << r.error;
  EXPECT_NE(r.error.find(log.string() + ":" + std::to_string(c.line) + ":"), std::string::npos) << r.error;
  if (*c.field) {
    EXPECT_NE(r.error.find(std::string("field '") + c.field + "'"), std::string::npos) << r.error;
  }
  EXPECT_NE(r.error.find(c.words), std::string::npos) << r.error;
}

// Replays tests/logs/<name> into `scene` through a History; a failure carries the replay's error.
inline ::testing::AssertionResult replay_log(core::Scene& scene, const std::string& name) {
  editor::History history(scene);
  const editor::ReplayResult r = editor::replay_lines(history, log_path(name));
  if (!r.ok) return ::testing::AssertionFailure() << r.error;
  return ::testing::AssertionSuccess();
}

}  // namespace trispline::test
