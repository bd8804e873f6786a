// Each `ringcrush` subcommand lives in its own file and registers itself here.
#pragma once

#include <CLI/CLI.hpp>

namespace ringcrush::compare::cli {

void add_formula_command(CLI::App& app);
void add_validate_command(CLI::App& app);

// Exit codes shared by all subcommands.
inline constexpr int exit_ok = 0;
inline constexpr int exit_failure = 1;      // a run failed (solver diagnosis printed)
inline constexpr int exit_bad_input = 2;    // scene, deck or flags rejected

}  // namespace ringcrush::compare::cli
