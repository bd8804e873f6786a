// The FE as a sweep model (compare/sweep.hpp): `model = "fe"` in a grid file runs each case's
// scene with the static crush or the dynamic impact, as `ringcrush fe` does, so a grid of
// speeds, masses or t/D over the FE writes one results directory per case.
#include "compare/fe_dynamic.hpp"
#include "compare/fe_static.hpp"
#include "compare/sweep.hpp"

namespace ringcrush::compare::cli {
namespace {

void run_fe_case(const Scene& scene, ResultsDir& out) {
  if (scene.analysis.type == AnalysisType::Static) {
    const fe::StaticResult r = fe::run_static(fe_static_input(scene));
    write_fe_static_outputs(scene, r, fe_static_run_result(scene, r), out);
    return;
  }
  fe::ChainInput chain = fe_chain_input(scene);
  chain.threads = 1;  // the sweep already runs one case per core
  const fe::DynamicResult r = fe::run_dynamic(chain, fe_dynamic_solver_input(scene));
  write_fe_dynamic_outputs(scene, r, fe_dynamic_run_result(scene, r), out);
}

const SweepModelRegistration fe_model{"fe", run_fe_case};
}  // namespace
}  // namespace ringcrush::compare::cli
