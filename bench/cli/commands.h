// The subcommands of the chainbench command. Each adds itself to the app; its callback does the
// work and leaves the exit status in *status.
#pragma once

#include <CLI/CLI.hpp>

namespace chainbench {

void add_list_commands(CLI::App& app, int* status);  // list, engines
void add_run_command(CLI::App& app, int* status);
void add_sweep_command(CLI::App& app, int* status);
void add_stress_command(CLI::App& app, int* status);
void add_replay_command(CLI::App& app, int* status);
void add_merge_command(CLI::App& app, int* status);

}  // namespace chainbench
