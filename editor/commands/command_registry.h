// trispline::editor::CommandRegistry — maps a log line's "cmd" id to a parser that builds the typed Command.
// Every command the editor knows is registered here (register_builtin_commands()), so the log format, the
// History panel and replay share one source of truth.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/commands/command.h"
#include "core/params/params.h"

namespace trispline::editor {

// Parses JSON into a command. Throws core::CommandError naming the bad field on missing/mistyped fields.
using CommandParser = std::function<core::CommandPtr(const nlohmann::json&, const core::CommandContext&)>;

class CommandRegistry {
 public:
  // The registry with every built-in command (scene.load, scene.primitive, camera.set, place.sketch, ...).
  static const CommandRegistry& builtin();

  void add(const std::string& id, std::string summary, CommandParser parser);
  // A command declared by a ParamSchema (core/commands/declared_command.h): id, summary, parser and parameter docs
  // all come from C::schema().
  template <class C>
  void add() {
    add(C::schema().id(), C::schema().summary(), &C::parse);
    entries_[C::schema().id()].params = C::schema().docs();
    entries_[C::schema().id()].declared = true;
  }
  // Throws core::CommandError("unknown command 'x'", "cmd") if the id is not registered, or if "cmd" is missing.
  core::CommandPtr parse(const nlohmann::json& line, const core::CommandContext& ctx) const;
  std::vector<std::string> ids() const;
  const std::string& summary(const std::string& id) const;
  // The declared parameters of `id` (empty for a command not declared by a ParamSchema).
  const std::vector<core::ParamDoc>& params(const std::string& id) const;
  bool declared(const std::string& id) const;

 private:
  struct Entry {
    std::string summary;
    CommandParser parser;
    std::vector<core::ParamDoc> params;
    bool declared = false;
  };
  std::map<std::string, Entry> entries_;
};

}  // namespace trispline::editor
