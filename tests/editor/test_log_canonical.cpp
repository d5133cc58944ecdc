// Every line of the shipped scenes and the test logs, parsed by the registry and written back by to_json() (or the
// error it raises), compared with tests/logs/canonical.txt. The file pins the log format: a change to a command's
// fields, defaults, what to_json writes or an error message shows up here as a diff. After an intended change,
// regenerate it with TRISPLINE_UPDATE_GOLDEN=1 and review the diff.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "editor/commands/command_log.h"
#include "editor/commands/command_registry.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

const fs::path kSource = TRISPLINE_SOURCE_DIR;

std::vector<fs::path> logs_in(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".jsonl") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// The source folder's absolute path is written as "$SRC", so the file does not depend on the checkout.
std::string without_source_dir(std::string text) {
  const std::string src = fs::absolute(kSource).lexically_normal().string();
  for (std::size_t at = text.find(src); at != std::string::npos; at = text.find(src, at))
    text.replace(at, src.size(), "$SRC");
  return text;
}

// Calls fn(log, line) for every line of the shipped scenes and top-level test logs that reads as JSON (logs that are
// malformed on purpose are passed over).
template <class Fn>
void for_each_readable_line(Fn fn) {
  for (const fs::path& dir :
       {kSource / "assets" / "scenes", kSource / "assets" / "scenes" / "seed", kSource / "tests" / "logs"}) {
    for (const fs::path& log : logs_in(dir)) {
      std::vector<editor::LogLine> lines;
      try {
        lines = editor::read_log(log);
      } catch (const std::exception&) {
        continue;  // malformed on purpose
      }
      for (const editor::LogLine& line : lines) fn(log, line);
    }
  }
}

// The first line of each command in the shipped scenes and test logs, with each of its fields in turn removed or
// given a value of another type or out of range: what the parser answers (the command written back, or its error).
std::string mutated_lines() {
  const editor::CommandRegistry& registry = editor::CommandRegistry::builtin();
  std::map<std::string, nlohmann::json> first;  // cmd -> its first valid line (with the context it came from)
  std::map<std::string, fs::path> where;
  for_each_readable_line([&](const fs::path& log, const editor::LogLine& line) {
    const std::string cmd = line.json.value("cmd", std::string());
    if (cmd.empty() || first.count(cmd)) return;
    try {
      registry.parse(line.json, core::CommandContext{log.parent_path(), {}});
    } catch (const std::exception&) {
      return;
    }
    first[cmd] = line.json;
    where[cmd] = log.parent_path();
  });
  const std::vector<std::pair<const char*, nlohmann::json>> values = {
      {"string", "x"},   {"-1", -1},
      {"0", 0},          {"0.5", 0.5},
      {"1e9", 1e9},      {"[]", nlohmann::json::array()},
      {"[1,2]", {1, 2}}, {"{}", nlohmann::json::object()},
      {"null", nullptr}, {"true", true}};
  std::ostringstream out;
  for (const auto& [cmd, line] : first) {
    const core::CommandContext ctx{where[cmd], {}};
    for (const auto& [field, value] : line.items()) {
      if (field == "cmd") continue;
      auto answer = [&](const nlohmann::json& j) {
        try {
          return without_source_dir(registry.parse(j, ctx)->to_json().dump());
        } catch (const core::CommandError& e) {
          return "error [" + e.field() + "] " + without_source_dir(e.what());
        } catch (const std::exception& e) {
          return "error " + without_source_dir(e.what());
        }
      };
      nlohmann::json missing = line;
      missing.erase(field);
      out << cmd << " " << field << "=<missing>: " << answer(missing) << "\n";
      for (const auto& [name, v] : values) {
        nlohmann::json changed = line;
        changed[field] = v;
        out << cmd << " " << field << "=" << name << ": " << answer(changed) << "\n";
      }
    }
  }
  return out.str();
}

std::string canonical_lines() {
  std::ostringstream out;
  const editor::CommandRegistry& registry = editor::CommandRegistry::builtin();
  for (const fs::path& dir : {kSource / "assets" / "scenes", kSource / "assets" / "scenes" / "seed",
                              kSource / "tests" / "logs", kSource / "tests" / "logs" / "hostile"}) {
    for (const fs::path& log : logs_in(dir)) {
      const std::string name = fs::relative(log, kSource).generic_string();
      std::vector<editor::LogLine> lines;
      try {
        lines = editor::read_log_text(log);
      } catch (const std::exception& e) {
        out << name << ": unreadable: " << without_source_dir(e.what()) << "\n";
        continue;
      }
      const core::CommandContext ctx{log.parent_path(), {}};
      for (editor::LogLine& line : lines) {
        out << name << ":" << line.number << ": ";
        try {
          editor::parse_log_line(log, line);
          const std::string cmd = line.json.value("cmd", std::string());
          if (cmd == "edit.undo" || cmd == "edit.redo") {
            out << line.json.dump() << "\n";
            continue;
          }
          out << without_source_dir(registry.parse(line.json, ctx)->to_json().dump()) << "\n";
        } catch (const core::CommandError& e) {
          out << "error [" << e.field() << "] " << without_source_dir(e.what()) << "\n";
        } catch (const std::exception& e) {
          out << "error " << without_source_dir(e.what()) << "\n";
        }
      }
    }
  }
  out << mutated_lines();
  return out.str();
}

TEST(LogCanonical, EveryShippedLineParsesAndWritesBackAsPinned) {
  const fs::path golden = kSource / "tests" / "logs" / "canonical.txt";
  const std::string now = canonical_lines();
  if (const char* update = std::getenv("TRISPLINE_UPDATE_GOLDEN"); update && std::string(update) == "1") {
    std::ofstream(golden, std::ios::binary) << now;
    GTEST_SUCCEED() << "wrote " << golden;
    return;
  }
  std::ifstream in(golden, std::ios::binary);
  ASSERT_TRUE(in) << "missing " << golden << " (run with TRISPLINE_UPDATE_GOLDEN=1)";
  std::stringstream pinned;
  pinned << in.rdbuf();
  std::istringstream a(pinned.str()), b(now);
  std::string la, lb;
  int n = 0;
  while (true) {
    const bool ha = static_cast<bool>(std::getline(a, la)), hb = static_cast<bool>(std::getline(b, lb));
    ++n;
    if (!ha && !hb) break;
    ASSERT_EQ(ha ? la : "<end>", hb ? lb : "<end>") << "canonical.txt line " << n << " differs";
  }
}

// Writing a parsed line and parsing it again is a fixed point: a log the editor writes replays to the same command.
TEST(LogCanonical, ToJsonIsAFixedPointOfParse) {
  const editor::CommandRegistry& registry = editor::CommandRegistry::builtin();
  int checked = 0;
  for_each_readable_line([&](const fs::path& log, const editor::LogLine& line) {
    const core::CommandContext ctx{log.parent_path(), {}};
    core::CommandPtr first;
    try {
      first = registry.parse(line.json, ctx);
    } catch (const std::exception&) {
      return;  // a bad line on purpose
    }
    const nlohmann::json once = first->to_json();
    const nlohmann::json twice = registry.parse(once, ctx)->to_json();
    EXPECT_EQ(once.dump(), twice.dump()) << log.filename() << ":" << line.number;
    ++checked;
  });
  EXPECT_GT(checked, 300);
}

}  // namespace
