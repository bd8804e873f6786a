// Models a sweep can run (compare/sweep.hpp): each case's scene in, its results directory out.
#include <fmt/format.h>

#include "compare/compare_run.hpp"
#include "compare/hinge_levels.hpp"
#include "compare/run_output.hpp"
#include "compare/sweep.hpp"

namespace ringcrush::compare::cli {
namespace {

// The hinge model at the scene's [hinge] level and settings.
void run_hinge_case(const Scene& scene, ResultsDir& out) {
  const auto& levels = hinge_level_registry();
  const auto it = levels.find(scene.hinge.level);
  if (it == levels.end())
    throw std::invalid_argument(fmt::format("hinge level {} is not available", scene.hinge.level));
  const HingeRunOptions options{scene.hinge.level, scene.hinge.integrator,
                                scene.hinge.relative_tolerance, scene.hinge.absolute_tolerance};
  write_run_result(it->second(scene, options), scene, out);
}

const SweepModelRegistration hinge{"hinge", run_hinge_case};

// Both, with the agreement verdicts (compare/compare_run.hpp).
void run_compare_case(const Scene& scene, ResultsDir& out) { (void)run_compare(scene, {}, out); }

const SweepModelRegistration compare_model{"compare", run_compare_case};

}  // namespace
}  // namespace ringcrush::compare::cli
