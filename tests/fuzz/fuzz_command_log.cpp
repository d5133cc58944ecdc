// libFuzzer target: the command-log reader and every command's parser, the code that Open, crash recovery and
// `trispline replay` run on untrusted text. The input is written to a file and read back through read_log_text (the
// size, line-length, line-count and regular-file checks), each line goes through parse_log_line (UTF-8, nesting,
// JSON) and CommandRegistry::parse (every field's validation). A parsed command must describe itself as a line that
// parses again to the same line (the log the editor writes must replay): a difference aborts, like a crash.
// Nothing is executed: execution is covered by the replay tests of tests/logs/ and tests/logs/hostile/.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "editor/commands/command_log.h"
#include "editor/commands/command_registry.h"

using namespace trispline;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = [] {
    const std::filesystem::path dir = std::filesystem::temp_directory_path();
    return dir / ("trispline_fuzz_log_" + std::to_string(::getpid()) + ".jsonl");
  }();
  if (std::FILE* f = std::fopen(file.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  std::vector<editor::LogLine> lines;
  try {
    lines = editor::read_log_text(file);
  } catch (const editor::LogError&) {
    return 0;
  }
  core::CommandContext ctx;
  ctx.base_dir = file.parent_path();
  const auto& registry = editor::CommandRegistry::builtin();
  for (editor::LogLine& line : lines) {
    try {
      editor::parse_log_line(file, line);
    } catch (const editor::LogError&) {
      continue;
    }
    core::CommandPtr cmd;
    try {
      cmd = registry.parse(line.json, ctx);
    } catch (const core::CommandError&) {
      continue;
    }
    const nlohmann::json written = cmd->to_json();
    try {
      const nlohmann::json again = registry.parse(written, ctx)->to_json();
      if (again != written) {
        std::fprintf(stderr, "a command's line does not round-trip:\n  %s\n  %s\n", written.dump().c_str(),
                     again.dump().c_str());
        std::abort();
      }
    } catch (const core::CommandError& e) {
      std::fprintf(stderr, "a command's own line does not parse: %s\n  %s\n", e.what(), written.dump().c_str());
      std::abort();
    }
  }
  return 0;
}
