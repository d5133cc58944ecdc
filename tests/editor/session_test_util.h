// Shared fixture of the editor-session tests: a fresh TRISPLINE_STATE_DIR per test and the Log panel's messages.
#pragma once

#include "ui/message_log.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace trispline::test {

class StateDirTest : public ::testing::Test {
 protected:
  explicit StateDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           (prefix_ + ::testing::UnitTest::GetInstance()->current_test_info()->name());
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

 private:
  std::string prefix_;
};

// Non-empty lines of a file.
inline std::size_t line_count(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::size_t n = 0;
  for (std::string s; std::getline(in, s);) n += !s.empty();
  return n;
}

}  // namespace trispline::test
