// Fixed mass scaling of the explicit solver (fe/dynamics/mass_scaling.hpp; ABAQUS *FIXED
// MASS SCALING DT=/TYPE=BELOW MIN and FACTOR=/TYPE=UNIFORM), a named change of the physics:
//  - every element whose own step (safety and bulk-viscosity reduction included) is below
//    the target reaches it, λ_max(K_e, M_e) re-solved on the scaled mass, to 1e-12;
//  - the added mass is the closed form Σ ρ A_e t ((Δt*/Δt_e)² − 1) over those elements, and
//    the others keep their masses bit for bit;
//  - the scaled mass is THE mass: a free-flying ring keeps its (scaled) momentum to 1e-10 and
//    its stress at zero; the energy balance of a short crush holds to 1 % of KE0;
//  - off (or a target below every element's step) changes nothing, bitwise;
//  - bad values and HHT are refused by name.
// Coarse chains (12 elements per half ring), fractions of a millisecond.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "rings_in_motion.hpp"
#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/dynamic_run.hpp"
#include "fe/dynamics/element_eigenvalue.hpp"
#include "fe/dynamics/explicit_driver.hpp"
#include "fe/dynamics/lumped_mass.hpp"
#include "fe/dynamics/mass_scaling.hpp"

namespace ringcrush::fe {
namespace {

ChainInput coarse(int rings, JointKind joints) {
  ChainInput in;
  in.rings = rings;
  in.joints = joints;
  in.mesh.elements_around = 12;
  in.mesh.grading = 2.0;  // elements of different lengths around: different own steps
  in.density_kg_m3 = 8410;
  in.pitch_m = 2 * in.ring.outer_radius_m;
  in.bulk_viscosity = 0.06;
  return in;
}

// Independently of ChainModel: element e's own explicit step, safety · (√(1+b1²) − b1) · 2/ω_e,
// from its HRZ mass and elastic stiffness on the reference shape; and its unscaled mass ρ A t.
struct OwnStep {
  double step_s, mass_kg;
  ElementMatrix k;
};
OwnStep own_step(const ChainInput& in, const ChainMesh& mesh, int e, double safety) {
  ElementCoords xe;
  for (int a = 0; a < 8; ++a) xe.row(a) = mesh.nodes[static_cast<std::size_t>(mesh.elements[e][a])].transpose();
  const auto m = hrz_lumped_mass(xe, in.density_kg_m3, in.ring.width_m);
  const J2PlaneStress material(in.material);
  OwnStep s;
  s.k = element_elastic_stiffness(xe, in.integration, in.ring.width_m, material);
  const double xi = in.bulk_viscosity;
  s.step_s = safety * (std::sqrt(1 + xi * xi) - xi) * 2 / std::sqrt(element_max_eigenvalue(s.k, m));
  s.mass_kg = 0;
  for (double v : m) s.mass_kg += v;
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

TEST(MassScaling, ScaledElementsReachTheTargetAndAddTheClosedFormMass) {
  const ChainInput plain = coarse(2, JointKind::Welded);
  const ChainModel m0(plain);
  const auto& mesh = m0.mesh();
  const int ne = static_cast<int>(mesh.elements.size());
  std::vector<OwnStep> own;
  std::vector<double> steps;
  for (int e = 0; e < ne; ++e) {
    own.push_back(own_step(plain, mesh, e, 0.8));
    steps.push_back(own.back().step_s);
  }
  ChainInput in = plain;
  in.mass_scaling.target_step_s = median(steps);  // about half the elements below it
  in.mass_scaling.safety = 0.8;
  const ChainModel m1(in);
  const double target = in.mass_scaling.target_step_s;
  double added = 0;
  int scaled = 0;
  std::vector<char> node_touched(mesh.nodes.size(), 0);
  for (int e = 0; e < ne; ++e) {
    if (own[e].step_s < target) {
      ++scaled;
      added += own[e].mass_kg * ((target / own[e].step_s) * (target / own[e].step_s) - 1);
      const double xi = in.bulk_viscosity;
      const double after =
          0.8 * (std::sqrt(1 + xi * xi) - xi) * 2 / std::sqrt(element_max_eigenvalue(own[e].k, m1.element_mass(e)));
      EXPECT_GE(after, target * (1 - 1e-12)) << "element " << e;
      EXPECT_LE(after, target * (1 + 1e-12)) << "element " << e;
      for (int n : mesh.elements[e]) node_touched[static_cast<std::size_t>(n)] = 1;
    } else {
      for (int a = 0; a < 8; ++a) EXPECT_EQ(m1.element_mass(e)[a], m0.element_mass(e)[a]) << "element " << e;
    }
  }
  ASSERT_GT(scaled, 0);
  ASSERT_LT(scaled, ne);
  const MassScalingReport& r = m1.mass_scaling();
  EXPECT_TRUE(r.active);
  EXPECT_EQ(r.scaled_elements, scaled);
  EXPECT_NEAR(r.added_mass_kg, added, 1e-12 * added);
  EXPECT_NEAR(r.min_scaled_element_step_s, target, 1e-12 * target);
  EXPECT_DOUBLE_EQ(r.min_element_step_s, *std::min_element(steps.begin(), steps.end()));
  // The assembled lumped mass carries exactly the added mass (ring nodes, y dofs), and nodes of
  // untouched elements only are bitwise as before.
  double lumped_added = 0;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (static_cast<int>(n) == mesh.impactor_node) {
      EXPECT_EQ(m1.lumped_mass()(2 * mesh.impactor_node + 1), m0.lumped_mass()(2 * mesh.impactor_node + 1));
      continue;
    }
    lumped_added += m1.lumped_mass()(2 * static_cast<Eigen::Index>(n) + 1) - m0.lumped_mass()(2 * static_cast<Eigen::Index>(n) + 1);
    if (!node_touched[n]) {
      EXPECT_EQ(m1.lumped_mass()(2 * static_cast<Eigen::Index>(n)), m0.lumped_mass()(2 * static_cast<Eigen::Index>(n)));
    }
  }
  EXPECT_NEAR(lumped_added, added, 1e-10 * added);
  // The stable step's element part follows: scaled, it is no longer the smallest element's.
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(m0.dofs());
  EXPECT_GT(m1.stable_step(u).step_s, m0.stable_step(u).step_s);
}

TEST(MassScaling, UniformFactorThenTarget) {
  ChainInput in = coarse(1, JointKind::Free);
  const ChainModel m0(in);
  in.mass_scaling.factor = 4;
  const ChainModel m4(in);
  const int ne = static_cast<int>(m0.mesh().elements.size());
  double ring = 0;
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 8; ++a) {
      EXPECT_NEAR(m4.element_mass(e)[a], 4 * m0.element_mass(e)[a], 1e-15 * m4.element_mass(e)[a]);
      ring += m0.element_mass(e)[a];
    }
  EXPECT_EQ(m4.mass_scaling().scaled_elements, ne);
  EXPECT_NEAR(m4.mass_scaling().added_mass_kg, 3 * ring, 1e-12 * ring);
  EXPECT_NEAR(m4.mass_scaling().min_scaled_element_step_s, 2 * m4.mass_scaling().min_element_step_s,
              1e-12 * m4.mass_scaling().min_scaled_element_step_s);
  // Factor first, then the target: a target at 3× the smallest unscaled step lifts the factor-4
  // elements (now at ≥ 2×) that are still below it, and only those.
  in.mass_scaling.target_step_s = 3 * m0.mass_scaling().min_element_step_s;
  const ChainModel both(in);
  EXPECT_NEAR(both.mass_scaling().min_scaled_element_step_s, in.mass_scaling.target_step_s,
              1e-12 * in.mass_scaling.target_step_s);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 8; ++a) EXPECT_GE(both.element_mass(e)[a], m4.element_mass(e)[a]);
}

