// Run time against error (issue 8 item 6, `ringcrush bench`): the error of one run against a
// reference run of the same model, the rows of bench.csv, the work–precision diagram and the
// terminal summary. Every number comes from the RunResults through compare/measures and
// compare/run_output, applied to both runs alike.
//
// The error measures (documented in README "Run time against error"):
//  - crush:  max over the rings of |c_i − c_i,ref|, c_i the final crush ratio δ_i/D of ring i
//            (absolute, in crush ratio; the headline "error" of bench.csv and the diagram);
//  - energy: |E − E_ref| / |E_ref|, E the energy the rings absorbed (plastic dissipation at
//            the end of the run, run_output absorbed_energy);
//  - peak force: |F − F_ref| / |F_ref|, F the peak of the impactor force averaged over
//            0.2 ms (run_output peak_mean_force; the agreement verdict's window), or the peak
//            plate force of a static run.
// A relative error whose reference is 0 is 0 when the run's value is 0 too and 1 otherwise.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "compare/run_result.hpp"

namespace ringcrush::compare {

struct RunErrors {
  double crush = 0;       // max |Δ crush ratio| over the rings
  double energy = 0;      // relative absorbed-energy error
  double peak_force = 0;  // relative peak-force error
};

// Throws std::invalid_argument when the runs have different ring counts or no final crush.
RunErrors run_errors(const RunResult& run, const RunResult& reference);

// The measures reported beside the errors.
struct RunMeasures {
  std::vector<double> crush_ratio;
  double absorbed_energy_j = 0;
  double peak_force_n = 0;
  double alternation_index = 0;
  long steps = 0;
};
RunMeasures run_measures(const RunResult& run);

// One row of bench.csv.
struct BenchRow {
  std::string group;          // "work_precision" | "outputs" | "symmetry"
  std::string model;          // "fe" | "hinge"
  std::string scene;
  std::string level_or_mesh;  // "16x1 half" (FE elements per half ring × through) | "level 1"
  std::string integrator;     // "hht" | "explicit" | "static" | "ida" | "odeint"
  std::string control;        // "haftol_N" | "safety" | "rtol" | "all fields" | "no fields" | "half" | "full"
  std::optional<double> tolerance;  // the control's value (haftol in N, safety factor, rtol)
  bool reference = false;     // the run the others of its model (and group) are measured against
  int repeats = 1;
  double wall_s = 0, cpu_s = 0;  // medians over the repeats
  std::optional<double> bytes_written;
  RunErrors error;                       // against the reference
  std::optional<RunErrors> model_error;  // hinge rows: against the finest FE run
  RunMeasures measures;
};

// Series label of the diagram: "fe hht", "hinge level 1 odeint", ...
std::string series_label(const BenchRow& row);

// bench.csv: one row per run; non-applicable cells are empty. Throws std::runtime_error on a
// non-finite number (a failed run must be reported, never written).
void write_bench_csv(const std::filesystem::path& file, const std::vector<BenchRow>& rows);

// Work–precision diagram of the "work_precision" rows: log crush error against log CPU time,
// one series per model/integrator (and hinge level); the references (error 0) cannot be drawn
// on a log axis and are left out. `model_error` = true: the hinge rows' model error against
// the finest FE instead (FE rows keep their error against the FE reference).
std::string render_work_precision(const std::vector<BenchRow>& rows, const std::string& title,
                                  bool model_error = false);

// The table printed on the terminal (and quoted in the README).
std::string bench_table(const std::vector<BenchRow>& rows);

}  // namespace ringcrush::compare
