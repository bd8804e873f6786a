// Level 2 polygon ring against Redwood's hardening curve (issue 7 verification a; THEORY
// §1.4): with the hinge length fitted in hinge/redwood_hinge_length.hpp, one ring crushed
// quasi-statically between plates carries Redwood's load for its α, at N = 48 and 96.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "hinge/polygon_simulation.hpp"
#include "hinge/redwood_hinge_length.hpp"
#include "hinge/ring_laws.hpp"
#include "quasi_static_ring.hpp"

using namespace ringcrush::hinge;

namespace {

const RingSection& section = plates_crush::test30_section;
constexpr double kHardening = 2.224e9;  // E′ of the thesis table (slope)

using Band = plates_crush::LoadBand;  // P / P_Redwood over δ/d ∈ [0.2, 0.5]

// The band of quasi_static_ring.hpp, as the DeRuntz–Hodge check of polygon_ring_test.cpp.
Band redwood_band(int nodes, double alpha, bool fitted) {
  PolygonChainInput in;
  in.nodes_per_ring = nodes;
  in.hardening_modulus_pa = kHardening;
  in.redwood_alpha = alpha;
  in.redwood_fitted_hardening = fitted;
  const auto out = plates_crush::crush_between_plates(in, 1e-4);
  const double d = section.mean_diameter();
  const double P0 = collapse_load(plastic_moment(section, in.yield_stress_pa, SectionState::PlaneStress), d);
  const auto band = plates_crush::load_band(
      out, [&](double delta) { return redwood_load(P0, kHardening, in.yield_stress_pa, alpha, delta, d); });
  EXPECT_GT(band.samples, 100);
  return band;
}

}  // namespace

TEST(PolygonRedwood, FittedHingeLengthFollowsRedwoodAtAlpha2N48) {
  const Band b = redwood_band(48, 2.0, true);
  EXPECT_NEAR(b.mean, 1.0, 0.03) << "range " << b.low << " … " << b.high;
}

TEST(PolygonRedwood, FittedHingeLengthFollowsRedwoodAtAlpha2N96) {
  const Band b = redwood_band(96, 2.0, true);  // the fit scales with the bar length
  EXPECT_NEAR(b.mean, 1.0, 0.03) << "range " << b.low << " … " << b.high;
}

TEST(PolygonRedwood, FittedHingeLengthFollowsRedwoodAtAlpha1And4) {
  for (double alpha : {1.0, 4.0}) {  // α = 4 was not used in the fit
    const Band b = redwood_band(48, alpha, true);
    EXPECT_NEAR(b.mean, 1.0, 0.03) << "α = " << alpha << ", range " << b.low << " … " << b.high;
  }
}

// Without the fit (l_h = α t at every node) the ring is well below Redwood: the reason the
// fit exists (the hinge rotation spreads over several nodes).
TEST(PolygonRedwood, PerNodeAlphaTLawFallsShortOfRedwood) {
  const Band b = redwood_band(48, 2.0, false);
  EXPECT_LT(b.mean, 0.92);
  EXPECT_GT(b.mean, 0.75);
}

TEST(PolygonRedwood, FitRefusesAlphaOutsideItsRangeAndBadBarLength) {
  EXPECT_NEAR(redwood_hinge_length(2.0, 1.0), 2 * 0.119 + 4 * 0.0432, 1e-15);
  EXPECT_THROW(redwood_hinge_length(0.5, 1.0), std::invalid_argument);
  EXPECT_THROW(redwood_hinge_length(4.5, 1.0), std::invalid_argument);
  EXPECT_THROW(redwood_hinge_length(2.0, 0.0), std::invalid_argument);
  PolygonChainInput in;
  in.redwood_alpha = 6.0;
  in.redwood_fitted_hardening = true;
  in.hardening_modulus_pa = kHardening;
  EXPECT_THROW(PolygonChain{in}, std::invalid_argument);
}