TEST(MassScaling, FreeFlightKeepsTheScaledMomentumAndZeroStress) {
  ChainInput in = coarse(1, JointKind::Free);
  in.impactor_velocity_m_s = 0;
  in.fixed_target = false;
  const ChainModel plain(in);
  in.mass_scaling.target_step_s = 2.5 * plain.mass_scaling().min_element_step_s;
  ChainModel model(in);
  ASSERT_GT(model.mass_scaling().scaled_elements, 0);
  test_support::RingsInMotion sys(model, {-5.0});  // the ring, not the impactor
  ExplicitOptions o;
  o.mass_scaling_target_s = in.mass_scaling.target_step_s;
  ExplicitDriver d(sys, o);
  auto momentum = [&] {
    double p = 0;
    for (int k = 1; k < sys.dofs(); k += 2) p += sys.lumped_mass()(k) * d.velocity()(k);
    return p;
  };
  const double p0 = momentum();
  // The momentum is that of the scaled ring: (rings' mass + added) × 5 m/s.
  EXPECT_NEAR(p0, -5.0 * (model.mass_scaling().element_mass_kg + model.mass_scaling().added_mass_kg),
              1e-12 * std::abs(p0));
  double worst = 0;
  const double end = 2e-4;
  while (d.time() < end * (1 - 1e-12)) {
    d.step(end);
    worst = std::max(worst, std::abs(momentum() - p0));
  }
  EXPECT_LT(worst, 1e-10 * std::abs(p0));
  double mises = 0;
  for (const auto& f : model.element_fields()) mises = std::max(mises, f.mises);
  EXPECT_LT(mises, 1e-9 * 273e6);
  // The step it bought: larger than the unscaled smallest element step.
  EXPECT_GT(d.max_step(), 1.5 * plain.mass_scaling().min_element_step_s);
}

