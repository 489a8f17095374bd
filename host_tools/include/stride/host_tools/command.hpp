// The `stride` command's subcommand registry.
//
// Each subcommand lives in its own file under host_tools/src/commands/ and registers itself:
//
//   STRIDE_COMMAND(sim, "simulate the robot: stand, walk or kick", run_sim);
//
// where `int run_sim(int argc, char** argv)` receives argv starting at the subcommand name.
// A subcommand prints `--help`, exits 0 on success, 2 on bad input (one line on stderr naming
// what was wrong) and 1 on a failure while running (command_errors.hpp prints and returns both).
#pragma once

#include <string_view>
#include <vector>

namespace stride::tools {

using CommandFn = int (*)(int argc, char** argv);

struct Command {
  std::string_view name;
  std::string_view summary;
  CommandFn run;
};

/// All registered subcommands, sorted by name.
const std::vector<Command>& commands();

/// Adds a subcommand (called from static initialisers via STRIDE_COMMAND).
bool register_command(Command command);

/// Runs `command` with argv starting at its name, and is every command's last line of defence:
/// an exception that escapes it (a bug, or memory exhausted) ends it as any failure does, with
/// "stride NAME: internal error: WHAT" on stderr and exit 1, instead of an abort.
int run_command(const Command& command, int argc, char** argv);

}  // namespace stride::tools

#define STRIDE_COMMAND(name, summary, fn)                               \
  [[maybe_unused]] static const bool stride_command_registered_##name = \
      ::stride::tools::register_command(::stride::tools::Command{#name, summary, fn})
