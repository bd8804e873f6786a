// The Level 2 hinge rotation without an atan2 per bar (hinge/polygon_hinge_angle.hpp): its
// series against atan in long double, and the whole rotation against the wrapped difference
// of the bars' angles it replaces, across the series' branch boundary and the range's ends.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "hinge/polygon_hinge_angle.hpp"

using namespace ringcrush::hinge;

namespace {

constexpr long double pi_l = 3.141592653589793238462643383279502884L;

// The rotation the bars' angles give, wrap(β_{k−1} − β_k) − turn0, in long double.
long double wrapped_rotation(long double beta_prev, long double beta, long double turn0) {
  long double tau = beta_prev - beta;
  while (tau > pi_l) tau -= 2 * pi_l;
  while (tau <= -pi_l) tau += 2 * pi_l;
  return tau - turn0;
}

// (cross, dot) of bar k and bar k − 1 turned back by turn0, as polygon_ring_forces.cpp forms
// them from the bars' unit vectors.
double rotation_of_bars(double beta_prev, double beta, double turn0) {
  const double px = std::cos(beta_prev), py = std::sin(beta_prev);
  const double ex = std::cos(beta), ey = std::sin(beta);
  const double c = std::cos(turn0), s = std::sin(turn0);
  const double tx = px * c + py * s, ty = py * c - px * s;
  return hinge_rotation(ex * ty - ey * tx, ex * tx + ey * ty, turn0);
}

}  // namespace

// Within 1.25 ulp of atan on the whole series range: one missing term (w²¹/21, 5e-16 of the
// result at w = 0.2) or a wrong coefficient fails it.
TEST(PolygonHingeAngle, SeriesIsAtanToAnUlp) {
  double worst = 0.0;
  for (int i = -4000; i <= 4000; ++i) {
    const double w = kHingeSeriesLimit * i / 4000.0;
    const long double ref = std::atan(static_cast<long double>(w));
    const double ulp = std::nextafter(std::abs(static_cast<double>(ref)), 1.0) - std::abs(static_cast<double>(ref));
    const double err = w == 0.0 ? std::abs(small_atan(w)) : static_cast<double>(std::abs(small_atan(w) - ref)) / ulp;
    worst = std::max(worst, err);
  }
  EXPECT_LE(worst, 1.25);
  EXPECT_EQ(small_atan(0.0), 0.0);
  EXPECT_EQ(small_atan(-0.1), -small_atan(0.1));  // odd
}

// Random bar pairs over every rotation: the same angle as the wrapped difference of the bars'
// angles to 2e-15 rad, in the same range (−π − turn0, π − turn0] (N = 48 and N = 8).
TEST(PolygonHingeAngle, RotationIsTheWrappedDifferenceOfTheBarAngles) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> beta(-std::numbers::pi, std::numbers::pi), theta(-3.3, 3.3), small(-0.5, 0.5);
  for (const int n : {48, 8}) {
    const double turn0 = 2.0 * std::numbers::pi / n;
    double worst = 0.0;
    int series = 0;
    for (int i = 0; i < 200000; ++i) {
      const double b = beta(rng);
      const double th = i % 2 ? small(rng) : theta(rng);  // half of them near the rest angle
      const double b_prev = b + turn0 + th;
      const long double ref = wrapped_rotation(b_prev, b, turn0);
      const double got = rotation_of_bars(b_prev, b, turn0);
      worst = std::max(worst, static_cast<double>(std::abs(got - ref)));
      if (std::abs(got) <= 2.0 * std::atan(kHingeSeriesLimit)) ++series;
      ASSERT_GT(got, -std::numbers::pi - turn0 - 1e-12);
      ASSERT_LE(got, std::numbers::pi - turn0 + 1e-12);
    }
    EXPECT_LE(worst, 2e-15) << "N = " << n;
    EXPECT_GT(series, 50000);  // the series branch is exercised
  }
}

// Across the branch boundary |w| = 0.2 (|θ| = 2 atan 0.2) and across the range's end θ = π − turn0
// (where the full turn wraps to −π − turn0) the rotation stays the bars' rotation.
TEST(PolygonHingeAngle, BranchBoundaryAndRangeEnd) {
  const double turn0 = 2.0 * std::numbers::pi / 48;
  const double edge = 2.0 * std::atan(kHingeSeriesLimit);
  for (const double sign : {1.0, -1.0})
    for (int i = -50; i <= 50; ++i) {
      const double th = sign * (edge + i * 1e-10);
      const double b = 0.3;
      EXPECT_NEAR(rotation_of_bars(b + turn0 + th, b, turn0), static_cast<double>(wrapped_rotation(b + turn0 + th, b, turn0)),
                  2e-15)
          << th;
    }
  const double end = std::numbers::pi - turn0;
  EXPECT_NEAR(rotation_of_bars(1.0 + turn0 + end - 1e-6, 1.0, turn0), end - 1e-6, 1e-12);
  EXPECT_NEAR(rotation_of_bars(1.0 + turn0 + end + 1e-6, 1.0, turn0), end + 1e-6 - 2.0 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(rotation_of_bars(1.0 + turn0 - 1e-3, 1.0, turn0), -1e-3, 1e-15);
}
