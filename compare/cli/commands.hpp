// Each `ringcrush` subcommand lives in its own file (compare/cli/cmd_*.cpp) and registers
// itself with a static CommandRegistration, so adding a command touches no shared file.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

namespace ringcrush::compare::cli {

using CommandFactory = std::function<void(CLI::App&)>;

// Commands in registration order of their `order` key (help lists them that way).
std::vector<std::pair<int, CommandFactory>>& command_registry();

struct CommandRegistration {
  CommandRegistration(int order, CommandFactory factory) {
    command_registry().emplace_back(order, std::move(factory));
  }
};

// Exit codes shared by all subcommands.
inline constexpr int exit_ok = 0;
inline constexpr int exit_failure = 1;      // a run failed (solver diagnosis printed)
inline constexpr int exit_bad_input = 2;    // scene, deck or flags rejected
inline constexpr int exit_disagree = 3;     // compare: both models ran and they disagree

// A command that completed but wants a non-zero status (compare: disagreement) sets this.
int& command_exit_status();

}  // namespace ringcrush::compare::cli
