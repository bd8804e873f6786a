// The FE static crush seen from compare/: Scene → fe::FeInput, fe::StaticResult → RunResult,
// and the results directory of `ringcrush fe` for a static scene (DESIGN.md "Machine-readable
// outputs"): summary.json, history.csv, load_deflection.svg, frames/*.vtu + series.pvd.
#pragma once

#include <vector>

#include "compare/results_dir.hpp"
#include "compare/run_result.hpp"
#include "compare/scene.hpp"
#include "fe/fe_input.hpp"
#include "fe/time/static_driver.hpp"

namespace ringcrush::compare {

// Throws std::invalid_argument for scenes the FE static model does not cover (more than
// one ring, plane strain). Coulomb friction acts at the plates only.
fe::FeInput fe_static_input(const Scene& scene);

RunResult fe_static_run_result(const Scene& scene, const fe::StaticResult& r);

// Redwood's curve fitted to a load–deflection history: the α in [lo, hi] (golden-section
// on the RMS relative deviation over δ/d ∈ [from, to]) and the largest relative deviation
// there. Closed forms from hinge/ring_laws (never re-implemented here).
struct RedwoodFit {
  double alpha = 0;
  double max_relative_deviation = 0;
  double rms_relative_deviation = 0;
  double min_ratio_to_deruntz_hodge = 0;  // min P_FE / P_DH over the same range
};
RedwoodFit fit_redwood(const Scene& scene, const std::vector<double>& deflection_m,
                       const std::vector<double>& force_n, double from = 0.1, double to = 0.7,
                       double lo = 0.5, double hi = 4.0);

// Writes every output of a static FE run into `out` (not committed).
void write_fe_static_outputs(const Scene& scene, const fe::StaticResult& r, const RunResult& run,
                             ResultsDir& out);

}  // namespace ringcrush::compare
