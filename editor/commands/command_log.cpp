#include "editor/commands/command_log.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "core/base/enum_names.h"
#include "core/base/text.h"

namespace trispline::editor {
namespace {

std::string describe(const std::filesystem::path& file, int line, const std::string& field, const std::string& msg) {
  std::string s = file.string() + ":" + std::to_string(line) + ": ";
  if (!field.empty() && msg.find("field '" + field + "'") == std::string::npos) s += "field '" + field + "': ";
  return s + msg;
}

// What a path that is not a regular file is, for error messages.
std::string describe_file_type(const std::filesystem::path& path) {
  using T = std::filesystem::file_type;
  std::error_code ec;
  const char* kind = core::code_name<T>(std::filesystem::status(path, ec).type(),
                                        {{T::not_found, "no such file"},
                                         {T::directory, "it is a directory"},
                                         {T::fifo, "it is a FIFO (named pipe)"},
                                         {T::character, "it is a character device"},
                                         {T::block, "it is a block device"},
                                         {T::socket, "it is a socket"},
                                         {T::regular, "a regular file"}},
                                        nullptr);
  return kind ? kind : ec ? ec.message() : "not a regular file";
}

// "cmd" first, other keys in their (sorted) order: logs read naturally.
// fsync that treats "this file cannot be synced" (a pipe, a character device) as success.
bool sync_fd(int fd) { return ::fsync(fd) == 0 || errno == EINVAL || errno == EROFS; }

std::string format_line(const nlohmann::json& line) {
  nlohmann::ordered_json out;
  if (line.contains("cmd")) out["cmd"] = line.at("cmd");
  for (auto it = line.begin(); it != line.end(); ++it)
    if (it.key() != "cmd") out[it.key()] = it.value();
  return out.dump();
}

}  // namespace

LogError::LogError(const std::filesystem::path& file, int line, const std::string& field, const std::string& message)
    : std::runtime_error(describe(file, line, field, message)), file_(file), line_(line), field_(field) {}

const LogLimits& log_limits() {
  static const LogLimits limits;
  return limits;
}

std::string utf8_error(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    if (const std::size_t len = core::utf8_sequence_length(text, i)) {
      i += len;
      continue;
    }
    // Why not: the length the lead byte's bit pattern announces (110xxxxx 2, 1110xxxx 3, 11110xxx 4), then the bytes
    // that follow; a sequence of that shape that is still not well-formed is overlong, a surrogate or > U+10FFFF.
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t shape = (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
    const std::string at = "invalid UTF-8 at byte " + std::to_string(i + 1);
    if (shape == 0) return at;
    if (i + shape > text.size()) return at + " (truncated sequence)";
    for (std::size_t k = 1; k < shape; ++k)
      if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return at;
    return at + " (overlong or not a character)";
  }
  return {};
}

int json_nesting_depth(std::string_view text) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

std::vector<LogLine> read_log_text(const std::filesystem::path& path) {
  const LogLimits& limits = log_limits();
  // Opened without blocking and checked on the descriptor itself (a path can change between a check and an open):
  // a FIFO or a device would never end, a directory reads as nothing.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw LogError(path, 0, "", "cannot open command log: " + std::string(std::strerror(errno)));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw LogError(path, 0, "", "not a command log: " + describe_file_type(path));
  }
  if (std::uintmax_t(st.st_size) > limits.max_file_bytes) {
    ::close(fd);
    throw LogError(path, 0, "",
                   "the file is " + std::to_string(st.st_size) + " bytes, over the " +
                       std::to_string(limits.max_file_bytes) + "-byte limit of a command log");
  }
  std::FILE* file = ::fdopen(fd, "rb");
  if (!file) {
    ::close(fd);
    throw LogError(path, 0, "", "cannot read command log: " + std::string(std::strerror(errno)));
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(file, &std::fclose);
  std::vector<LogLine> lines;
  std::string text;
  int number = 0;
  std::uintmax_t read_total = 0;
  for (int c = std::getc(in.get()); c != EOF; c = std::getc(in.get())) {
    ++number;
    text.clear();
    // Reads one line but never holds more than max_line_bytes of it.
    bool too_long = false;
    for (; c != EOF && c != '\n'; c = std::getc(in.get())) {
      if (++read_total > limits.max_file_bytes)
        throw LogError(path, number, "", "the file grew past the limit of a command log while being read");
      if (text.size() >= limits.max_line_bytes) {
        too_long = true;
        break;
      }
      text.push_back(char(c));
    }
    if (too_long)
      throw LogError(
          path, number, "",
          "line longer than " + std::to_string(limits.max_line_bytes) + " bytes (the limit of a command log line)");
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#' || text.compare(first, 2, "//") == 0) continue;
    if (lines.size() >= limits.max_lines)
      throw LogError(path, number, "", "more than " + std::to_string(limits.max_lines) + " command lines");
    lines.push_back(LogLine{number, text, {}});
  }
  return lines;
}

void parse_log_line(const std::filesystem::path& path, LogLine& line) {
  if (const std::string bad = utf8_error(line.text); !bad.empty()) throw LogError(path, line.number, "", bad);
  if (const int depth = json_nesting_depth(line.text); depth > log_limits().max_depth)
    throw LogError(path, line.number, "",
                   "JSON nested " + std::to_string(depth) + " levels deep (the limit is " +
                       std::to_string(log_limits().max_depth) + ")");
  try {
    line.json = nlohmann::json::parse(line.text);
  } catch (const nlohmann::json::exception& e) {  // parse errors, and numbers out of range such as 1e999
    throw LogError(path, line.number, "", std::string("malformed JSON: ") + e.what());
  }
  if (!line.json.is_object()) throw LogError(path, line.number, "", "a log line must be a JSON object");
}

std::vector<LogLine> read_log(const std::filesystem::path& path) {
  std::vector<LogLine> lines = read_log_text(path);
  for (auto& l : lines) parse_log_line(path, l);
  return lines;
}

void write_log_atomic(const std::filesystem::path& path, const std::vector<nlohmann::json>& lines) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    for (const auto& l : lines) out << format_line(l) << '\n';
    out.flush();
    if (!out) throw std::runtime_error("write failed: " + tmp.string());
  }
  if (int fd = ::open(tmp.c_str(), O_RDONLY); fd >= 0) {
    const bool synced = sync_fd(fd);
    const int err = errno;
    ::close(fd);
    if (!synced) throw std::runtime_error("cannot fsync " + tmp.string() + ": " + std::strerror(err));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message());
  // The rename itself lives in the folder: sync it so a power loss cannot bring the old file back.
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY); fd >= 0) {
    sync_fd(fd);  // best effort: the file's content is safe already
    ::close(fd);
  }
}

