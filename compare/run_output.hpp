// RunResult → the stable machine-readable outputs of DESIGN.md "Machine-readable outputs":
// summary.json and history.csv, plus the standard SVG plots. Shared by every model's
// subcommand (hinge, fe): metrics are computed here once, from the RunResult alone.
#pragma once

#include <nlohmann/json.hpp>

#include "compare/results_dir.hpp"
#include "compare/run_result.hpp"
#include "compare/scene.hpp"
#include "compare/table_output.hpp"

namespace ringcrush::compare {

// max over the history of |KE + elastic + plastic + contact + numerical − external − KE0| / KE0,
// KE0 = ½MV² of the scene's impactor (dynamic runs; 0 when there is no impactor).
double energy_balance_error(const RunResult& r, const Scene& scene);
// Largest impactor force; first time the impactor velocity reaches zero (or the model's own
// "arrest_time_s" in extra), −1 if never.
double peak_force(const RunResult& r);
double arrest_time(const RunResult& r);
// Mean crushing force: work of the impactor force over its loading travel / largest travel.
double mean_force(const RunResult& r);
// Energy the rings absorbed: plastic dissipation at the end of the run.
double absorbed_energy(const RunResult& r);

nlohmann::json summary_json(const RunResult& r, const Scene& scene);
CsvTable history_table(const RunResult& r);

// Writes summary.json and history.csv (and, if scene.outputs.plots, the SVG plots:
// crush.svg, crush_final.svg, impactor.svg, force.svg, energy.svg) into `out`. Does not
// commit `out`.
void write_run_result(const RunResult& r, const Scene& scene, ResultsDir& out);
void write_run_plots(const RunResult& r, const Scene& scene, ResultsDir& out);

}  // namespace ringcrush::compare
