// The analytic iteration matrix of the Level 2 polygon chain (PolygonChain::analytic_jacobian,
// which drives IDA's Newton iteration) against central differences of the generalised forces
// φ along random directions, on states of a two-ring Test 30 impact where hinges flow, rings
// touch the plates and each other and (welded) pull on their tie. Every row is checked,
// the accumulator rows (plastic work, contact damping, Kelvin–Voigt damping) included.
// Rows where φ is not differentiable along the direction (a hinge crossing its yield
// moment, a contact opening: forward and backward differences disagree) are skipped, and
// there must be few of them. The matrix leaves out the curvature terms (hinge moment ×
// change of the hinge-angle gradient, the contact point sliding along its segment, and in
// the contact dissipation rate the turn of the contact normal): each state row must match
// to 5 % of its own scale
// Σ_j |J_ij δ_j|, each accumulator row to 40 % (the contact-dissipation row, whose normal
// turn is left out, measured 10–28 %; the plastic-work and damper rows match to < 0.1 %),
// and the whole to 1 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "two_ring_chain.hpp"
#include "hinge/polygon_simulation.hpp"

using namespace ringcrush::hinge;

namespace {

PolygonChainInput two_rings(PolygonJoint joint) { return two_ring_chain::input(joint); }

struct Agreement {
  double worst_row = 0.0;  // max over checked state rows of |Jδ − Dδ| / Σ|J_ij δ_j|
  double worst_accumulator_row = 0.0;  // the same over the energy accumulators' rows
  double total = 0.0;      // ‖Jδ − Dδ‖ / ‖Dδ‖ over the checked rows
  std::size_t checked = 0, skipped = 0;
};

Agreement along_directions(PolygonChain& chain, double t, const std::vector<double>& y) {
  const std::size_t n = y.size();
  const std::size_t acc = chain.accumulator_offset();
  std::vector<PolygonChain::Triplet> jac;
  chain.analytic_jacobian(t, 0.0, y.data(), jac);  // cj = 0: −∂φ/∂y alone
  const auto scales = chain.component_scales();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Agreement a;
  double en = 0.0, dn = 0.0;
  for (int direction = 0; direction < 4; ++direction) {
    std::vector<double> d(n), jd(n, 0.0), mag(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) d[i] = u(rng) * scales[i];
    for (const auto& e : jac) {
      const double v = e.value * d[static_cast<std::size_t>(e.col)];
      jd[static_cast<std::size_t>(e.row)] += v;
      mag[static_cast<std::size_t>(e.row)] += std::abs(v);
    }
    const double h = 1e-7;  // × scale: 2.5 nm, 3 µm/s
    std::vector<double> yp(y), ym(y), fp(n), fm(n), f0(n);
    for (std::size_t i = 0; i < n; ++i) {
      yp[i] += h * d[i];
      ym[i] -= h * d[i];
    }
    chain.generalised_forces(t, y.data(), f0.data());
    chain.generalised_forces(t, yp.data(), fp.data());
    chain.generalised_forces(t, ym.data(), fm.data());
    for (std::size_t i = 0; i < n; ++i) {
      if (mag[i] == 0.0) continue;
      const double fwd = -(fp[i] - f0[i]) / h, bwd = -(f0[i] - fm[i]) / h;
      if (std::abs(fwd - bwd) > 1e-3 * mag[i]) {
        ++a.skipped;
        continue;
      }
      ++a.checked;
      const double central = 0.5 * (fwd + bwd);
      const double e = std::abs(jd[i] - central) / mag[i];
      if (i >= acc)
        a.worst_accumulator_row = std::max(a.worst_accumulator_row, e);
      else
        a.worst_row = std::max(a.worst_row, e);
      en += (jd[i] - central) * (jd[i] - central);
      dn += central * central;
    }
  }
  a.total = std::sqrt(en / dn);
  return a;
}

void check_joint(PolygonJoint joint, bool elastic_rate_damper = false) {
  auto in = two_rings(joint);
  in.hinge_damper_on_elastic_rate = elastic_rate_damper;
  PolygonRunOptions o;
  o.relative_tolerance = 1e-5;
  o.absolute_scale = 1e-5;
  o.output_interval_s = 1e-4;
  for (double end : {2e-4, 1.2e-3}) {
    o.end_time_s = end;
    const auto out = run_polygon_chain(in, o);
    ASSERT_GT(out.history.plastic_j.back(), 0.0);
    PolygonChain chain(in);
    const auto a = along_directions(chain, end, out.final_state);
    EXPECT_LT(a.worst_row, 0.05) << "t = " << end << " s";
    EXPECT_LT(a.worst_accumulator_row, 0.4) << "t = " << end << " s";
    EXPECT_LT(a.total, 0.01) << "t = " << end << " s";
    EXPECT_LT(a.skipped, a.checked / 20) << "t = " << end << " s";
  }
}

}  // namespace

TEST(PolygonJacobian, AnalyticMatchesDifferencesWelded) { check_joint(PolygonJoint::Welded); }
TEST(PolygonJacobian, AnalyticMatchesDifferencesFree) { check_joint(PolygonJoint::Free); }
TEST(PolygonJacobian, AnalyticMatchesDifferencesPlates) { check_joint(PolygonJoint::Plates); }
// The hinge damper on the elastic rate (PolygonChainInput::hinge_damper_on_elastic_rate): its
// moment −c_θ λ̇ sign M of the flowing hinges, in the forces and the damper power.
TEST(PolygonJacobian, AnalyticMatchesDifferencesElasticRateDamper) { check_joint(PolygonJoint::Welded, true); }

// The solver choice is numerics only: the direct solve on the analytic matrix and the
// previous SPGMR on the coloured-difference preconditioner (PolygonIdaOptions) give the same
// first millisecond of a two-ring impact (crush of both rings to 1e-3, plastic work to 1e-3).
TEST(PolygonJacobian, DirectAnalyticAndKrylovDifferencesAgree) {
  const auto in = two_rings(PolygonJoint::Free);
  PolygonRunOptions o;
  o.relative_tolerance = 1e-5;
  o.absolute_scale = 1e-5;
  o.end_time_s = 1e-3;
  o.output_interval_s = 1e-4;
  const auto direct = run_polygon_chain(in, o);
  o.ida_linear_solver = PolygonLinearSolver::Krylov;
  o.ida_jacobian = PolygonJacobian::Differences;
  const auto krylov = run_polygon_chain(in, o);
  EXPECT_EQ(krylov.symbolic_factorisations, 0);
  EXPECT_GT(krylov.linear_iterations, 0);
  EXPECT_EQ(direct.linear_iterations, 0);
  auto crush = [&](const PolygonShape& s, int ring) {
    double lo = 1e300, hi = -1e300;
    for (const auto& p : s.nodes[static_cast<std::size_t>(ring)]) {
      lo = std::min(lo, p[1]);
      hi = std::max(hi, p[1]);
    }
    return in.outer_diameter_m - (hi - lo + in.wall_thickness_m);
  };
  for (int ring = 0; ring < 2; ++ring) {
    const double a = crush(direct.history.shapes.back(), ring), b = crush(krylov.history.shapes.back(), ring);
    EXPECT_NEAR(a, b, 1e-3 * std::max(std::abs(b), 1e-3)) << "ring " << ring + 1;
  }
  EXPECT_GT(crush(direct.history.shapes.back(), 0), 5e-3);
  EXPECT_NEAR(direct.history.plastic_j.back(), krylov.history.plastic_j.back(),
              1e-3 * krylov.history.plastic_j.back());
}
