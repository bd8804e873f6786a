// The central difference's implicit membrane (CentralDifferenceOptions::implicit_membrane,
// hinge/polygon_central_difference.hpp, hinge/polygon_implicit_membrane.cpp): the membrane
// tangent against differences of φ and the banded solve against a dense one, stability at ten
// times the membrane's explicit limit (and the explicit membrane's divergence there),
// second-order convergence against a fine explicit reference, the energy balance and the crush
// of an impact against the explicit membrane, the step bound without the membrane, bad input.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "compare/hinge_run_2d.hpp"
#include "compare/scene.hpp"
#include "minimal_scene.hpp"
#include "hinge/polygon_central_difference.hpp"
#include "hinge/polygon_simulation.hpp"
#include "hinge/polygon_stiffness_spectrum.hpp"
#include "two_ring_chain.hpp"

using namespace ringcrush::hinge;

namespace {

// One ring alone, elastic (σ0 out of reach: the flow's backward Euler is first order), no
// target, the impactor lifted 1 cm off it: only the ring's own forces act.
PolygonChainInput lone_ring(bool half, double wall_m, double damping_ratio) {
  PolygonChainInput in = two_ring_chain::input(PolygonJoint::Free);
  in.rings = 1;
  in.half_symmetry = half;
  in.fixed_target = false;
  in.impactor_velocity_m_s = 0.0;
  in.wall_thickness_m = wall_m;
  in.yield_stress_pa = 1e13;
  in.yield_cap_ratio = 0.0;
  in.membrane_damping_ratio = in.hinge_damping_ratio = damping_ratio;
  return in;
}

// The rest state with a smooth velocity field: breathing 0.5 m/s and ovalisation 1 m/s
// (radial), plus `noise` m/s at random on every node row (exciting the short modes).
std::vector<double> moving_state(const PolygonChain& chain, double noise) {
  auto y = chain.initial_state();
  y[chain.body_offset(0)] += 0.01;
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const bool half = chain.input().half_symmetry;
  const int n = chain.nodes_per_ring();
  for (int j = 0; j < chain.independent_nodes(); ++j) {
    const auto o = chain.node_offset(0, j);
    const double a = 2.0 * std::numbers::pi * j / n;
    const double vr = 0.5 + std::cos(2.0 * a);
    const bool axis = half && (j == 0 || j == chain.independent_nodes() - 1);
    y[o + 2] = axis ? 0.0 : vr * std::sin(a) + noise * u(gen);
    y[o + 3] = vr * std::cos(a) + noise * u(gen);
  }
  return y;
}

using two_ring_chain::velocity_rows;

double ring_energy(PolygonChain& chain, const std::vector<double>& y) {
  const auto e = chain.energies(0.0, y.data());
  return e.kinetic + e.elastic;
}

}  // namespace

