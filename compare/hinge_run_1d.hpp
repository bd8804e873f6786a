// Scene → hinge model inputs → RunResult for the one-dimensional hinge levels (THEORY §4.2):
//   "0"      Level 0, elastic–plastic ring springs with lumped masses (hinge::simulate_level0)
//   "1"      Level 1, rigid–plastic DeRuntz–Hodge/Redwood rings with J(φ) (simulate_level1)
//   "shock"  the Reid–Bell–Barr r-p-p-l plastic shock model (hinge::integrate_shock), with
//            its closed form and discrete sequential counterpart in the summary.
// The ring backbone is Redwood's with the scene's α and the slope E′ of the first hardening
// segment of the material table (a single-point table gives DeRuntz–Hodge).
#pragma once

#include "compare/hinge_levels.hpp"
#include "hinge/chain_1d.hpp"
#include "hinge/shock_model.hpp"

namespace ringcrush::compare {

// Inner-wall contact stiffness past lock-up, in units of the ring's elastic stiffness.
inline constexpr double level0_lock_stiffness_scale = 50.0;

hinge::RingLaw ring_law(const Scene& scene);
hinge::ChainInput chain_input(const Scene& scene);
hinge::HybridOptions hybrid_options(const Scene& scene, const HingeRunOptions& options);

RunResult run_hinge_level0(const Scene& scene, const HingeRunOptions& options);
RunResult run_hinge_level1(const Scene& scene, const HingeRunOptions& options);
RunResult run_hinge_shock(const Scene& scene, const HingeRunOptions& options);

}  // namespace ringcrush::compare
