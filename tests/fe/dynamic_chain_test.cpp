// The dynamic drivers on the ChainModel (issue 4 verification a, b, d; cheap versions: 12
// elements per half ring, one or two rings, fractions of a millisecond):
//  a. free flight: a ring translating at constant speed keeps its momentum to 1e-10 and its
//     stress at zero, both integrators;
//  d. two elastic rings colliding head-on conserve momentum to 1e-8, both integrators;
//  b. the energy balance of an impact on a coarse chain (run_dynamic): explicit < 1 %, HHT's
//     numerical dissipation reported, ≥ 0 and < 3 %.
#include <gtest/gtest.h>

#include <cmath>

#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/dynamic_run.hpp"
#include "fe/dynamics/explicit_driver.hpp"
#include "fe/dynamics/hht_driver.hpp"
#include "fe/time/static_driver.hpp"
#include "rings_in_motion.hpp"

namespace ringcrush::fe {
namespace {

using test_support::RingsInMotion;

ChainInput coarse(int rings, JointKind joints) {
  ChainInput in;
  in.rings = rings;
  in.joints = joints;
  in.mesh.elements_around = 12;
  in.mesh.grading = 1.0;
  in.density_kg_m3 = 8410;
  in.pitch_m = 2 * in.ring.outer_radius_m;
  return in;
}

// Elastic rings: the yield stress is out of reach.
void elastic(ChainInput& in) { in.material.hardening = {{1e12, 0.0}}; }

double momentum_y(const DynamicSystem& s, const Eigen::VectorXd& v) {
  double p = 0;
  for (int d = 1; d < s.dofs(); d += 2) p += s.lumped_mass()(d) * v(d);
  return p;
}

double ring_mass(const ChainModel& m, int ring) {
  const auto& mesh = m.mesh();
  std::vector<char> seen(mesh.nodes.size(), 0);
  double mass = 0;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e)
    if (mesh.element_ring[e] == ring)
      for (int n : mesh.elements[e])
        if (!seen[static_cast<std::size_t>(n)]) {
          seen[static_cast<std::size_t>(n)] = 1;
          mass += m.lumped_mass()(2 * n + 1);
        }
  return mass;
}

double ring_momentum(const ChainModel& m, int ring, const Eigen::VectorXd& v) {
  const auto& mesh = m.mesh();
  std::vector<char> seen(mesh.nodes.size(), 0);
  double p = 0;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e)
    if (mesh.element_ring[e] == ring)
      for (int n : mesh.elements[e])
        if (!seen[static_cast<std::size_t>(n)]) {
          seen[static_cast<std::size_t>(n)] = 1;
          p += m.lumped_mass()(2 * n + 1) * v(2 * n + 1);
        }
  return p;
}

HhtOptions hht_for_momentum() {
  HhtOptions o;
  o.initial_step_s = 2e-7;
  o.max_step_s = 2e-6;
  o.haftol_n = 1e3;
  o.ptol_n = 1e-7;  // Σ residual bounds the momentum error per step (Σ f = 0 exactly)
  o.max_iterations = 15;
  return o;
}

template <class Driver>
void free_flight(Driver& d, ChainModel& model, const DynamicSystem& sys, double end) {
  const double p0 = momentum_y(sys, d.velocity());
  ASSERT_GT(std::abs(p0), 0.0);
  double worst = 0;
  while (d.time() < end * (1 - 1e-12)) {
    d.step(end);
    worst = std::max(worst, std::abs(momentum_y(sys, d.velocity()) - p0));
  }
  EXPECT_LT(worst, 1e-10 * std::abs(p0));
  double mises = 0;
  for (const auto& f : model.element_fields()) mises = std::max(mises, f.mises);
  EXPECT_LT(mises, 1e-9 * 273e6);  // zero to round-off (relative to the yield stress)
  EXPECT_EQ(model.contact_forces().active, 0);
  // Rigid translation: every ring node has moved by v t.
  const int node = model.mesh().ring_outer_nodes[0][0];
  EXPECT_NEAR(d.displacement()(2 * node + 1), -5.0 * end, 1e-9);
}

ChainInput single_ring_flying() {
  ChainInput in = coarse(1, JointKind::Free);
  in.impactor_velocity_m_s = 0;
  in.fixed_target = false;
  return in;
}

TEST(DynamicChain, FreeFlightExplicit) {
  ChainInput in = single_ring_flying();
  ChainModel model(in);
  RingsInMotion sys(model, {-5.0});  // away from the resting impactor
  ExplicitDriver d(sys, ExplicitOptions{});
  free_flight(d, model, sys, 2e-4);
}

TEST(DynamicChain, FreeFlightHht) {
  ChainInput in = single_ring_flying();
  ChainModel model(in);
  RingsInMotion sys(model, {-5.0});
  HhtDriver d(sys, hht_for_momentum());
  free_flight(d, model, sys, 2e-4);
  EXPECT_EQ(d.rejected_steps(), 0);
}