// K_m v (membrane_stiffness_product) is the membrane's tangent: at the rest shape (N = 0, so
// no geometric term) the difference of ∂φ/∂x · v between membrane scales 1 and ½ — the hinges
// cancel — equals the difference of the products, to 1e-6 (central differences of φ); and the
// banded solve with c_b + h k_m (no dampers) solves (μ + h² K_m) v = μ v* with K_m read off
// the product column by column, to 1e-12, half model and full ring.
TEST(PolygonImplicitMembrane, ProductIsTheMembraneTangentAndFitsTheBand) {
  for (bool half : {true, false}) {
    auto in = lone_ring(half, 0.0016, 0.0);
    PolygonChain stiff(in);
    in.membrane_stiffness_scale = 0.5;
    PolygonChain soft(in);
    auto y = stiff.initial_state();
    y[stiff.body_offset(0)] += 0.01;
    const auto rows = velocity_rows(stiff);
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> v(y.size(), 0.0);
    for (const auto r : rows) v[r] = u(gen);
    // ∂φ/∂x v by central differences on the positions (row r − 2 of velocity row r).
    const double eps = 1e-9;
    auto directional = [&](PolygonChain& c) {
      auto yp = y, ym = y;
      for (const auto r : rows) {
        yp[r - 2] += eps * v[r];
        ym[r - 2] -= eps * v[r];
      }
      std::vector<double> fp(y.size()), fm(y.size()), d(y.size());
      c.generalised_forces(0.0, yp.data(), fp.data());
      c.generalised_forces(0.0, ym.data(), fm.data());
      for (std::size_t i = 0; i < y.size(); ++i) d[i] = (fp[i] - fm[i]) / (2.0 * eps);
      return d;
    };
    const auto dphi_stiff = directional(stiff), dphi_soft = directional(soft);
    std::vector<double> k_stiff(y.size(), 0.0), k_soft(y.size(), 0.0);
    stiff.membrane_stiffness_product(y.data(), v.data(), k_stiff.data());
    soft.membrane_stiffness_product(y.data(), v.data(), k_soft.data());
    // The second product at the same positions reuses the bar directions: the same bits.
    std::vector<double> w2(y.size(), 0.0), k_full(y.size(), 0.0), k_again(y.size(), 0.0);
    for (const auto r : rows) w2[r] = u(gen);
    stiff.membrane_stiffness_product(y.data(), w2.data(), k_full.data());
    stiff.membrane_stiffness_product(y.data(), v.data(), k_stiff.data());
    stiff.membrane_stiffness_product_again(w2.data(), k_again.data());
    for (const auto r : rows) EXPECT_EQ(k_again[r], k_full[r]);
    double norm = 0.0;
    for (const auto r : rows) norm = std::max(norm, std::abs(k_stiff[r] - k_soft[r]));
    ASSERT_GT(norm, 0.0);
    for (const auto r : rows)
      EXPECT_NEAR(-(dphi_stiff[r] - dphi_soft[r]), k_stiff[r] - k_soft[r], 1e-6 * norm) << "half " << half;

    // The band: a distorted ring (the bars' directions all differ).
    auto yd = y;
    const double l0 = stiff.bar_length();
    for (const auto r : rows) yd[r - 2] += 0.2 * l0 * u(gen);
    const auto n = static_cast<Eigen::Index>(rows.size());
    Eigen::MatrixXd K(n, n);
    std::vector<double> e(y.size(), 0.0), ke(y.size(), 0.0);
    for (Eigen::Index m = 0; m < n; ++m) {
      e[rows[static_cast<std::size_t>(m)]] = 1.0;
      stiff.membrane_stiffness_product(yd.data(), e.data(), ke.data());
      e[rows[static_cast<std::size_t>(m)]] = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) K(i, m) = ke[rows[static_cast<std::size_t>(i)]];
    }
    EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm()) << "half " << half;
    Eigen::VectorXd mu(n), vstar(n);
    std::vector<double> w(y.size(), 0.0), d(y.size(), 0.0);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto r = rows[static_cast<std::size_t>(i)];
      mu(i) = stiff.mass_row(r);
      w[r] = vstar(i) = u(gen);
    }
    const double h = 3e-6;  // h² k_m/μ ≫ 1: the membrane's modes far past 2/Δt
    EXPECT_GT(h * h * K.diagonal().maxCoeff() / mu.minCoeff(), 10.0);
    Eigen::MatrixXd A = h * h * K;
    A.diagonal() += mu;
    const Eigen::VectorXd dense = A.ldlt().solve(mu.cwiseProduct(vstar));
    stiff.set_implicit_membrane(true);
    stiff.ring_damper_membrane_step(yd.data(), h, w.data(), d.data());
    const Eigen::VectorXd hKv = h * K * dense;
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto r = rows[static_cast<std::size_t>(i)];
      EXPECT_NEAR(w[r], dense(i), 1e-12 * dense.norm()) << "half " << half << " row " << i;
      EXPECT_NEAR(d[r], hKv(i), 1e-10 * hKv.norm()) << "half " << half << " row " << i;
    }
  }
}

// A thin ring (t = 0.2 mm: its hinges bound the step ~30× above its membrane bars) ringing in
// all its modes, stepped at 10× the membrane's Gershgorin step for 2000 steps: with the
// membrane implicit its energy (kinetic + elastic) never exceeds the initial one and the
// ring stays round to 1 %; the explicit membrane at the same step diverges within 200 steps.
// Without dampers (the linear trapezoidal rule: no growth, no numerical loss beyond bounded
// oscillation) and with them (the energy falls); half model and full ring.
TEST(PolygonImplicitMembrane, StableAtTenTimesTheMembraneLimit) {
  for (bool half : {true, false})
    for (double zeta : {0.0, 1.0}) {
      const auto in = lone_ring(half, 0.0002, zeta);
      PolygonChain chain(in);
      chain.set_implicit_ring_dampers(true);  // as the driver: the dampers leave the bound
      const auto y0 = moving_state(chain, 0.2);
      chain.energies(0.0, y0.data());
      std::vector<double> phi(y0.size());
      chain.generalised_forces(0.0, y0.data(), phi.data());  // the contact rows of the bound
      const double membrane = chain.stable_step(PolygonChain::kMembrane);
      const double hinges = chain.stable_step(PolygonChain::kHinges);
      ASSERT_GT(hinges, 20.0 * membrane);
      const double dt = 10.0 * membrane;
      const double e0 = ring_energy(chain, y0);
      CentralDifferenceOptions o;
      o.fixed_step_s = dt;
      o.implicit_membrane = true;
      {
        PolygonCentralDifference cd(chain, 0.0, y0, o);
        double e_max = 0.0, r_dev = 0.0;
        for (int s = 1; s <= 20; ++s) {
          cd.advance(s * 100 * dt);
          auto y = cd.y();
          e_max = std::max(e_max, ring_energy(chain, y));
          for (int j = 0; j < chain.independent_nodes(); ++j) {
            const auto o6 = chain.node_offset(0, j);
            const double r = std::hypot(y[o6], y[o6 + 1]);
            r_dev = std::max(r_dev, std::abs(r / chain.mean_radius() - 1.0));
          }
        }
        EXPECT_EQ(cd.statistics().steps, 2000);
        EXPECT_LE(e_max, e0 * 1.01) << "half " << half << " zeta " << zeta;
        EXPECT_LT(r_dev, 0.1) << "half " << half << " zeta " << zeta;
        if (zeta > 0) {
          EXPECT_LT(ring_energy(chain, cd.y()), 0.5 * e0);
        }
      }
      o.implicit_membrane = false;
      chain.set_implicit_membrane(false);
      bool diverged = false;
      try {
        PolygonCentralDifference cd(chain, 0.0, y0, o);
        cd.advance(200 * dt);
        const double e = ring_energy(chain, cd.y());
        diverged = !(e < 100.0 * e0);
      } catch (const std::exception&) {
        diverged = true;
      }
      EXPECT_TRUE(diverged) << "half " << half << " zeta " << zeta;
    }
}

