// The central difference's stable step visits only the nodes the last evaluation gave contact
// rows and one node of each remaining class (hinge/polygon_stable_step.cpp): the same bound, to
// the bit, as the scan of every node (stable_step_all_nodes), for every mask of stiffness
// terms — on rings pushed into each other (one flattened onto its own inner wall), welded,
// free and plated, half model and full rings, explicit and implicit dampers, with and without
// mass damping; and at rest, without contact rows, where the node classes alone set it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "hinge/polygon_chain.hpp"

using namespace ringcrush::hinge;

namespace {

PolygonChainInput pressed_rings(bool half, PolygonJoint joint) {
  PolygonChainInput in;
  in.rings = 3;
  in.half_symmetry = half;
  in.nodes_per_ring = 48;
  in.joint = joint;
  in.pitch_m = in.outer_diameter_m - 0.6 * in.wall_thickness_m;  // neighbours overlap by 0.6 t
  if (joint == PolygonJoint::Plates) {
    in.plate_mass_kg = 0.05;
    in.plate_thickness_m = 0.002;
    in.pitch_m = 0.0;
  }
  in.impactor_velocity_m_s = 20.0;
  in.redwood_alpha = 2.0;
  in.membrane_damping_ratio = 0.5;
  in.hinge_damping_ratio = 0.5;
  return in;
}

// Ring 1 flattened to 3 % of its height (its inner walls in contact), the whole chain moved
// by up to 0.4 t per coordinate so that the plates and the impactor press on the rings too;
// velocities at random (closing and opening rates).
std::vector<double> pressed_state(const PolygonChain& chain, std::mt19937& rng) {
  std::vector<double> y = chain.initial_state();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double t = chain.input().wall_thickness_m;
  const double c1 = 0.5 * (y[chain.node_offset(1, 0) + 1] + y[chain.node_offset(1, chain.independent_nodes() - 1) + 1]);
  const bool half = chain.input().half_symmetry;
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < chain.independent_nodes(); ++j) {
      const auto o = chain.node_offset(r, j);
      if (r == 1) y[o + 1] = c1 + 0.03 * (y[o + 1] - c1);
      const bool axis = half && (j == 0 || j == chain.independent_nodes() - 1);
      if (!axis) y[o] += 0.4 * t * u(rng);
      y[o + 1] += 0.4 * t * u(rng);
      y[o + 2] = axis ? 0.0 : 3.0 * u(rng);
      y[o + 3] = 3.0 * u(rng);
    }
  // The impactor's face pushed 0.3 t into ring 0.
  y[chain.body_offset(0)] -= 0.3 * t;
  return y;
}

void expect_every_mask_equal(PolygonChain& chain, const char* what) {
  using T = PolygonChain::StepTerm;
  for (unsigned terms = 0; terms <= T::kAllStiffness; ++terms) {
    const double listed = chain.stable_step(terms), scanned = chain.stable_step_all_nodes(terms);
    EXPECT_EQ(listed, scanned) << what << ", terms " << terms;
  }
}

void check(bool half, PolygonJoint joint, unsigned seed) {
  for (const bool implicit : {true, false})
    for (const double mass_damping : {0.0, 300.0}) {
      auto in = pressed_rings(half, joint);
      in.mass_damping_per_s = mass_damping;
      {  // The rings at rest 2 t apart (the welded ties stretched): no contact rows, so the
         // node classes alone set the bound (the tied nodes' in the welded chain).
        auto resting = in;
        resting.pitch_m = in.outer_diameter_m + 2.0 * in.wall_thickness_m;
        PolygonChain chain(resting);
        chain.set_implicit_ring_dampers(implicit);
        std::vector<double> y = chain.initial_state(), dydt(y.size());
        chain.rhs(0.0, y.data(), dydt.data());
        ASSERT_EQ(chain.stable_step(), chain.stable_step(PolygonChain::kAllStiffness & ~PolygonChain::kContacts));
        expect_every_mask_equal(chain, "at rest");
      }
      PolygonChain chain(in);
      chain.set_implicit_ring_dampers(implicit);
      std::vector<double> y = chain.initial_state(), dydt(y.size());
      chain.rhs(0.0, y.data(), dydt.data());
      expect_every_mask_equal(chain, "initial state (neighbours overlapping)");
      std::mt19937 rng(seed);
      for (int k = 0; k < 4; ++k) {
        y = pressed_state(chain, rng);
        chain.rhs(0.0, y.data(), dydt.data());
        // The state is one with contact rows: the contacts shorten the bound.
        ASSERT_LT(chain.stable_step(), chain.stable_step(PolygonChain::kAllStiffness & ~PolygonChain::kContacts));
        expect_every_mask_equal(chain, "pressed state");
      }
    }
}

}  // namespace

TEST(PolygonStableStepNodes, ListedNodesEqualTheScanHalfModel) {
  check(true, PolygonJoint::Free, 21u);
  check(true, PolygonJoint::Welded, 22u);
  check(true, PolygonJoint::Plates, 23u);
}

TEST(PolygonStableStepNodes, ListedNodesEqualTheScanFullRings) {
  check(false, PolygonJoint::Free, 24u);
  check(false, PolygonJoint::Welded, 25u);
}
