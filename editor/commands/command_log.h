// trispline::editor command logs (JSON Lines, one command object per line; see docs/commands.md).
//  * CommandLog: the append-only session log, flushed (and fsync'ed) after every line so a crash loses nothing;
//    append() checks fwrite/fflush/fsync and returns false (error() says why) when the line may be lost.
//  * read_log(): parses a log file into lines with their line numbers (blank lines and lines starting with
//    '#' or '//' are skipped); a malformed JSON line throws LogError naming file and line.
//    Hostile input is refused before it costs memory or stack (LogLimits): the path must be a regular file no larger
//    than max_file_bytes, a line no longer than max_line_bytes (checked while reading, so a 200 MB line is never
//    held), valid UTF-8, and nested no deeper than max_depth arrays/objects (checked before the JSON parser and
//    every recursive JSON operation after it see the line).
//  * write_log_atomic(): Save — writes to PATH.tmp, fsyncs, renames over PATH, fsyncs PATH's folder.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace trispline::editor {

class LogError : public std::runtime_error {
 public:
  LogError(const std::filesystem::path& file, int line, const std::string& field, const std::string& message);
  const std::filesystem::path& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }

 private:
  std::filesystem::path file_;
  int line_;
  std::string field_;
};

// Bounds on what a command log may hold (docs/decisions.md, "Command logs"). The longest line a real session writes
// is a stroke of a few thousand points (≈ 100 KB); the deepest nesting is 3 (an array of points in an object).
struct LogLimits {
  std::uintmax_t max_file_bytes = std::uintmax_t(1) << 30;  // 1 GiB
  std::size_t max_line_bytes = std::size_t(8) << 20;        // 8 MiB
  int max_depth = 32;                                       // nested JSON arrays/objects in one line
  std::size_t max_lines = 1000000;                          // command lines (comments and blanks not counted)
};
const LogLimits& log_limits();

// "" when `text` is valid UTF-8, else where it is not ("invalid UTF-8 at byte 17").
std::string utf8_error(std::string_view text);
// Depth of nested JSON arrays/objects in `text` (brackets inside strings ignored), counted without parsing.
int json_nesting_depth(std::string_view text);

struct LogLine {
  int number = 0;    // 1-based line number in the file
  std::string text;  // the line as written
  nlohmann::json json;
};

// Every command line of the file (comments/blank lines skipped), parsed. Throws LogError at the first bad line.
std::vector<LogLine> read_log(const std::filesystem::path& path);
// The command lines with `json` left empty, for callers that parse line by line (replay stops at the bad line
// but keeps the lines before it). Throws LogError if the file cannot be opened, is not a regular file, or breaks
// LogLimits (file size, line length, line count: the error names the line).
std::vector<LogLine> read_log_text(const std::filesystem::path& path);
// Parses one line's text into line.json. Throws LogError (invalid UTF-8, nesting deeper than LogLimits::max_depth,
// malformed JSON, not an object).
void parse_log_line(const std::filesystem::path& path, LogLine& line);
void write_log_atomic(const std::filesystem::path& path, const std::vector<nlohmann::json>& lines);

// Rewrites absolute "path" fields of scene.load lines relative to `dir` (the folder a log is saved in), as Blender
// does with "//" paths, so a saved scene and its meshes can move together. Paths more than two folders above
// `dir` stay absolute (a relative "../../../usr/share/..." would break as soon as the log moved).
void make_paths_relative(std::vector<nlohmann::json>& lines, const std::filesystem::path& dir);

class CommandLog {
 public:
  explicit CommandLog(std::filesystem::path path, bool truncate = true);  // throws std::runtime_error
  ~CommandLog();
  CommandLog(const CommandLog&) = delete;
  CommandLog& operator=(const CommandLog&) = delete;
  // Writes, flushes and fsyncs one line. False if any of them failed; error() then says which and why.
  bool append(const nlohmann::json& line);
  const std::filesystem::path& path() const { return path_; }
  const std::string& error() const { return error_; }  // the last append failure ("" = none)

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  std::string error_;
};

}  // namespace trispline::editor