// Consistency and order: the Test 30 ring (dampers on, elastic) from a smooth velocity field
// over 10 µs at Δt = ½, ¼, ⅛ of its hinges' step (the coarsest 1.6× past the membrane's
// explicit step), against the explicit membrane at 1/64 of the explicit step: the error of the
// node positions falls by ≥ 3 per halving (second order: 4).
TEST(PolygonImplicitMembrane, ConvergesAtSecondOrder) {
  const auto in = lone_ring(true, 0.0016, 1.0);
  PolygonChain chain(in);
  chain.set_implicit_ring_dampers(true);
  const auto y0 = moving_state(chain, 0.0);
  std::vector<double> phi(y0.size());
  chain.generalised_forces(0.0, y0.data(), phi.data());
  const double all = chain.stable_step(), hinges = chain.stable_step(PolygonChain::kHinges);
  const double membrane = chain.stable_step(PolygonChain::kMembrane);
  const double T = 1e-5;
  auto run = [&](double dt, bool implicit) {
    CentralDifferenceOptions o;
    o.fixed_step_s = dt;
    o.implicit_membrane = implicit;
    PolygonCentralDifference cd(chain, 0.0, y0, o);
    cd.advance(T);
    return cd.y();
  };
  const auto ref = run(all / 64.0, false);
  std::vector<double> err;
  for (double f : {0.5, 0.25, 0.125}) {
    const auto y = run(f * hinges, true);
    double e = 0.0;
    for (int j = 0; j < chain.independent_nodes(); ++j)
      for (int c = 0; c < 2; ++c) {
        const auto i = chain.node_offset(0, j) + static_cast<std::size_t>(c);
        e = std::max(e, std::abs(y[i] - ref[i]));
      }
    err.push_back(e);
  }
  EXPECT_GT(0.5 * hinges, 1.5 * membrane);
  EXPECT_GT(err[0] / err[1], 3.0) << err[0] << " " << err[1];
  EXPECT_GT(err[1] / err[2], 3.0) << err[1] << " " << err[2];
  EXPECT_LT(err[2], 1e-3 * chain.bar_length());
}

// The two welded rings struck at 27.7 m/s over 1.5 ms, membrane implicit at full EA: the
// balance closes to 1e-3 with the correction's work booked (and that work is reported, small),
// the step exceeds the membrane's explicit bound, and each ring's crush is that of the
// explicit membrane to 0.01 D.
TEST(PolygonImplicitMembrane, ImpactBalanceAndCrushAgainstTheExplicitMembrane) {
  const auto in = two_ring_chain::input(PolygonJoint::Welded);
  PolygonChain probe(in);
  const double membrane_step = probe.stable_step(PolygonChain::kMembrane);
  PolygonRunOutput out[2];
  for (int implicit = 0; implicit < 2; ++implicit) {
    PolygonRunOptions o;
    o.integrator = PolygonIntegrator::CentralDifference;
    o.central_difference_implicit_membrane = implicit == 1;
    o.end_time_s = 1.5e-3;
    o.output_interval_s = 5e-5;
    out[implicit] = run_polygon_chain(in, o);
    EXPECT_LT(out[implicit].energy_balance_error, 1e-3) << "implicit " << implicit;
  }
  EXPECT_GT(out[1].max_step_s, 1.2 * membrane_step);
  EXPECT_LT(out[1].steps, out[0].steps);
  EXPECT_EQ(out[0].membrane_correction_work_j, 0.0);
  EXPECT_NE(out[1].membrane_correction_work_j, 0.0);
  EXPECT_LT(std::abs(out[1].membrane_correction_work_j), 1e-2 * out[1].initial_energy_j);
  for (int r = 0; r < 2; ++r)
    EXPECT_NEAR(two_ring_chain::crush(out[1].history.shapes.back(), r, in) / in.outer_diameter_m,
                two_ring_chain::crush(out[0].history.shapes.back(), r, in) / in.outer_diameter_m, 0.01)
        << "ring " << r;
}

