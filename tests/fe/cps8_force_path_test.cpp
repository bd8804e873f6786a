// The force-only CPS8 path (cps8_force, used by the explicit driver) against the reference
// path (cps8_evaluate with the tangent, which forms Bᵀ S): same internal force, energies and
// trial point states to round-off (1e-12 relative) on random distorted elements with a
// finite rotation, elastic and yielding states, for all three integration rules
// (thesis §3.6.1.4).
#include <gtest/gtest.h>

#include <random>

#include "cps8_random_elements.hpp"

using namespace ringcrush::fe;

namespace {

constexpr double kTol = 1e-12;

const char* name(Integration r) {
  return r == Integration::Full ? "full" : r == Integration::Reduced ? "reduced" : "selective";
}

double rel(double a, double b, double scale) { return std::abs(a - b) / std::max(scale, 1e-300); }

// Compares both paths on `count` random elements; returns the number of points that yielded.
int compare_paths(Integration rule, double strain, bool near_yield, int count, unsigned seed) {
  const J2PlaneStress material(kernel_test::thesis_steel());
  std::mt19937 rng(seed);
  int yielded = 0;
  for (int k = 0; k < count; ++k) {
    const auto el = kernel_test::random_element(rng, strain, near_yield);
    const Cps8Geometry geo = cps8_geometry(el.x, rule, 0.0125);
    std::vector<PointState> fast(9), ref(9);
    Cps8Output of, orf;
    cps8_evaluate(geo, el.du, el.committed.data(), fast.data(), material, false, of);
    cps8_evaluate(geo, el.du, el.committed.data(), ref.data(), material, true, orf);
    const std::string where = std::string(name(rule)) + " element " + std::to_string(k);
    EXPECT_LE((of.force - orf.force).norm(), kTol * orf.force.norm()) << where;
    EXPECT_LE(rel(of.elastic_energy, orf.elastic_energy, orf.elastic_energy), kTol) << where;
    EXPECT_LE(rel(of.plastic_work, orf.plastic_work, orf.plastic_work), kTol) << where;
    for (int i = 0; i < geo.points; ++i) {
      const PointState &a = fast[i], &b = ref[i];
      EXPECT_LE((a.stress - b.stress).norm(), kTol * b.stress.norm()) << where << " point " << i;
      EXPECT_LE((a.plastic_strain - b.plastic_strain).norm(), kTol * std::max(b.plastic_strain.norm(), 1e-6))
          << where << " point " << i;
      EXPECT_LE(rel(a.peeq, b.peeq, std::max(b.peeq, 1e-6)), kTol) << where << " point " << i;
      EXPECT_LE(rel(a.plastic_work, b.plastic_work, std::max(b.plastic_work, 1.0)), kTol) << where;
      EXPECT_LE(rel(a.thickness_stretch, b.thickness_stretch, 1.0), kTol) << where << " point " << i;
      if (b.peeq > el.committed[i].peeq) ++yielded;
    }
  }
  return yielded;
}

const Integration rules[] = {Integration::Full, Integration::Reduced, Integration::Selective};

}  // namespace

TEST(Cps8ForcePath, MatchesReferenceOnElasticSteps) {
  for (const Integration rule : rules) EXPECT_EQ(compare_paths(rule, 1e-4, false, 200, 1), 0) << name(rule);
}

TEST(Cps8ForcePath, MatchesReferenceOnYieldingSteps) {
  for (const Integration rule : rules) {
    const int yielded = compare_paths(rule, 1e-2, true, 200, 2);
    // Most points must actually go through the return mapping, else this test proves nothing.
    EXPECT_GT(yielded, 100 * (rule == Integration::Reduced ? 4 : 9)) << name(rule);
  }
}

TEST(Cps8ForcePath, MatchesReferenceOnMixedSteps) {
  // Points just below yield with small increments: some yield, some unload elastically.
  for (const Integration rule : rules) {
    const int yielded = compare_paths(rule, 3e-3, true, 200, 3);
    EXPECT_GT(yielded, 0) << name(rule);
  }
}
