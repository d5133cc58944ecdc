// The parameter tables of docs/commands.md, generated from the commands' declarations (core/params/params.h).
//  * params_table(): one command's fields as a Markdown table (field, type, default, range, unit, meaning).
//  * with_generated_tables(): a document with every `<!-- params: ID -->` … `<!-- /params -->` block replaced by
//    ID's table. `trispline commands --docs FILE` rewrites FILE so; a test fails when docs/commands.md differs.
#pragma once

#include <string>

#include "editor/commands/command_registry.h"

namespace trispline::editor {

// Throws std::out_of_range for an unknown id.
std::string params_table(const CommandRegistry& registry, const std::string& id);
// Throws std::runtime_error for a block with no end marker or an unknown id.
std::string with_generated_tables(const std::string& document, const CommandRegistry& registry);

}  // namespace trispline::editor