// 0.128 kg (half model) at 30 m/s on two welded rings, 0.2 ms.
ChainInput coarse_impact() {
  ChainInput in = coarse(2, JointKind::Welded);
  in.impactor_mass_kg = 0.256;
  in.impactor_velocity_m_s = 30;
  return in;
}

DynamicSolverInput short_explicit() {
  DynamicSolverInput s;
  s.scheme = DynamicScheme::Explicit;
  s.end_time_s = 2e-4;
  s.frames = 0;
  return s;
}

TEST(MassScaling, EnergyBalanceOfAScaledCrush) {
  const ChainInput plain = coarse_impact();
  const double dt0 = ChainModel(plain).mass_scaling().min_element_step_s;
  ChainInput in = plain;
  in.mass_scaling.target_step_s = 2 * dt0;
  std::vector<std::string> lines;
  DynamicCallbacks cb;
  cb.log = [&](const std::string& l) { lines.push_back(l); };
  const DynamicResult r = run_dynamic(in, short_explicit(), cb);
  const DynamicResult r0 = run_dynamic(plain, short_explicit());
  EXPECT_LT(r.energy_balance_error, 0.01);
  EXPECT_NEAR(r.initial_kinetic_j, 0.5 * 0.256 * 30 * 30, 1e-9);  // the impactor is not scaled
  EXPECT_GT(r.history.back().plastic_j, 0.0);
  ASSERT_TRUE(r.mass_scaling.active);
  EXPECT_GT(r.mass_scaling.added_mass_kg, 0.0);
  // Whole chain (× 2 for the half model): the rings' unscaled mass is ρ · π (R² − r²) · w per ring.
  const double ring = plain.density_kg_m3 * std::numbers::pi *
                      (std::pow(plain.ring.outer_radius_m, 2) - std::pow(plain.ring.inner_radius_m, 2)) *
                      plain.ring.width_m;
  EXPECT_NEAR(r.mass_scaling.element_mass_kg, 2 * ring, 0.01 * 2 * ring);  // polygonal mesh: within 1 %
  // The time it buys: fewer steps than the unscaled run (not 2×: the contact springs add to ω²).
  EXPECT_LT(static_cast<double>(r.statistics.steps), 0.8 * static_cast<double>(r0.statistics.steps));
  // The impactor touches ring 1 from the start: the contact springs hold the step below the
  // target, and the log says so.
  EXPECT_GT(r.statistics.steps_below_mass_scaling_target, 0);
  const bool said = std::any_of(lines.begin(), lines.end(), [](const std::string& l) {
    return l.find("below the mass-scaling target") != std::string::npos;
  });
  EXPECT_TRUE(said);
  EXPECT_FALSE(r0.mass_scaling.active);
  EXPECT_EQ(r0.statistics.steps_below_mass_scaling_target, 0);
}

