// The return mapping's bitwise savings (session 14, h49): the hardening table searched once per
// Newton iterate, its differences tabulated, f′(0) formed without a second evaluation of f(0),
// the bracket end 1/(2G) not evaluated where a bound shows f negative there, and the tangent's
// inputs skipped on the force-only path. Each must leave every bit of J2Update as it was: the
// reference below is the session-13 return mapping and hardening table, frozen verbatim, and
// both paths (update(), update_stress()) are compared to it bit for bit on random plastic and
// elastic increments from random committed states, for tables of one, two and four points
// (one falling). A last test shows the comparison can fail: the reference with its f′(0)
// perturbed by one ulp moves the result.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "fe/material/j2_plane_stress.hpp"

using namespace ringcrush::fe;

namespace {

// The session-13 HardeningTable (j2_plane_stress.cpp at cd067af).
struct ReferenceTable {
  std::vector<HardeningPoint> points_;
  double yield_stress(double a) const {
    if (a <= 0.0) return points_.front().yield_stress_pa;
    for (std::size_t i = 1; i < points_.size(); ++i) {
      const auto& p = points_[i - 1];
      const auto& q = points_[i];
      if (a < q.plastic_strain)
        return p.yield_stress_pa + (q.yield_stress_pa - p.yield_stress_pa) * (a - p.plastic_strain) /
                                       (q.plastic_strain - p.plastic_strain);
    }
    return points_.back().yield_stress_pa;
  }
  double slope(double a) const {
    for (std::size_t i = 1; i < points_.size(); ++i) {
      const auto& p = points_[i - 1];
      const auto& q = points_[i];
      if (a < q.plastic_strain) return (q.yield_stress_pa - p.yield_stress_pa) / (q.plastic_strain - p.plastic_strain);
    }
    return 0.0;
  }
};

// The session-13 J2PlaneStress::return_map (cd067af), `df0_ulps` nudging f′(0) for the
// can-fail test.
J2Update reference_return_map(const MaterialInput& m, const Vec3& strain_increment, const PointState& committed,
                              bool want_tangent, int df0_ulps = 0) {
  const double e_ = m.youngs_modulus_pa, nu_ = m.poisson_ratio, g_ = e_ / (2.0 * (1.0 + nu_));
  const ReferenceTable table_{m.hardening};
  Mat3 c_, p_;
  const double ff = e_ / (1.0 - nu_ * nu_);
  c_ << ff, ff * nu_, 0, ff * nu_, ff, 0, 0, 0, g_;
  const Mat3 c_inv_ = c_.inverse();
  p_ << 2.0 / 3.0, -1.0 / 3.0, 0, -1.0 / 3.0, 2.0 / 3.0, 0, 0, 0, 2.0;

  J2Update out;
  out.peeq = committed.peeq;
  const Vec3 trial = committed.stress + c_ * strain_increment;
  const double sy_n = table_.yield_stress(committed.peeq);
  const double xi_trial = trial.dot(p_ * trial);
  const double f_trial = 0.5 * xi_trial - sy_n * sy_n / 3.0;
  if (f_trial <= 1e-12 * sy_n * sy_n) {
    out.stress = trial;
    if (want_tangent) out.tangent = c_;
    else out.tangent.setZero();
    out.elastic_energy = 0.5 * trial.dot(c_inv_ * trial);
    out.strain33_increment = -nu_ / e_ * (trial(0) + trial(1) - committed.stress(0) - committed.stress(1));
    return out;
  }
  const double a1 = (trial(0) + trial(1)) * (trial(0) + trial(1)) / 6.0;
  const double a2 = 0.5 * (trial(1) - trial(0)) * (trial(1) - trial(0)) + 2.0 * trial(2) * trial(2);
  const double c1 = e_ / (3.0 * (1.0 - nu_));
  const double c2 = 2.0 * g_;
  const double sq23 = std::sqrt(2.0 / 3.0);
  auto xi_of = [&](double dg, double& dxi) {
    const double d1 = 1.0 + c1 * dg, d2 = 1.0 + c2 * dg;
    dxi = -2.0 * a1 * c1 / (d1 * d1 * d1) - 2.0 * a2 * c2 / (d2 * d2 * d2);
    return a1 / (d1 * d1) + a2 / (d2 * d2);
  };
  auto residual = [&](double dg, double& df) {
    double dxi;
    const double xi = xi_of(dg, dxi);
    const double sxi = std::sqrt(xi);
    const double alpha = committed.peeq + sq23 * dg * sxi;
    const double dalpha = sq23 * (sxi + dg * dxi / (2.0 * sxi));
    const double sy = table_.yield_stress(alpha);
    df = 0.5 * dxi - 2.0 / 3.0 * sy * table_.slope(alpha) * dalpha;
    return 0.5 * xi - sy * sy / 3.0;
  };
  double lo = 0.0, hi = 1.0 / c2, df = 0.0;
  while (residual(hi, df) > 0.0) hi *= 2.0;
  double dg = 0.0;
  double f = f_trial;
  residual(dg, df);
  for (int k = 0; k < std::abs(df0_ulps); ++k) df = std::nextafter(df, df0_ulps > 0 ? 1e300 : -1e300);
  const double ftol = 1e-14 * sy_n * sy_n;
  for (int it = 0; it < 200; ++it) {
    double next = dg - f / df;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    dg = next;
    f = residual(dg, df);
    if (f > 0.0) lo = dg; else hi = dg;
    if (std::abs(f) <= ftol || hi - lo <= 1e-15 * hi) break;
  }
  Mat3 xi_mat = (c_inv_ + dg * p_).inverse();
  const Vec3 s = xi_mat * (c_inv_ * trial);
  const Vec3 ps = p_ * s;
  const double xi = s.dot(ps);
  const double alpha = committed.peeq + sq23 * dg * std::sqrt(xi);
  const double h = table_.slope(alpha);
  const Vec3 n = xi_mat * ps;
  const double beta = 2.0 / 3.0 * h * xi / (1.0 - 2.0 / 3.0 * h * dg);
  out.stress = s;
  if (want_tangent) out.tangent = xi_mat - n * n.transpose() / (ps.dot(n) + beta);
  else out.tangent.setZero();
  out.plastic = true;
  out.plastic_increment = dg * ps;
  out.peeq = alpha;
  out.dissipation = 0.5 * (s + committed.stress).dot(out.plastic_increment);
  out.elastic_energy = 0.5 * s.dot(c_inv_ * s);
  out.strain33_increment = -nu_ / e_ * (s(0) + s(1) - committed.stress(0) - committed.stress(1)) -
                           out.plastic_increment(0) - out.plastic_increment(1);
  return out;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every field of J2Update bit for bit; the number of fields that differ.
int differing_fields(const J2Update& a, const J2Update& b) {
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    n += !same_bits(a.stress(i), b.stress(i));
    n += !same_bits(a.plastic_increment(i), b.plastic_increment(i));
    for (int j = 0; j < 3; ++j) n += !same_bits(a.tangent(i, j), b.tangent(i, j));
  }
  n += !same_bits(a.peeq, b.peeq) + !same_bits(a.dissipation, b.dissipation);
  n += !same_bits(a.strain33_increment, b.strain33_increment) + !same_bits(a.elastic_energy, b.elastic_energy);
  n += a.plastic != b.plastic;
  return n;
}

MaterialInput material_with(std::vector<HardeningPoint> table) {
  MaterialInput m;
  m.youngs_modulus_pa = 202e9;
  m.poisson_ratio = 0.3;
  m.hardening = std::move(table);
  return m;
}

// Random committed states on or inside the current yield surface (some beyond the table's
// end) and increments from elastic to strongly plastic, including large trial overshoots that
// need the bracket loop.
struct Case {
  PointState committed;
  Vec3 increment;
};
std::vector<Case> random_cases(const MaterialInput& m, unsigned seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const ReferenceTable table{m.hardening};
  std::vector<Case> cases;
  for (int k = 0; k < count; ++k) {
    Case c;
    c.committed.peeq = k % 7 == 0 ? 0.0 : 0.05 * std::abs(u(rng));
    const Vec3 dir(u(rng), u(rng), 0.5 * u(rng));
    const double sy = table.yield_stress(c.committed.peeq);
    c.committed.stress = dir * (std::abs(u(rng)) * sy / std::max(1e-3, mises(dir)));
    const double scale = k % 5 == 0 ? 5e-2 : (k % 3 == 0 ? 1e-5 : 2e-3);  // bracket doublings / elastic / plastic
    c.increment = Vec3(u(rng), u(rng), u(rng)) * scale;
    cases.push_back(c);
  }
  return cases;
}

void expect_bitwise_reference(const MaterialInput& m, unsigned seed) {
  const J2PlaneStress mat(m);
  int plastic = 0, mismatched_update = 0, mismatched_stress = 0;
  for (const Case& c : random_cases(m, seed, 4000)) {
    const J2Update ref_tangent = reference_return_map(m, c.increment, c.committed, true);
    const J2Update ref_force = reference_return_map(m, c.increment, c.committed, false);
    plastic += ref_tangent.plastic;
    mismatched_update += differing_fields(mat.update(c.increment, c.committed), ref_tangent) != 0;
    // update_stress()'s elastic branch is its own (inline) form; its plastic results are return_map's.
    if (ref_force.plastic)
      mismatched_stress += differing_fields(mat.update_stress(c.increment, c.committed), ref_force) != 0;
  }
  EXPECT_GT(plastic, 1500);  // the cases do exercise the return mapping
  EXPECT_EQ(mismatched_update, 0);
  EXPECT_EQ(mismatched_stress, 0);
}

}  // namespace

