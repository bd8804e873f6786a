// Closed forms of THEORY.md §1 against the hand-computed reference checks of §5.
#include "hinge/ring_laws.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace ringcrush::hinge;

namespace {
const RingSection test30{0.0508, 0.0016, 0.0125};  // thesis Test 30 ring
constexpr double sigma0 = 273e6, Ep = 2.2e9, E = 202e9, nu = 0.3;
constexpr double d = 0.0492;
constexpr double rel = 1e-6;

void expect_rel(double actual, double expected, double tol) {
  EXPECT_NEAR(actual, expected, std::abs(expected) * tol) << "expected " << expected;
}
}  // namespace

TEST(RingLaws, PlasticMomentAndCollapseLoad) {  // THEORY §5 #1–#4
  const double m0 = plastic_moment(test30, sigma0, SectionState::PlaneStress);
  const double m0e = plastic_moment(test30, sigma0, SectionState::PlaneStrain);
  expect_rel(m0, 2.18400, rel);
  expect_rel(m0e, 2.52187, 2e-6);
  expect_rel(collapse_load(m0, d), 355.122, 2e-6);
  expect_rel(collapse_load(m0e, d), 410.060, 2e-6);
  // Hand value quoted by the issue: P0 ≈ 355 N for d = 49.2 mm.
  EXPECT_NEAR(collapse_load(m0, test30.mean_diameter()), 355.0, 0.5);
}

TEST(RingLaws, DeRuntzHodgeLoad) {  // #5–#7
  const double p0 = collapse_load(plastic_moment(test30, sigma0, SectionState::PlaneStress), d);
  expect_rel(deruntz_hodge_load(p0, 0.5 * d, d), 410.060, 2e-6);
  expect_rel(deruntz_hodge_load(p0, 0.5 * d, d) / p0, 1.154701, rel);
  expect_rel(deruntz_hodge_load(p0, 0.25 * d, d), 366.77, 2e-5);
  expect_rel(deruntz_hodge_load(p0, 0.7 * d, d), 497.27, 2e-5);
  expect_rel(deruntz_hodge_load(p0, 0.8 * d, d), 591.87, 2e-5);
  expect_rel(deruntz_hodge_load(p0, 0.9 * d, d), 814.71, 2e-5);
  expect_rel(deruntz_hodge_load(p0, test30.lock_deflection(), d), 1403.93, 2e-6);
  // Coincidence of §1.3: P_DH(δ/d = 0.5) in plane stress is P0 in plane strain.
  const double p0e = collapse_load(plastic_moment(test30, sigma0, SectionState::PlaneStrain), d);
  expect_rel(deruntz_hodge_load(p0, 0.5 * d, d), p0e, 1e-12);
}

TEST(RingLaws, DeRuntzHodgeLimits) {
  const double p0 = 355.122;
  EXPECT_DOUBLE_EQ(deruntz_hodge_load(p0, 0.0, d), p0);  // δ → 0 gives P0
  EXPECT_NEAR(deruntz_hodge_load(p0, 1e-9 * d, d), p0, 1e-12 * p0);
  EXPECT_THROW(deruntz_hodge_load(p0, d, d), std::domain_error);
  EXPECT_THROW(deruntz_hodge_load(p0, -1e-3, d), std::domain_error);
  EXPECT_THROW(deruntz_hodge_load(p0, 1.1 * d, d), std::domain_error);
}

TEST(RingLaws, RedwoodLoad) {  // #8, #9
  const double p0 = collapse_load(plastic_moment(test30, sigma0, SectionState::PlaneStress), d);
  const double expected[] = {986.81, 698.43, 554.25, 482.15};
  const double alphas[] = {1, 2, 4, 8};
  for (int i = 0; i < 4; ++i)
    expect_rel(redwood_load(p0, Ep, sigma0, alphas[i], 0.5 * d, d), expected[i], 1e-5);
  expect_rel(redwood_load(p0, Ep, sigma0, 2, 0.25 * d, d), 491.24, 1e-5);
  expect_rel(redwood_load(p0, Ep, sigma0, 2, 0.7 * d, d), 1015.15, 1e-5);
  // E′ = 0 is DeRuntz–Hodge, and the factor is 1 at δ = 0 for any α.
  EXPECT_DOUBLE_EQ(redwood_load(p0, 0.0, sigma0, 2, 0.6 * d, d), deruntz_hodge_load(p0, 0.6 * d, d));
  EXPECT_DOUBLE_EQ(redwood_factor(Ep, sigma0, 0.5, 0.0, d), 1.0);
  EXPECT_THROW(redwood_factor(Ep, sigma0, 0.0, 0.1 * d, d), std::domain_error);
}

TEST(RingLaws, ElasticStiffnessAndFirstYield) {  // #10–#12
  expect_rel(elastic_stiffness(test30, E, nu, SectionState::PlaneStress), 389.130e3, 2e-6);
  expect_rel(elastic_stiffness(test30, E, nu, SectionState::PlaneStrain), 427.616e3, 2e-6);
  EXPECT_NEAR(std::numbers::pi / 4 - 2 / std::numbers::pi, 0.1487784, 1e-7);
  const double py = first_yield_load(test30, sigma0);
  expect_rel(py, 185.941, 3e-6);
  EXPECT_NEAR(py / elastic_stiffness(test30, E, nu, SectionState::PlaneStress) * 1e3, 0.4778, 1e-4);
  // Test 3 tube with E = 207 GPa (THEORY #25): 3351 N/mm.
  const RingSection test3{0.050, 0.0016, 0.100};
  EXPECT_NEAR(elastic_stiffness(test3, 207e9, nu, SectionState::PlaneStress) / 1e3, 3351, 1.0);
}

