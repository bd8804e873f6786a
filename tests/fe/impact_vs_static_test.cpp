// Issue 4 verification c: a single ring hit at 2 m/s by a heavy mass absorbs, up to its
// largest deflection, the energy under the static load–deflection curve to that deflection
// (within 10 %): at 2 m/s inertia and wave effects are small and the material has no rate
// dependence, so the impact is quasi-static. Coarse mesh (12 CPS8 per half ring, 2×2) for
// both runs, the same ring, material and contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fe/dynamics/dynamic_run.hpp"
#include "fe/time/static_driver.hpp"

namespace ringcrush::fe {
namespace {

TEST(ImpactVsStatic, HeavyMassAtTwoMetresPerSecondAbsorbsTheStaticWork) {
  ChainInput chain;
  chain.rings = 1;
  chain.joints = JointKind::Free;
  chain.mesh.elements_around = 12;
  chain.integration = Integration::Reduced;
  chain.density_kg_m3 = 7850;
  chain.pitch_m = 2 * chain.ring.outer_radius_m;
  chain.impactor_mass_kg = 5.0;  // KE0 = 10 J: δ ≈ 20 mm, δ/D ≈ 0.4
  chain.impactor_velocity_m_s = 2.0;
  chain.fixed_target = true;

  DynamicSolverInput solver;
  solver.scheme = DynamicScheme::Hht;
  solver.end_time_s = 0.03;
  solver.stop_at_rest = true;
  solver.frames = 0;
  solver.output_interval_s = 2e-5;
  const DynamicResult d = run_dynamic(chain, solver);

  // The state at the largest impactor travel (the impactor has stopped there).
  const auto peak = std::max_element(d.history.begin(), d.history.end(), [](const DynamicRow& a, const DynamicRow& b) {
    return a.impactor_displacement_m < b.impactor_displacement_m;
  });
  const double delta = peak->impactor_displacement_m;
  const double absorbed = peak->elastic_j + peak->plastic_j + peak->contact_j;
  ASSERT_GT(delta, 0.01);
  ASSERT_LT(delta, 0.035);
  EXPECT_NEAR(absorbed, d.initial_kinetic_j, 0.05 * d.initial_kinetic_j) << "the impactor's energy went into the ring";

  FeInput in;
  in.ring = chain.ring;
  in.material = chain.material;
  in.mesh = chain.mesh;
  in.integration = chain.integration;
  in.contact = chain.contact;
  in.solver.crush_m = delta;
  in.solver.frames = 0;
  const StaticResult s = run_static(in);
  const double static_work = s.history.back().external_work_j;
  std::printf("delta %.3f mm: dynamic absorbed %.4f J (KE0 %.4f J), static work %.4f J\n", 1e3 * delta, absorbed,
              d.initial_kinetic_j, static_work);
  EXPECT_NEAR(s.history.back().deflection_m, delta, 1e-9);
  EXPECT_NEAR(absorbed, static_work, 0.10 * static_work)
      << "dynamic " << absorbed << " J against static " << static_work << " J at delta " << delta;
}

}  // namespace
}  // namespace ringcrush::fe