TEST(J2ReturnMapBitwise, ThesisTableMatchesTheSession13ReturnMap) {
  expect_bitwise_reference(material_with({{273e6, 0.0}, {320e6, 0.02113}}), 1);
}

TEST(J2ReturnMapBitwise, PerfectlyPlasticAndMultiSegmentTablesMatch) {
  expect_bitwise_reference(material_with({{250e6, 0.0}}), 2);
  // Four points, the last segment softening (min σy at the end: the bracket bound's minimum).
  expect_bitwise_reference(material_with({{200e6, 0.0}, {260e6, 0.01}, {300e6, 0.03}, {150e6, 0.04}}), 3);
}

TEST(J2ReturnMapBitwise, TableLookupsMatchTheSession13Table) {
  const std::vector<HardeningPoint> pts{{200e6, 0.0}, {260e6, 0.01}, {300e6, 0.03}, {150e6, 0.04}};
  const HardeningTable table(pts);
  const ReferenceTable ref{pts};
  EXPECT_EQ(table.min_yield_stress(), 150e6);
  for (double a : {-1.0, -0.0, 0.0, 1e-9, 0.005, 0.01, 0.02, 0.03, 0.035, 0.04, 0.5, std::nan("")}) {
    double sy = 0, h = 0;
    table.yield_stress_and_slope(a, sy, h);
    EXPECT_TRUE(same_bits(sy, ref.yield_stress(a))) << a;
    EXPECT_TRUE(same_bits(h, ref.slope(a))) << a;
    EXPECT_TRUE(same_bits(table.yield_stress(a), ref.yield_stress(a))) << a;
    EXPECT_TRUE(same_bits(table.slope(a), ref.slope(a))) << a;
  }
}

// The comparison above is sharp: one ulp of f′(0) in the reference changes some result bits.
TEST(J2ReturnMapBitwise, OneUlpOfTheFirstNewtonSlopeIsDetected) {
  const MaterialInput m = material_with({{273e6, 0.0}, {320e6, 0.02113}});
  const J2PlaneStress mat(m);
  int differing = 0;
  for (const Case& c : random_cases(m, 4, 400))
    differing += differing_fields(mat.update(c.increment, c.committed),
                                  reference_return_map(m, c.increment, c.committed, true, 1)) != 0;
  EXPECT_GT(differing, 0);
}