// Two elastic rings 1 mm apart closing at 20 m/s: they meet at 50 µs, bounce, separate.
ChainInput head_on() {
  ChainInput in = coarse(2, JointKind::Free);
  elastic(in);
  in.pitch_m = 2 * in.ring.outer_radius_m + 1e-3;
  in.impactor_velocity_m_s = 0;
  in.fixed_target = false;
  return in;
}

template <class Driver>
void collide(Driver& d, ChainModel& model, const DynamicSystem& sys) {
  const double scale = ring_mass(model, 0) * 10.0;  // one ring's momentum
  const double p0 = momentum_y(sys, d.velocity());
  double worst = 0, peak = 0;
  const double end = 1.6e-4;
  while (d.time() < end * (1 - 1e-12)) {
    d.step(end);
    worst = std::max(worst, std::abs(momentum_y(sys, d.velocity()) - p0));
    peak = std::max(peak, model.contact_forces().ring_ring_n);
  }
  EXPECT_GT(peak, 100.0);  // they did collide (N, model)
  EXPECT_LT(worst, 1e-8 * scale);
  // The collision has taken a good part of ring 1's momentum (−10 m/s × its mass before).
  EXPECT_GT(ring_momentum(model, 0, d.velocity()), -0.7 * scale);
}

TEST(DynamicChain, HeadOnCollisionConservesMomentumExplicit) {
  ChainInput in = head_on();
  ChainModel model(in);
  RingsInMotion sys(model, {-10.0, 10.0});
  ExplicitDriver d(sys, ExplicitOptions{});
  int active = 0;
  const double p0 = momentum_y(sys, d.velocity());
  double worst = 0, peak = 0;
  const double scale = ring_mass(model, 0) * 10.0, end = 1.6e-4;
  while (d.time() < end * (1 - 1e-12)) {
    d.step(end);
    if (model.contact_forces().active != active) {
      active = model.contact_forces().active;
      d.request_stable_step();
    }
    worst = std::max(worst, std::abs(momentum_y(sys, d.velocity()) - p0));
    peak = std::max(peak, model.contact_forces().ring_ring_n);
  }
  EXPECT_GT(peak, 100.0);
  EXPECT_LT(worst, 1e-8 * scale);
  EXPECT_GT(ring_momentum(model, 0, d.velocity()), -0.7 * scale);
  EXPECT_LT(d.energy().relative_balance_error(), 0.01);
}

TEST(DynamicChain, HeadOnCollisionConservesMomentumHht) {
  ChainInput in = head_on();
  ChainModel model(in);
  RingsInMotion sys(model, {-10.0, 10.0});
  HhtDriver d(sys, hht_for_momentum());
  collide(d, model, sys);
}

// 0.128 kg (half model: the scene's 0.256 kg) at 30 m/s on two welded rings, 0.2 ms.
ChainInput coarse_impact() {
  ChainInput in = coarse(2, JointKind::Welded);
  in.impactor_mass_kg = 0.256;
  in.impactor_velocity_m_s = 30;
  return in;
}

TEST(DynamicChain, EnergyBalanceOfAnImpactExplicit) {
  DynamicSolverInput s;
  s.scheme = DynamicScheme::Explicit;
  s.end_time_s = 2e-4;
  s.frames = 4;
  const DynamicResult r = run_dynamic(coarse_impact(), s);
  ASSERT_GE(r.history.size(), 3u);
  EXPECT_EQ(r.end_reason, "end_time");
  EXPECT_NEAR(r.initial_kinetic_j, 0.5 * 0.256 * 30 * 30, 1e-9);
  EXPECT_LT(r.energy_balance_error, 0.01);
  EXPECT_LT(std::abs(r.numerical_dissipation), 0.01);
  // The impact did something: the impactor slowed and ring 1 crushed.
  EXPECT_LT(r.history.back().impactor_velocity_m_s, 29.0);
  EXPECT_GT(r.history.back().ring_crush_m[0], 1e-4);
  EXPECT_GT(r.history.back().plastic_j, 0.0);
  EXPECT_GE(r.frames.size(), 4u);
  EXPECT_LE(r.frames.size(), 9u);
  EXPECT_DOUBLE_EQ(r.history.front().time_s, 0.0);
  EXPECT_NEAR(r.history.back().time_s, 2e-4, 1e-12);
  for (const auto& row : r.history) ASSERT_TRUE(std::isfinite(row.kinetic_j + row.numerical_j + row.impactor_force_n));
  EXPECT_GT(r.statistics.steps, 100);
  EXPECT_FALSE(r.statistics.step_limited_by.empty());
}

