#include "editor/command_log.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace trispline::editor {
namespace {

std::string describe(const std::filesystem::path& file, int line, const std::string& field, const std::string& msg) {
  std::string s = file.string() + ":" + std::to_string(line) + ": ";
  if (!field.empty() && msg.find("field '" + field + "'") == std::string::npos) s += "field '" + field + "': ";
  return s + msg;
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

std::vector<LogLine> read_log_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw LogError(path, 0, "", "cannot open command log");
  std::vector<LogLine> lines;
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    ++number;
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#' || text.compare(first, 2, "//") == 0) continue;
    lines.push_back(LogLine{number, std::move(text), {}});
  }
  return lines;
}

void parse_log_line(const std::filesystem::path& path, LogLine& line) {
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