TEST(MassScaling, OffOrBelowEveryElementChangesNothing) {
  const ChainInput plain = coarse_impact();
  const ChainModel m0(plain);
  // Off: the lumped mass is the HRZ masses summed in element order, bit for bit.
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(m0.dofs());
  const auto& mesh = m0.mesh();
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    ElementCoords xe;
    for (int a = 0; a < 8; ++a) xe.row(a) = mesh.nodes[static_cast<std::size_t>(mesh.elements[e][a])].transpose();
    const auto me = hrz_lumped_mass(xe, plain.density_kg_m3, plain.ring.width_m);
    for (int a = 0; a < 8; ++a) {
      expected(2 * mesh.elements[e][a]) += me[a];
      expected(2 * mesh.elements[e][a] + 1) += me[a];
    }
  }
  expected(2 * mesh.impactor_node) = expected(2 * mesh.impactor_node + 1) = plain.impactor_mass_kg / m0.symmetry_factor();
  for (Eigen::Index k = 0; k < m0.dofs(); ++k) EXPECT_EQ(m0.lumped_mass()(k), expected(k)) << "dof " << k;
  EXPECT_FALSE(m0.mass_scaling().active);
  EXPECT_EQ(m0.mass_scaling().scaled_elements, 0);
  EXPECT_EQ(m0.mass_scaling().added_mass_kg, 0.0);
  // A target below every element's own step: active, nothing scaled, the run bitwise the same.
  ChainInput low = plain;
  low.mass_scaling.target_step_s = 0.5 * m0.mass_scaling().min_element_step_s;
  DynamicSolverInput s = short_explicit();
  s.end_time_s = 5e-5;
  const DynamicResult a = run_dynamic(plain, s), b = run_dynamic(low, s);
  EXPECT_TRUE(b.mass_scaling.active);
  EXPECT_EQ(b.mass_scaling.scaled_elements, 0);
  ASSERT_EQ(a.history.size(), b.history.size());
  ASSERT_EQ(a.statistics.steps, b.statistics.steps);
  for (std::size_t k = 0; k < a.history.size(); ++k) {
    EXPECT_EQ(a.history[k].impactor_displacement_m, b.history[k].impactor_displacement_m);
    EXPECT_EQ(a.history[k].kinetic_j, b.history[k].kinetic_j);
    EXPECT_EQ(a.history[k].plastic_j, b.history[k].plastic_j);
    EXPECT_EQ(a.history[k].ring_crush_m, b.history[k].ring_crush_m);
  }
  for (Eigen::Index k = 0; k < a.final_displacement.size(); ++k)
    EXPECT_EQ(a.final_displacement(k), b.final_displacement(k));
}

void expect_named(const std::function<void()>& f, const std::string& name) {
  try {
    f();
    ADD_FAILURE() << "no exception, expected one naming " << name;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
  }
}

TEST(MassScaling, BadInputIsRefusedByName) {
  auto with = [](double dt, double factor, double safety = 0.8) {
    MassScaling s;
    s.target_step_s = dt;
    s.factor = factor;
    s.safety = safety;
    return s;
  };
  expect_named([&] { validate(with(-1e-7, 1)); }, "mass_scaling_dt");
  expect_named([&] { validate(with(NAN, 1)); }, "mass_scaling_dt");
  expect_named([&] { validate(with(INFINITY, 1)); }, "mass_scaling_dt");
  expect_named([&] { validate(with(0, 0.5)); }, "mass_scaling_factor");
  expect_named([&] { validate(with(0, NAN)); }, "mass_scaling_factor");
  expect_named([&] { validate(with(1e-7, 1, 1.5)); }, "safety");
  EXPECT_NO_THROW(validate(with(0, 1)));
  EXPECT_NO_THROW(validate(with(1e-7, 2)));
  // Through the chain input, and refused with HHT (its step is not the stable step).
  ChainInput in = coarse_impact();
  in.mass_scaling.factor = 0.9;
  expect_named([&] { validate(in); }, "mass_scaling_factor");
  in.mass_scaling.factor = 1;
  in.mass_scaling.target_step_s = 1e-7;
  DynamicSolverInput hht = short_explicit();
  hht.scheme = DynamicScheme::Hht;
  expect_named([&] { run_dynamic(in, hht); }, "explicit solver only");
  // The driver's own option.
  ChainModel model(coarse_impact());
  ExplicitOptions o;
  o.mass_scaling_target_s = -1;
  expect_named([&] { ExplicitDriver d(model, o); }, "mass_scaling_target_s");
}

}  // namespace
}  // namespace ringcrush::fe
