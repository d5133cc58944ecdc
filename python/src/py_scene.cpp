#include "python/src/py_scene.h"

#include "editor/commands/command_log.h"
#include "editor/commands/command_registry.h"

namespace trispline::python {

core::CommandPtr parse_command(const nlohmann::json& line, const core::CommandContext& ctx) {
  return editor::CommandRegistry::builtin().parse(line, ctx);
}

nlohmann::json PyScene::run(const nlohmann::json& line, const core::CommandContext& ctx) {
  const auto it = line.find("cmd");
  const std::string id = it != line.end() && it->is_string() ? it->get<std::string>() : "";
  if (id == "edit.undo" || id == "edit.redo") {
    const bool is_undo = id == "edit.undo";
    if (!(is_undo ? undo() : redo()))
      throw core::CommandError(std::string("nothing to ") + (is_undo ? "undo" : "redo"), "cmd");
    return {{"line", lines_},          {"cmd", id}, {"ok", true}, {"ms", 0.0}, {"stats", nlohmann::json::object()},
            {"command", {{"cmd", id}}}};
  }
  return execute(parse_command(line, ctx));
}

nlohmann::json PyScene::execute(core::CommandPtr command) {
  const editor::ExecutionRecord rec = history_.execute(std::move(command));
  ++lines_;
  return {{"line", lines_},         {"cmd", rec.cmd},     {"ok", true},
          {"ms", rec.milliseconds}, {"stats", rec.stats}, {"command", rec.line}};
}

bool PyScene::undo() {
  if (!history_.can_undo()) return false;
  history_.undo();
  ++lines_;
  return true;
}

bool PyScene::redo() {
  if (!history_.can_redo()) return false;
  history_.redo();
  ++lines_;
  return true;
}

void PyScene::save(const std::filesystem::path& path) const {
  std::vector<nlohmann::json> lines = history_.applied_lines();
  editor::make_paths_relative(lines, std::filesystem::absolute(path).parent_path());
  editor::write_log_atomic(path, lines);
}

}  // namespace trispline::python