TEST(RingLaws, EnergiesClosedForm) {  // #13–#16
  const double m0 = plastic_moment(test30, sigma0, SectionState::PlaneStress);
  const double m0e = plastic_moment(test30, sigma0, SectionState::PlaneStrain);
  const double lock = test30.lock_deflection();
  EXPECT_NEAR(lock, 0.0476, 1e-12);
  expect_rel(deruntz_hodge_energy(m0, 0.5 * d, d), 9.1483, 1e-5);
  expect_rel(deruntz_hodge_energy(m0, lock, d), 22.977, 2e-5);
  expect_rel(deruntz_hodge_energy(m0e, lock, d), 26.531, 2e-5);
  expect_rel(4 * std::numbers::pi * m0, 27.445, 2e-5);
  const double expected[] = {63.560, 43.269, 33.123, 28.050};
  const double alphas[] = {1, 2, 4, 8};
  for (int i = 0; i < 4; ++i)
    expect_rel(redwood_energy(m0, Ep, sigma0, alphas[i], lock, d), expected[i], 2e-5);
}

// The closed-form energies against Gauss–Legendre quadrature of the loads (the integrand
// is smooth on [0, δ_lock]; 200 panels × 5 points resolves it to far below 1e-9).
TEST(RingLaws, EnergyIntegralMatchesQuadrature) {
  const double m0 = plastic_moment(test30, sigma0, SectionState::PlaneStress);
  const double p0 = collapse_load(m0, d);
  const double gx[] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
  const double gw[] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891, 0.2369268850561891};
  for (double upper : {0.3 * d, 0.7 * d, test30.lock_deflection()}) {
    double dh = 0, rw = 0;
    const int panels = 200;
    const double h = upper / panels;
    for (int k = 0; k < panels; ++k)
      for (int g = 0; g < 5; ++g) {
        const double x = (k + 0.5) * h + 0.5 * h * gx[g];
        dh += 0.5 * h * gw[g] * deruntz_hodge_load(p0, x, d);
        rw += 0.5 * h * gw[g] * redwood_load(p0, Ep, sigma0, 1.5, x, d);
      }
    expect_rel(deruntz_hodge_energy(m0, upper, d), dh, 1e-9);
    expect_rel(redwood_energy(m0, Ep, sigma0, 1.5, upper, d), rw, 1e-9);
  }
}

TEST(RingLaws, InertiaFactorAndMass) {  // #17, #18
  expect_rel(dh_inertia_factor(0.0), 0.712389, 1e-6);
  expect_rel(dh_inertia_factor(0.3), 0.718504, 1e-6);
  expect_rel(dh_inertia_factor(0.7), 0.586564, 1e-6);
  expect_rel(dh_inertia_factor(1.2), 0.173875, 1e-5);
  EXPECT_NEAR(dh_inertia_factor(0.0), 3 * std::numbers::pi / 2 - 4, 1e-14);
  for (double phi : {0.1, 0.5, 1.0, 1.4}) {
    const double h = 1e-6;
    const double fd = (dh_inertia_factor(phi + h) - dh_inertia_factor(phi - h)) / (2 * h);
    EXPECT_NEAR(dh_inertia_factor_derivative(phi), fd, 1e-8);
    const double fd2 = (dh_inertia_factor_derivative(phi + h) - dh_inertia_factor_derivative(phi - h)) / (2 * h);
    EXPECT_NEAR(dh_inertia_factor_second_derivative(phi), fd2, 1e-8);
  }
  expect_rel(ring_mass(test30, 7850), 24.267e-3, 2e-5);
  expect_rel(ring_mass(test30, 8410), 25.998e-3, 2e-5);
}

TEST(RingLaws, Tables1Checks) {  // #25, #26
  const RingSection test3{0.050, 0.0016, 0.100};
  const double d3 = test3.mean_diameter();
  const double m0 = plastic_moment(test3, 269e6, SectionState::PlaneStress);
  const double m0e = plastic_moment(test3, 269e6, SectionState::PlaneStrain);
  EXPECT_NEAR(collapse_load(m0, d3), 2845.6, 0.1);
  EXPECT_NEAR(collapse_load(m0e, d3), 3285.8, 0.1);
  EXPECT_NEAR(deruntz_hodge_energy(m0, test3.lock_deflection(), d3), 180.83, 0.01);
  EXPECT_NEAR(deruntz_hodge_energy(m0e, test3.lock_deflection(), d3), 208.80, 0.01);
  const double m0al = plastic_moment(test3, 100e6, SectionState::PlaneStress);
  EXPECT_NEAR(collapse_load(m0al, d3), 1057.85, 0.01);
  EXPECT_NEAR(deruntz_hodge_energy(m0al, test3.lock_deflection(), d3), 67.22, 0.01);
}

TEST(RingLaws, RejectsNonPhysicalInput) {
  EXPECT_THROW(plastic_moment({0.05, 0.0, 0.01}, sigma0, SectionState::PlaneStress), std::domain_error);
  EXPECT_THROW(plastic_moment({0.05, 0.001, 0.01}, -1.0, SectionState::PlaneStress), std::domain_error);
  EXPECT_THROW(collapse_load(1.0, 0.0), std::domain_error);
  EXPECT_THROW(elastic_stiffness(test30, -E, nu, SectionState::PlaneStress), std::domain_error);
}