TEST(DynamicChain, NumericalDissipationOfAnImpactHht) {
  DynamicSolverInput s;
  s.scheme = DynamicScheme::Hht;
  s.end_time_s = 2e-4;
  s.frames = 0;
  const DynamicResult r = run_dynamic(coarse_impact(), s);
  EXPECT_EQ(r.end_reason, "end_time");
  EXPECT_LT(r.energy_balance_error, 0.01);
  EXPECT_GE(r.numerical_dissipation, -1e-3);
  EXPECT_LT(r.numerical_dissipation, 0.03);
  EXPECT_GT(r.statistics.newton_iterations, r.statistics.steps);
  EXPECT_LT(r.history.back().impactor_velocity_m_s, 29.0);
}

TEST(DynamicChain, HhtAndExplicitAgreeOnACoarseImpact) {
  // Verification f in small: the same impact (two welded coarse rings, 0.4 ms) by both
  // integrators; crush of each ring within 10 % of ring 1's, impactor speed within 2 %.
  DynamicSolverInput s;
  s.end_time_s = 4e-4;
  s.frames = 0;
  s.scheme = DynamicScheme::Explicit;
  const DynamicResult e = run_dynamic(coarse_impact(), s);
  s.scheme = DynamicScheme::Hht;
  const DynamicResult h = run_dynamic(coarse_impact(), s);
  const auto &ce = e.history.back().ring_crush_m, &ch = h.history.back().ring_crush_m;
  ASSERT_GT(ce[0], 2e-3);
  for (std::size_t i = 0; i < ce.size(); ++i) EXPECT_NEAR(ch[i], ce[i], 0.1 * ce[0]) << "ring " << i + 1;
  EXPECT_NEAR(h.history.back().impactor_velocity_m_s, e.history.back().impactor_velocity_m_s,
              0.02 * e.history.back().impactor_velocity_m_s);
}

TEST(DynamicChain, ArrestEndsTheRun) {
  // One coarse ring hit at 2 m/s: the impactor stops and rebounds, the ring comes to rest.
  ChainInput in = coarse(1, JointKind::Welded);
  in.impactor_velocity_m_s = 2;
  DynamicSolverInput s;
  s.scheme = DynamicScheme::Explicit;
  s.end_time_s = 0.02;
  s.frames = 0;
  s.rest_kinetic_fraction = 0.05;
  const DynamicResult r = run_dynamic(in, s);
  EXPECT_EQ(r.end_reason, "arrest");
  EXPECT_LT(r.history.back().time_s, 0.02);
  EXPECT_LE(r.history.back().impactor_velocity_m_s, 0.0);
  // Everything but the impactor holds less than 5 % of KE0.
  const double ke_impactor = 0.5 * in.impactor_mass_kg * std::pow(r.history.back().impactor_velocity_m_s, 2);  // whole chain
  EXPECT_LT(r.history.back().kinetic_j - ke_impactor, 0.05 * r.initial_kinetic_j);
  EXPECT_LT(r.energy_balance_error, 0.01);
}

TEST(DynamicChain, EnergyLimitStopsTheRun) {
  DynamicSolverInput s;
  s.scheme = DynamicScheme::Explicit;
  s.end_time_s = 2e-4;
  s.energy_error_limit = 1e-9;
  try {
    run_dynamic(coarse_impact(), s);
    FAIL() << "no SolveFailure";
  } catch (const SolveFailure& e) {
    EXPECT_NE(std::string(e.what()).find("energy_error_limit"), std::string::npos) << e.what();
  }
}

// A failed step says what the contact was doing (dynamic_run.cpp contact_context): HHT with
// an unreachable half-step tolerance and a minimum step that soon stops it, once the impactor
// is pressing on ring 1.
TEST(DynamicChain, FailedStepNamesTheDeepestContact) {
  DynamicSolverInput s;
  s.scheme = DynamicScheme::Hht;
  s.end_time_s = 2e-4;
  s.frames = 0;
  s.haftol_n = 1e-3;
  s.initial_step_s = 2e-6;
  s.min_step_s = 1e-6;
  try {
    run_dynamic(coarse_impact(), s);
    FAIL() << "no SolveFailure";
  } catch (const SolveFailure& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("HAFTOL"), std::string::npos) << m;
    EXPECT_NE(m.find("deepest contact penetration"), std::string::npos) << m;
    EXPECT_NE(m.find("of ring 1 (X = "), std::string::npos) << m;  // the impactor presses on ring 1
    EXPECT_NE(m.find("into the impactor face"), std::string::npos) << m;
    EXPECT_NE(m.find("% of the "), std::string::npos) << m;
  }
}

TEST(DynamicChain, RejectsBadSolverInput) {
  DynamicSolverInput s;
  s.end_time_s = -1;
  EXPECT_THROW(run_dynamic(coarse_impact(), s), std::invalid_argument);
  s = DynamicSolverInput{};
  s.rest_kinetic_fraction = 2;
  EXPECT_THROW(run_dynamic(coarse_impact(), s), std::invalid_argument);
}

}  // namespace
}  // namespace ringcrush::fe
