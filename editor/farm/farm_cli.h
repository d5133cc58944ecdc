// `trispline farm submit|batch|status|resume|assemble|task` on the command line (CLI11); editor/farm/farm.h does the
// work. A bad value of any farm subcommand exits 2 (editor/cli/cli.cpp maps CLI11's parse errors for `farm`).
#pragma once

#include "editor/farm/farm.h"

namespace CLI {
class App;
}

namespace trispline::editor {

// What the farm subcommands were given, and the subcommand objects to test which one ran.
struct FarmCli {
  FarmPlan plan;
  std::string frames;                  // "A-B"
  std::filesystem::path batch_folder;  // farm batch FOLDER
  std::filesystem::path dir;           // status / resume / assemble DIR
  bool json = false;                   // status --json
  int task_index = 0;                  // task DIR K
  CLI::App *submit = nullptr, *batch = nullptr, *status = nullptr, *resume = nullptr, *assemble = nullptr,
           *task = nullptr;
};

// Adds `farm` and its subcommands to `app`.
void add_farm_commands(CLI::App& app, FarmCli& o);
// Runs the farm subcommand that was parsed; returns the exit code, or −1 when no farm subcommand ran.
int run_farm_command(FarmCli& o);

}  // namespace trispline::editor
