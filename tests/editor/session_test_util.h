// Shared fixture of the editor-session tests: a fresh TRISPLINE_STATE_DIR per test and the Log panel's messages.
#pragma once

#include "ui/message_log.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

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

}  // namespace trispline::test
