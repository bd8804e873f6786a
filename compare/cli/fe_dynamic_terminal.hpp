// What `ringcrush fe` shows on the terminal for a dynamic scene (issue 4 item 7): the options
// (integrator, Δt control, mesh, joints, masses), one updating progress line on a TTY, the
// end reason and the run statistics, the per-ring table and the alternation index.
#pragma once

#include "compare/run_result.hpp"
#include "compare/scene.hpp"
#include "fe/chain/chain_input.hpp"
#include "fe/dynamics/dynamic_run.hpp"

namespace ringcrush::compare::cli {

void echo_dynamic(const Scene& scene, const fe::ChainInput& chain, const fe::DynamicSolverInput& solver);

// Progress (at most ~10 lines a second, on stderr, only on a TTY) and log lines (unless quiet).
fe::DynamicCallbacks dynamic_terminal_callbacks(bool quiet);

void print_dynamic_result(const Scene& scene, const fe::DynamicResult& result, const RunResult& run);

const char* scheme_name(fe::DynamicScheme scheme);

}  // namespace ringcrush::compare::cli