// With the implicit membrane set, the Gershgorin bound and the power-iteration stiffness leave
// the membrane out: stable_step() is the bound without the membrane term, and λ_max of the
// spectrum's matrix (dense) drops below half the one with it (the Test 30 ring alone, lifted
// off the impactor: the hinges remain; in a chain the contacts and ties would set both).
TEST(PolygonImplicitMembrane, StepBoundLeavesTheMembraneOut) {
  PolygonChain chain(lone_ring(true, 0.0016, 1.0));
  chain.set_implicit_ring_dampers(true);
  auto y = chain.initial_state();
  y[chain.body_offset(0)] += 0.01;
  std::vector<double> phi(y.size());
  chain.generalised_forces(0.0, y.data(), phi.data());
  const double without = chain.stable_step(PolygonChain::kAllStiffness & ~PolygonChain::kMembrane);
  const double with = chain.stable_step();
  // λ_max of the spectrum's A = M^{-1/2} K M^{-1/2}, dense.
  auto lambda_max = [&] {
    PolygonStiffnessSpectrum spectrum(chain);
    spectrum.estimate(0.0, y.data(), 1, 1, 1.0);
    const auto n = static_cast<Eigen::Index>(spectrum.position_rows().size());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    for (const auto& e : spectrum.entries()) A(e.i, e.j) += e.a;
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (A + A.transpose())).eigenvalues().maxCoeff();
  };
  const double lambda_with = lambda_max();
  chain.set_implicit_membrane(true);
  EXPECT_EQ(chain.stable_step(), without);
  EXPECT_GT(chain.stable_step(), 1.5 * with);
  EXPECT_EQ(chain.stable_step(PolygonChain::kMembrane), std::numeric_limits<double>::infinity());
  const double lambda_without = lambda_max();
  EXPECT_LT(lambda_without, 0.5 * lambda_with);
  EXPECT_GT(2.0 / std::sqrt(lambda_without), chain.stable_step());  // Gershgorin stays a bound
}

// Bad input: the implicit membrane without the implicit dampers, a non-positive h, the solve
// before set_implicit_membrane, a scene key that is not a boolean; the scene key reaches the
// Level 2 settings.
TEST(PolygonImplicitMembrane, BadInputIsNamed) {
  const auto in = two_ring_chain::input(PolygonJoint::Free);
  PolygonChain chain(in);
  CentralDifferenceOptions o;
  o.implicit_membrane = true;
  o.implicit_ring_dampers = false;
  try {
    PolygonCentralDifference cd(chain, 0.0, chain.initial_state(), o);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("implicit_membrane needs implicit_ring_dampers"), std::string::npos);
  }
  auto y = chain.initial_state();
  std::vector<double> d(y.size());
  auto v = y;
  EXPECT_THROW(chain.ring_damper_membrane_step(y.data(), 1e-7, v.data(), d.data()), std::logic_error);
  chain.set_implicit_membrane(true);
  for (double h : {0.0, -1e-7, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(chain.ring_damper_membrane_step(y.data(), h, v.data(), d.data()), std::invalid_argument);

  using namespace ringcrush::compare;
  const std::string scene = test_scenes::minimal_dynamic + R"([hinge]
level = 2
integrator = "central_difference"
)";
  try {
    parse_scene(scene + "level2_implicit_membrane = 1\n", "bad.toml");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("level2_implicit_membrane"), std::string::npos) << what;
    EXPECT_NE(what.find("true or false"), std::string::npos) << what;
  }
  const Scene off = parse_scene(scene + "level2_implicit_membrane = false\n", "off.toml");
  EXPECT_FALSE(level2_settings(off, HingeIntegrator::CentralDifference).central_difference_implicit_membrane);
  const Scene unset = parse_scene(scene, "unset.toml");  // the central difference's default: on
  EXPECT_FALSE(unset.hinge.level2_implicit_membrane.has_value());
  EXPECT_TRUE(level2_settings(unset, HingeIntegrator::CentralDifference).central_difference_implicit_membrane);
  EXPECT_FALSE(level2_settings(unset, HingeIntegrator::Ida).central_difference_implicit_membrane);
}

