// HRZ lumped mass of CPS8 (issue 4 item 5): positive at every node where the row sums of the
// consistent mass are not (−1/12 of the element mass at each corner of a rectangle), the
// HRZ corner : mid-side split of a parallelogram (3/76 : 16/76, from ∫N_c² : ∫N_m² =
// 2/15 : 32/45), and the nodal masses of a chain adding up to ρ·A·width.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/lumped_mass.hpp"

using namespace ringcrush::fe;

namespace {
ElementCoords parallelogram(double a, double b, double shear) {
  ElementCoords x;
  const double c[8][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  for (int k = 0; k < 8; ++k) {
    x(k, 0) = a * c[k][0] + shear * c[k][1];
    x(k, 1) = b * c[k][1];
  }
  return x;
}

ChainInput small_chain(int rings, bool half) {
  ChainInput in;
  in.rings = rings;
  in.mesh.elements_around = 8;
  in.mesh.half_ring = half;
  in.pitch_m = 2 * in.ring.outer_radius_m;
  return in;
}
}  // namespace

TEST(LumpedMass, ParallelogramCornerAndMidSideShares) {
  const double rho = 7850, t = 0.0125;
  const auto x = parallelogram(0.003, 0.001, 0.0007);
  const double mass = rho * t * (2 * 0.003) * (2 * 0.001);
  const auto m = hrz_lumped_mass(x, rho, t);
  double sum = 0;
  for (int a = 0; a < 8; ++a) {
    EXPECT_GT(m[a], 0.0);
    sum += m[a];
  }
  EXPECT_NEAR(sum, mass, 1e-14 * mass);
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(m[a], 3.0 / 76.0 * mass, 1e-13 * mass) << "corner " << a;
  for (int a = 4; a < 8; ++a) EXPECT_NEAR(m[a], 16.0 / 76.0 * mass, 1e-13 * mass) << "mid-side " << a;
}

TEST(LumpedMass, DegenerateElementIsAnError) {
  ElementCoords x = ElementCoords::Zero();
  EXPECT_THROW(hrz_lumped_mass(x, 7850, 0.01), std::invalid_argument);
}

TEST(LumpedMass, ChainMassIsRingAreaTimesWidthTimesDensity) {
  for (bool half : {true, false}) {
    double previous_error = 0;
    for (int around : {8, 16}) {
      ChainInput in = small_chain(3, half);
      in.mesh.elements_around = around;
      const ChainModel model(in);
      const auto& m = model.lumped_mass();
      const auto& mesh = model.mesh();
      double rings = 0;
      for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
        EXPECT_GT(m(2 * n), 0.0);
        EXPECT_EQ(m(2 * n), m(2 * n + 1));
        if (static_cast<int>(n) != mesh.impactor_node) rings += m(2 * n);
      }
      const double pi = std::numbers::pi;
      const double ro = in.ring.outer_radius_m, ri = in.ring.inner_radius_m;
      const double exact = in.rings * in.density_kg_m3 * in.ring.width_m * pi * (ro * ro - ri * ri) / model.symmetry_factor();
      // The quadratic edges approximate the arcs (area error O(Δφ⁴)): ~5e-5 with 8 elements
      // per half ring, 16× less with 16.
      const double error = std::abs(rings - exact) / exact;
      EXPECT_LT(error, 1e-4) << (half ? "half" : "full") << around;
      if (previous_error > 0) {
        EXPECT_LT(error, previous_error / 10) << (half ? "half" : "full");
      }
      previous_error = error;
      EXPECT_NEAR(m(2 * mesh.impactor_node + 1), in.impactor_mass_kg / model.symmetry_factor(), 1e-15);
    }
  }
}
