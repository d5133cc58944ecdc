// What every command's parameters are read against: CommandError (a bad field of a log line, named) and
// CommandContext (the log's folder and the output folder its paths resolve in).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace trispline::core {

class CommandError : public std::runtime_error {
 public:
  explicit CommandError(const std::string& message, std::string field = {})
      : std::runtime_error(message), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// What a command needs from outside the scene while parsing/executing.
struct CommandContext {
  std::filesystem::path base_dir;  // relative paths in a log are relative to the log's folder
  // The folder every file a command writes (volume.export) must stay in: replay's --out folder, the folder the
  // editor's user chose in a dialog; empty = base_dir.
  std::filesystem::path output_dir;
  std::filesystem::path resolve(const std::string& path) const;
  // An output path of a log (`path`, as written in the line, named `field` in errors) resolved under output_dir
  // (base_dir when empty): the absolute, canonical file path, with `..` and every existing symlink resolved.
  // Throws CommandError(field) when `path` is empty, absolute, holds a control character, names a folder, or
  // resolves outside the output folder (a log is shared input: it must not write where its reader did not ask).
  std::filesystem::path resolve_output(const std::string& path, const char* field = "path") const;
};

}  // namespace trispline::core
