// SPDX-License-Identifier: MIT
// What the subcommands of the chainbench command share. Each command is a file, cli/cmd_NAME.cpp,
// that defines add_NAME_command(app, status), listed in main.cpp's command table: it adds itself
// to the app, and its callback does the work and leaves the exit status in *status.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace chainbench {

using AddCommand = void (*)(CLI::App& app, int* status);

// --engines given empty is a mistake (a shell variable that expanded to nothing), not a request
// for the defaults: those come from leaving the option out.
inline const CLI::Validator kEngineList(
    [](std::string& list) {
      return list.empty() ? std::string("no engine named (leave --engines out for the defaults)")
                          : std::string();
    },
    "ENGINES", "engine list");

// `engines SPEC` given an empty SPEC, likewise: every engine is listed by leaving it out.
inline const CLI::Validator kEngineSpec(
    [](std::string& spec) {
      return spec.empty() ? std::string("no engine named (leave SPEC out for every engine)")
                          : std::string();
    },
    "SPEC", "engine spec");

}  // namespace chainbench
