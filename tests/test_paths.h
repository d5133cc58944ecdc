// Where the tests find the shipped replay logs (tests/logs/), one definition for every test folder.
#pragma once

#include <filesystem>
#include <string>

namespace trispline::test {

// tests/logs/ of the source tree.
inline std::filesystem::path logs_dir() { return std::filesystem::path(TRISPLINE_SOURCE_DIR) / "tests" / "logs"; }

// tests/logs/<name>.
inline std::filesystem::path log_path(const std::string& name) { return logs_dir() / name; }

}  // namespace trispline::test
