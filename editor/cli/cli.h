// trispline's command line (CLI11): `trispline [edit] [LOG]`, `trispline replay LOG --out DIR`,
// `trispline bench ffd [--json] [--mesh PATH]`, `trispline commands`, `trispline farm ...` (editor/farm/farm_cli.h).
#pragma once

namespace trispline::editor {

// Parses argv and runs the chosen subcommand; returns the process exit code. Never throws.
int run_cli(int argc, char** argv);

}  // namespace trispline::editor
