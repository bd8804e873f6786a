// One comparison run (issue 8 item 2), shared by `ringcrush compare` and the sweep model
// "compare": the hinge model at the scene's [hinge] level and the FE at its [fe] settings on
// the same scene, their agreement, and the results directory:
//   summary.json (model "compare", "agreement"), report.html, crush_compare.svg,
//   fe/ (the FE run's own results directory), hinge/ (the hinge run's).
// The FE result is cached (compare/result_cache.hpp) under the canonical scene, the FE
// options and the code identity, so a rerun is instant and a changed scene or build is
// never served stale.
#pragma once

#include <functional>
#include <string>

#include "compare/agreement.hpp"
#include "compare/results_dir.hpp"
#include "compare/run_result.hpp"
#include "compare/scene.hpp"
#include "fe/dynamics/dynamic_run.hpp"

namespace ringcrush::compare {

struct CompareRunOptions {
  bool use_cache = true;
  AgreementThresholds thresholds;
  std::function<void(const fe::DynamicProgress&)> fe_progress;  // optional
};

struct CompareOutcome {
  RunResult fe, hinge;
  Agreement agreement;
  double fe_wall_time_s = 0;     // of this call (instant when cached)
  double hinge_wall_time_s = 0;
  bool fe_from_cache = false;
};

// Throws std::invalid_argument for scenes that are not dynamic impacts or that either model
// refuses (before running anything), SolveFailure / std::runtime_error when a run fails.
// Writes into `out` without committing it.
CompareOutcome run_compare(const Scene& scene, const CompareRunOptions& options, ResultsDir& out);

}  // namespace ringcrush::compare
