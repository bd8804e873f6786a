// Scene → hinge Level 3 (THEORY §4.5; hinge/level3_mechanism.hpp) → RunResult: the thesis's
// few-hinge mechanisms (uniform DeRuntz–Hodge; wrap of the lower arc over the next ring,
// hinges C, F, B; bottom flattening of the ring underneath, hinges E, C, B) in a massless
// rigid-plastic chain with mode selection by least load at each event. Per ring: crush,
// wrapped angle and inverted arc (compare::measure_wrap on the mechanism's half-ring mean
// lines), wrap flag, mechanism, hinge map (extra["hinge_map"]).
#pragma once

#include "compare/hinge_levels.hpp"
#include "hinge/level3_mechanism.hpp"

namespace ringcrush::compare {

struct Level3RunOptions {
  double theta_f_deg = -1.0;  // < 0: θ_F of least wrap onset load
  bool record_history = true;
};

hinge::Level3Input level3_input(const Scene& scene, const Level3RunOptions& extra = {});
RunResult run_hinge_level3(const Scene& scene, const HingeRunOptions& options,
                           const Level3RunOptions& extra = {});

}  // namespace ringcrush::compare
