// Parameter sweeps over scenes (DESIGN.md "compare"): a grid of scene overrides, one case per
// directory, idempotent (a finished case is one whose results directory exists, and results
// directories appear atomically), all cores, one tidy sweep.csv.
//
// Grid file (TOML):
//   base_scene = "../scenes/test30_welded.toml"   # relative to the grid file
//   model = "hinge"                                # what each case runs (a registered model)
//   [[axis]]                                       # one table per axis, in order
//   key = "impactor.velocity_m_s"                  # a dotted scene key …
//   values = [15.0, 20.0, 30.0]
//   [[axis]]
//   key = "t_over_D"                               # … or t/D: sets rings.wall_thickness_m
//   values = [0.02, 0.03]
// Cases are the Cartesian product, the first axis varying slowest.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/results_dir.hpp"
#include "compare/scene.hpp"

namespace ringcrush::compare {

struct SweepAxis {
  std::string key;                    // dotted scene key, or "t_over_D"
  std::vector<std::string> values;    // TOML literals, e.g. "15.0", "\"welded\""
};

struct SweepCase {
  int index;
  std::string name;                          // directory name, e.g. "case_0007"
  std::vector<std::string> values;           // one per axis, as written in the grid
  std::string scene_toml;                    // the case's full scene text
};

struct SweepGrid {
  std::filesystem::path source;
  std::filesystem::path base_scene;
  std::string model;
  std::vector<SweepAxis> axes;
  std::vector<SweepCase> cases;              // every case's scene is validated on load
};

// Parses the grid, expands the cases and validates every case's scene (a bad combination
// fails here, naming the case, before anything runs). Throws SceneError.
SweepGrid load_sweep_grid(const std::filesystem::path& grid_file);

// Runs one case, writing its outputs into `out` (the sweep commits it on return).
using SweepCaseRunner = std::function<void(const Scene& scene, ResultsDir& out)>;

// Models a sweep can run, by name; runners register themselves (see hinge_levels.hpp for
// the same pattern).
std::map<std::string, SweepCaseRunner>& sweep_model_registry();
struct SweepModelRegistration {
  SweepModelRegistration(const std::string& name, SweepCaseRunner runner) {
    sweep_model_registry()[name] = std::move(runner);
  }
};

struct SweepOptions {
  int threads = 0;           // 0: all cores
  int rank = 0, ranks = 1;   // this process's share: cases with index % ranks == rank
  bool progress = true;      // a progress line on stderr
};

struct SweepReport {
  int total = 0, run = 0, skipped = 0, failed = 0;
  std::vector<std::string> failures;   // "case_0003: reason"
  double wall_time_s = 0.0;
};

// Runs the unfinished cases of this rank's share into `out_dir/<case name>`, writing each
// case's scene.toml beside its results. A failing case is recorded (its message in
// out_dir/<case>.failed) and does not stop the others.
SweepReport run_sweep(const SweepGrid& grid, const std::filesystem::path& out_dir,
                      const SweepCaseRunner& runner, const SweepOptions& options = {});

// Gathers every finished case's summary.json into one table: case, the axis values, then
// the summary's numbers (arrays flattened to name_1, name_2, …; booleans as 0/1).
// Returns the number of cases merged; unfinished cases are left out and counted in `missing`.
int merge_sweep(const SweepGrid& grid, const std::filesystem::path& out_dir,
                const std::filesystem::path& csv_file, int* missing = nullptr);

}  // namespace ringcrush::compare
