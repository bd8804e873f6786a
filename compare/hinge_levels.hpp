// The hinge model's levels (THEORY §4.2) behind `ringcrush hinge --level L`. Each level's
// runner turns a Scene into a RunResult; runners register themselves from files in
// compare/cli/ (static registration in the executable), so levels are added independently.
#pragma once

#include <functional>
#include <map>
#include <string>

#include "compare/run_result.hpp"
#include "compare/scene.hpp"

namespace ringcrush::compare {

struct HingeRunOptions {
  std::string level;                  // "0", "1", "2", "3", "shock"
  HingeIntegrator integrator = HingeIntegrator::Ida;
  double relative_tolerance = 1e-8;
  double absolute_tolerance = 1e-10;
};

using HingeLevelRunner = std::function<RunResult(const Scene&, const HingeRunOptions&)>;

std::map<std::string, HingeLevelRunner>& hinge_level_registry();

struct HingeLevelRegistration {
  HingeLevelRegistration(const std::string& level, HingeLevelRunner runner) {
    hinge_level_registry()[level] = std::move(runner);
  }
};

}  // namespace ringcrush::compare
