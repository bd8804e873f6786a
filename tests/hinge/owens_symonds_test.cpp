// Owens–Symonds free ring under a concentrated dynamic force (THEORY §2): the onset
// threshold from the shear-free hinge condition, its static admissibility, the same value
// from the virtual power of the rigid-body d'Alembert loads (upper bound minimised), and the
// mechanism phase: hinge angle continuous at onset and moving toward the load as F grows,
// energy balance of a force pulse on both integrators.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "chain_fixtures.hpp"
#include "hinge/owens_symonds.hpp"

using namespace ringcrush::hinge;

namespace {

FreeRing test30_free_ring() {
  const auto law = ringcrush::hinge::testing::test30_ring();
  return {0.5 * law.mean_diameter(), law.plastic_moment_nm, law.mass_kg};
}

TEST(OwensSymonds, OnsetThresholdFromTheShearFreeCondition) {
  const auto ring = test30_free_ring();
  const auto on = owens_symonds_onset(ring);
  // tan θ_E = π − θ_E
  EXPECT_NEAR(std::tan(on.hinge_angle_rad), std::numbers::pi - on.hinge_angle_rad, 1e-12);
  EXPECT_NEAR(on.hinge_angle_rad, 1.112835, 1e-6);  // 63.76°, between A and the side C
  EXPECT_NEAR(on.force_n * ring.mean_radius_m / ring.plastic_moment_nm, 6.90572, 1e-5);
  // Statically admissible: |M| ≤ M0 everywhere, = M0 at A, E and B.
  EXPECT_LE(on.max_moment_ratio, 1.0 + 1e-12);
  EXPECT_NEAR(onset_moment_ratio(ring, 0.0), -1.0, 1e-12);
  EXPECT_NEAR(onset_moment_ratio(ring, on.hinge_angle_rad), 1.0, 1e-12);
  EXPECT_NEAR(onset_moment_ratio(ring, std::numbers::pi), -1.0, 1e-12);
  // The free ring needs more than the diametral collapse load P0 = 4M0/R between plates.
  EXPECT_GT(on.force_n, 1.7 * 4 * ring.plastic_moment_nm / ring.mean_radius_m);
}

TEST(OwensSymonds, VirtualPowerOfTheRigidBodyPhaseGivesTheSameLimitLoad) {
  const auto ring = test30_free_ring();
  const auto on = owens_symonds_onset(ring);
  // Every mechanism {A, ±θ, B} is an upper bound; the least is at θ_E and equals F_c.
  EXPECT_NEAR(mechanism_collapse_force(ring, on.hinge_angle_rad) / on.force_n, 1.0, 1e-8);
  for (double theta : {0.5, 0.8, 1.0, 1.25, 1.5, 2.0, 2.5})
    EXPECT_GT(mechanism_collapse_force(ring, theta), on.force_n) << theta;
  // and the equilibrium expression 4M0/(R(1 − θ/π) sin θ) for any θ
  for (double theta : {0.6, 1.3, 2.2})
    EXPECT_NEAR(mechanism_collapse_force(ring, theta) * ring.mean_radius_m * (1 - theta / std::numbers::pi) *
                    std::sin(theta) / (4 * ring.plastic_moment_nm),
                1.0, 1e-8);
}

TEST(OwensSymonds, MechanismHingeMovesTowardTheLoadAsTheForceGrows) {
  const auto ring = test30_free_ring();
  const auto on = owens_symonds_onset(ring);
  const auto near = owens_symonds_mechanism(ring, 1.0001 * on.force_n);
  EXPECT_NEAR(near.hinge_angle_rad, on.hinge_angle_rad, 2e-3);  // continuous at onset
  EXPECT_NEAR(near.translation_acceleration * ring.mass_kg / (1.0001 * on.force_n), 1.0, 1e-2);
  double previous = near.hinge_angle_rad;
  for (double k : {1.5, 2.0, 4.0}) {
    const auto m = owens_symonds_mechanism(ring, k * on.force_n);
    EXPECT_LT(m.hinge_angle_rad, previous) << k;
    EXPECT_GT(m.rotation_acceleration, 0.0);
    previous = m.hinge_angle_rad;
  }
  EXPECT_THROW(owens_symonds_mechanism(ring, 0.9 * on.force_n), std::invalid_argument);
}

class OwensSymondsPulse : public ::testing::TestWithParam<HybridIntegrator> {};

TEST_P(OwensSymondsPulse, WorkGoesIntoHingesAndRigidBodyMotion) {
  const auto ring = test30_free_ring();
  const auto on = owens_symonds_onset(ring);
  const double tau = 20e-6;
  const auto p = owens_symonds_pulse(ring, 2.0 * on.force_n, tau, ringcrush::hinge::testing::tight(GetParam()));
  EXPECT_LT(p.energy_balance_error(), 1e-8);
  EXPECT_GT(p.deformation_end_s, tau);  // the mechanism runs on after the pulse
  EXPECT_GT(p.final_rotation_rad, 0.0);
  EXPECT_LT(p.final_rotation_rad, 0.2);  // small deflection
  // After deformation the ring moves as a rigid body with the whole impulse.
  EXPECT_NEAR(p.final_velocity_m_s * ring.mass_kg / (2.0 * on.force_n * tau), 1.0, 1e-6);
  EXPECT_NEAR(p.kinetic_j, 0.5 * ring.mass_kg * p.final_velocity_m_s * p.final_velocity_m_s, 1e-9 * p.kinetic_j);
}

INSTANTIATE_TEST_SUITE_P(BothIntegrators, OwensSymondsPulse,
                         ::testing::Values(HybridIntegrator::Ida, HybridIntegrator::Odeint),
                         [](const auto& param_info) { return to_string(param_info.param); });

}  // namespace