void make_paths_relative(std::vector<nlohmann::json>& lines, const std::filesystem::path& dir) {
  const std::filesystem::path base = std::filesystem::absolute(dir).lexically_normal();
  auto relative = [&](nlohmann::json& value) {
    if (!value.is_string()) return;
    const std::filesystem::path p(value.get<std::string>());
    if (!p.is_absolute()) return;  // generated tiles are names, and already relative paths stay
    const std::filesystem::path rel = p.lexically_relative(base);
    int ups = 0;
    for (const auto& part : rel) ups += part == "..";
    if (!rel.empty() && ups <= 2) value = rel.generic_string();  // farther away: a moved folder would break it
  };
  for (auto& l : lines) {
    const std::string cmd = l.value("cmd", "");
    if (cmd == "scene.load" || cmd == "anim.clip") {
      if (auto it = l.find("path"); it != l.end()) relative(*it);
    } else if (cmd.rfind("ddm.", 0) == 0) {  // tile files of ddm.fill / ddm.paint / ddm.animate
      for (const char* field : {"tile", "morph_tile"})
        if (auto it = l.find(field); it != l.end()) relative(*it);
      for (const char* field : {"tiles", "morph_tiles"})
        if (auto it = l.find(field); it != l.end() && it->is_array())
          for (auto& t : *it) relative(t);
    }
  }
}

CommandLog::CommandLog(std::filesystem::path path, bool truncate) : path_(std::move(path)) {
  if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path());
  file_ = std::fopen(path_.c_str(), truncate ? "w" : "a");
  if (!file_) throw std::runtime_error("cannot open command log " + path_.string());
}

CommandLog::~CommandLog() {
  if (file_) std::fclose(file_);
}

bool CommandLog::append(const nlohmann::json& line) {
  const std::string s = format_line(line) + "\n";
  auto fail = [&](const char* what) {
    error_ = std::string(what) + " " + path_.string() + " failed: " + std::strerror(errno);
    std::clearerr(file_);
    return false;
  };
  errno = 0;
  if (std::fwrite(s.data(), 1, s.size(), file_) != s.size()) return fail("writing to");
  if (std::fflush(file_) != 0) return fail("flushing");
  if (!sync_fd(::fileno(file_))) return fail("fsync of");  // a kill or a crash right after a command loses nothing
  return true;
}

}  // namespace trispline::editor
