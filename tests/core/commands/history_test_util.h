// Commands run as a log replays them: parsed by the registry (editor::CommandRegistry) and executed through the undo
// history, for the command tests that link trispline_editor_commands.
#pragma once

#include <nlohmann/json.hpp>

#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"

namespace trispline::test {

// Parses `line` with the builtin registry and executes it in `history`; throws core::CommandError as a replay would.
inline void run(editor::History& history, const nlohmann::json& line) {
  const core::CommandContext ctx;
  history.execute(editor::CommandRegistry::builtin().parse(line, ctx));
}

}  // namespace trispline::test
