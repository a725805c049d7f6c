// SPDX-License-Identifier: MIT
// chainbench: runs the collision-chaining solver and rigid-body engines on the same scenes and
// compares them.
// Exit status: 0 done; 2 bad input or usage; 3 `run --require` not met; 1 an output file that
// could not be finished, an internal failure, or (stress) the modern solver not ok on a case;
// 130 a run, sweep or stress stopped by Ctrl-C (what finished is kept). A failed write to standard
// output or standard error is an output error (1).
#include "cli/commands.h"
#include "support/input_error.h"
#include "support/output_file.h"

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <string>

namespace chainbench {

// The commands, in the order --help lists them; each is defined in its cli/cmd_NAME.cpp.
void add_list_commands(CLI::App& app, int* status);  // list, engines
void add_run_command(CLI::App& app, int* status);
void add_sweep_command(CLI::App& app, int* status);
void add_stress_command(CLI::App& app, int* status);
void add_replay_command(CLI::App& app, int* status);
void add_merge_command(CLI::App& app, int* status);
constexpr AddCommand kCommands[] = {add_list_commands,  add_run_command,    add_sweep_command,
                                    add_stress_command, add_replay_command, add_merge_command};

}  // namespace chainbench

int main(int argc, char** argv) {
  CLI::App app{"chainbench: collision chaining against rigid-body engines, in numbers"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "this help and every command's help");
  app.set_version_flag("--version", "chainbench " CHAINBENCH_VERSION);
  int status = 0;
  for (chainbench::AddCommand add : chainbench::kCommands)
    add(app, &status);
  // Each command inherits --help-all, but has no commands below it: there it prints what --help
  // does, and says so.
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    sub->set_help_all_flag("--help-all",
                           "this command's help, as --help (chainbench --help-all: every "
                           "command's help)");
  // Every message of ours starts with the command's name; so do CLI11's.
  // CLI11 says "--scene: At Most 1 required but received 2" of an option given twice: say so.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    // Split on the text rather than with std::regex, which GCC 12 warns about under the
    // sanitizers' optimisation (a maybe-uninitialized inside std::function).
    std::string what = e.what();
    const std::string marker = ": At Most 1 required but received ";
    if (const std::size_t at = what.find(marker); at != std::string::npos) {
      const std::string count = what.substr(at + marker.size());
      if (!count.empty() && count.find_first_not_of("0123456789") == std::string::npos)
        what = what.substr(0, at) + " given " + count + " times; give it once";
    }
    return "chainbench: " + what + "\n(--help, or COMMAND --help, says more)\n";
  });
  // CLI11 would say only that a subcommand is required: name the word or option it did not know
  // before the command.
  if (argc > 1) {
    const std::string first = argv[1];
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      found = found || sub->check_name(first);
      known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    if (first[0] == '-' && first != "--help" && first != "-h" && first != "--help-all" &&
        first != "--version") {
      std::cerr << "chainbench: unknown option " << first << " (commands: " << known
                << "; options before a command: --help, --help-all, --version)\n";
      return 2;
    }
    if (first[0] != '-' && !found) {
      std::cerr << "chainbench: unknown command \"" << first << "\" (commands: " << known
                << "; --help says more)\n";
      return 2;
    }
  }
  int code = status;
  try {
    app.parse(argc, argv);
    code = status;
  } catch (const CLI::ParseError& e) {
    code = app.exit(e) == 0 ? 0 : 2;
  } catch (const chainbench::InputError& e) {
    std::cerr << "chainbench: " << e.what() << '\n';
    code = 2;
  } catch (const chainbench::OutputError& e) {
    std::cerr << "chainbench: " << e.what() << '\n';
    code = 1;
  } catch (const std::exception& e) {
    std::cerr << "chainbench: internal error: " << e.what() << '\n';
    code = 1;
  }
  // What was printed must have arrived: a table sent to a full disk is a failure, not a success.
  try {
    chainbench::check_standard_streams();
  } catch (const chainbench::OutputError& e) {
    std::cerr << "chainbench: " << e.what() << '\n';
    return code == 0 ? 1 : code;
  }
  return code;
}
