// Verification (c): the J2 plane-stress material point alone (STYLE.md practice 2, 10).
// Uniaxial and equibiaxial plane-stress paths against the hardening table, the algorithmic
// tangent against central finite differences, elastic unloading.
#include <gtest/gtest.h>

#include <cmath>

#include "fe/material/j2_plane_stress.hpp"

using namespace ringcrush::fe;

namespace {

MaterialInput thesis_material() {
  MaterialInput m;
  m.youngs_modulus_pa = 202e9;
  m.poisson_ratio = 0.3;
  m.hardening = {{273e6, 0.0}, {320e6, 0.02113}};
  return m;
}

// Advances a committed state by a strain increment and returns the committed result.
PointState step(const J2PlaneStress& mat, const PointState& s, const Vec3& de) {
  const J2Update u = mat.update(de, s);
  PointState n = s;
  n.stress = u.stress;
  n.peeq = u.peeq;
  n.plastic_strain += u.plastic_increment;
  return n;
}

// Uniaxial stress in direction 1: find Δε22 with S22 = 0 by Newton on the tangent.
PointState uniaxial_step(const J2PlaneStress& mat, const PointState& s, double de11) {
  Vec3 de(de11, -0.3 * de11, 0.0);
  for (int it = 0; it < 50; ++it) {
    const J2Update u = mat.update(de, s);
    if (std::abs(u.stress(1)) < 1e-6) break;
    de(1) -= u.stress(1) / u.tangent(1, 1);
  }
  return step(mat, s, de);
}

}  // namespace

TEST(J2PlaneStress, HardeningTableIsPiecewiseLinearAndFlatAfterLastPoint) {
  HardeningTable t({{100e6, 0.0}, {150e6, 0.1}, {160e6, 0.3}});
  EXPECT_DOUBLE_EQ(t.yield_stress(0.0), 100e6);
  EXPECT_NEAR(t.yield_stress(0.05), 125e6, 1e-6);
  EXPECT_NEAR(t.yield_stress(0.2), 155e6, 1e-6);
  EXPECT_DOUBLE_EQ(t.yield_stress(5.0), 160e6);
  EXPECT_NEAR(t.slope(0.05), 500e6, 1e-3);
  EXPECT_NEAR(t.slope(0.2), 50e6, 1e-3);
  EXPECT_EQ(t.slope(0.5), 0.0);
  EXPECT_THROW(HardeningTable({{100e6, 0.1}}), std::invalid_argument);
  EXPECT_THROW(HardeningTable({{100e6, 0.0}, {90e6, 0.0}}), std::invalid_argument);
}

TEST(J2PlaneStress, UniaxialPathFollowsTheTable) {
  const auto m = thesis_material();
  const J2PlaneStress mat(m);
  PointState s;
  const HardeningTable table(m.hardening);
  double eps = 0.0;
  for (int k = 0; k < 400; ++k) {
    const double de = 1e-4;
    s = uniaxial_step(mat, s, de);
    eps += de;
    ASSERT_NEAR(s.stress(1), 0.0, 1e-3);
    ASSERT_NEAR(s.stress(2), 0.0, 1e-3);
    if (s.peeq > 0) {
      // On the yield surface: σ = σy(ᾱ), and ε11 = σ/E + ᾱ (uniaxial: εp11 = ᾱ).
      EXPECT_NEAR(s.stress(0), table.yield_stress(s.peeq), 1e-6 * 320e6);
      EXPECT_NEAR(eps, s.stress(0) / m.youngs_modulus_pa + s.peeq, 1e-9);
    } else {
      EXPECT_NEAR(s.stress(0), m.youngs_modulus_pa * eps, 1e-6 * m.youngs_modulus_pa * eps + 1.0);
    }
  }
  EXPECT_GT(s.peeq, 0.03);  // went past the last table point
  EXPECT_NEAR(s.stress(0), 320e6, 1.0);
}

TEST(J2PlaneStress, EquibiaxialPathFollowsTheTable) {
  const auto m = thesis_material();
  const J2PlaneStress mat(m);
  const HardeningTable table(m.hardening);
  PointState s;
  double eps = 0.0;
  for (int k = 0; k < 300; ++k) {
    s = step(mat, s, Vec3(1e-4, 1e-4, 0));
    eps += 1e-4;
    EXPECT_NEAR(s.stress(0), s.stress(1), 1e-6 * std::abs(s.stress(0)));
    if (s.peeq > 0) {
      EXPECT_NEAR(mises(s.stress), table.yield_stress(s.peeq), 1e-6 * 320e6);
      // εp11 = εp22 = ᾱ/2; elastic part σ(1 − ν)/E.
      EXPECT_NEAR(eps, s.stress(0) * (1 - m.poisson_ratio) / m.youngs_modulus_pa + 0.5 * s.peeq, 1e-9);
    }
  }
  EXPECT_GT(s.peeq, 0.025);
}

TEST(J2PlaneStress, AlgorithmicTangentMatchesFiniteDifferences) {
  const auto m = thesis_material();
  const J2PlaneStress mat(m);
  // States: virgin, on the hardening segment, on the flat part; increments of mixed sign.
  std::vector<PointState> states(3);
  states[1].stress = Vec3(200e6, -50e6, 60e6);
  states[1].peeq = 0.005;
  states[2].stress = Vec3(-250e6, 40e6, -80e6);
  states[2].peeq = 0.05;
  const std::vector<Vec3> increments{Vec3(2e-3, -1e-3, 1.5e-3), Vec3(-4e-3, 2e-3, 1e-3), Vec3(1e-3, 3e-3, -2e-3),
                                     Vec3(1e-4, 0, 0)};
  int plastic = 0;
  for (const auto& s : states)
    for (const auto& de : increments) {
      const J2Update u = mat.update(de, s);
      plastic += u.plastic;
      const double h = 1e-9;
      Mat3 fd;
      for (int j = 0; j < 3; ++j) {
        Vec3 p = de, q = de;
        p(j) += h;
        q(j) -= h;
        fd.col(j) = (mat.update(p, s).stress - mat.update(q, s).stress) / (2 * h);
      }
      const double err = (fd - u.tangent).norm() / u.tangent.norm();
      EXPECT_LT(err, 1e-6) << "state peeq " << s.peeq << " increment " << de.transpose();
      EXPECT_LT((u.tangent - u.tangent.transpose()).norm(), 1e-9 * u.tangent.norm());
    }
  EXPECT_GE(plastic, 8);  // the check covered plastic steps, not only elastic ones
}

TEST(J2PlaneStress, UnloadingIsElastic) {
  const auto m = thesis_material();
  const J2PlaneStress mat(m);
  PointState s;
  for (int k = 0; k < 100; ++k) s = uniaxial_step(mat, s, 1e-4);
  ASSERT_GT(s.peeq, 0.005);
  const Vec3 de(-5e-4, 1e-4, 2e-4);
  const J2Update u = mat.update(de, s);
  EXPECT_FALSE(u.plastic);
  EXPECT_EQ(u.peeq, s.peeq);
  EXPECT_LT((u.stress - s.stress - mat.elastic_tangent() * de).norm(), 1e-6);
  EXPECT_LT((u.tangent - mat.elastic_tangent()).norm(), 1e-6);
}
