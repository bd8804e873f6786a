// The FE dynamic impact seen from compare/ (issue 4 item 7; thesis §3.5, §4.2): Scene →
// fe::ChainInput + fe::DynamicSolverInput, fe::DynamicResult → RunResult (with the geometric
// measures of compare/measures taken on the FINAL outer surfaces), and the results directory
// of `ringcrush fe` for a dynamic scene (DESIGN.md "Machine-readable outputs"):
// summary.json, history.csv, rings.csv, SVG plots, frames/*.vtu + series.pvd.
#pragma once

#include <vector>

#include "compare/measures.hpp"
#include "compare/results_dir.hpp"
#include "compare/run_result.hpp"
#include "compare/scene.hpp"
#include "compare/table_output.hpp"
#include "fe/chain/chain_input.hpp"
#include "fe/dynamics/dynamic_run.hpp"

namespace ringcrush::compare {

// Every scene value the dynamic FE uses. Throws std::invalid_argument for scenes it does not
// cover: static analyses, fe.solver = "static", plane strain, friction ≠ 0.
fe::ChainInput fe_chain_input(const Scene& scene);
fe::DynamicSolverInput fe_dynamic_solver_input(const Scene& scene);

// The scene's FE impact: fe_chain_input + fe_dynamic_solver_input → fe::run_dynamic, with
// `threads` element-loop threads (0: automatic; 1 for timings and for cases run in parallel).
fe::DynamicResult run_scene_dynamic(const Scene& scene, int threads = 0);

// The outer surface of each ring at displacement u (2 per node of `mesh`), ordered by material
// angle from the top apex, ready for compare/measures (surface_offset 0).
std::vector<RingShape> outer_surface_shapes(const fe::ChainMesh& mesh, const Eigen::VectorXd& u);

// Histories, final crush ratio / wrap measures / mode per ring, statistics, and the FE's own
// numbers in `extra` (energy_balance_error and numerical_dissipation of the driver, end
// reason, max PEEQ per ring, what limited the step, time per element-step, contact share).
// Throws std::runtime_error if the result holds a non-finite number (a failed run must be
// reported, never written).
RunResult fe_dynamic_run_result(const Scene& scene, const fe::DynamicResult& result);

// summary.json: compare/run_output's summary_json with the driver's energy_balance_error.
nlohmann::json fe_dynamic_summary(const Scene& scene, const RunResult& run);

// rings.csv: ring, final crush ratio, crush (m), wrapped angle, inverted arc, wrap flag,
// max PEEQ.
CsvTable rings_table(const Scene& scene, const RunResult& run);

// Writes every output of a dynamic FE run into `out` (not committed): summary.json and
// history.csv (compare/run_output), rings.csv, the SVG plots of run_output plus
// crush_per_ring.svg (bars), and frames/*.vtu + series.pvd when outputs.fields and frames.
void write_fe_dynamic_outputs(const Scene& scene, const fe::DynamicResult& result, const RunResult& run,
                              ResultsDir& out);

}  // namespace ringcrush::compare
