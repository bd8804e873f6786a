// The half model's band solve (solve_ring_bands, hinge/polygon_band_solve.cpp) two rings to an
// SSE2 vector and four to an AVX one against the ring-by-ring solve: the solution v, d = C v,
// the factor L and 1/D to the bit, on distorted rings with random velocities, for ring counts
// that fill the vectors, leave a spare lane, and leave a pair after the quads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "hinge/polygon_band_lanes.hpp"
#include "hinge/polygon_band_solve.hpp"
#include "hinge/polygon_chain.hpp"
#include "two_ring_chain.hpp"

using namespace ringcrush::hinge;

#ifndef __FMA__  // a build with FMA keeps the solve two to a vector (polygon_implicit_dampers.cpp)
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

int differing(const std::vector<double>& a, const std::vector<double>& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += !same_bits(a[i], b[i]);
  return n;
}

// One solve's inputs and results: the band of `rings` distorted rings (assembled ring by ring,
// the bar coefficient of a membrane kick), the masses, v* and the arrays the solve writes.
struct Problem {
  int n_ind, rings;
  double h;
  std::vector<double> C, mu, v, d, L, inv, b;

  Problem(int ring_count, unsigned seed, double step) : rings(ring_count), h(step) {
    PolygonChain chain(two_ring_chain::apart(rings, true));
    std::mt19937 gen(seed);
    const auto y = two_ring_chain::distorted(chain, gen);
    n_ind = chain.independent_nodes();
    const int S = band_lane_count(rings);
    C.assign(static_cast<std::size_t>(12 * n_ind * S), 0.0);
    std::vector<double> scratch(ring_band_scratch_size(n_ind), 0.0);
    for (int r = 0; r < rings; ++r)
      assemble_ring_band(y.data() + chain.node_offset(r, 0), n_ind, 3.7e3, 1.3e-4, C.data() + r, S, scratch.data(),
                         nullptr);
    for (std::size_t i = 0; i < chain.size(); ++i) mu.push_back(chain.mass_row(i));
    v = y;  // v* in the node velocity rows: y's random 10 m/s
    d.assign(y.size(), 0.0);
    band_factor_rows(n_ind, rings, L, inv, b);
  }

  bool solve(int width) {
    const auto S = static_cast<std::size_t>(band_lane_count(rings));
    const BandSolve p{C.data(), L.data() + 6 * kBandPadRows * S, b.data() + kBandPadRows * S,
                      inv.data() + kBandPadRows * S, mu.data(), n_ind, rings, h, v.data(), d.data()};
    return solve_ring_bands(p, width);
  }
};

// The solve `width` rings to a vector against the ring-by-ring one: v, d, L and 1/D bitwise; the
// solve moved every inner velocity row (a solve that did nothing would pass the comparison).
void expect_same_as_ring_by_ring(int width) {
  for (const int rings : {3, 4, 5, 6, 7})
    for (const double h : {2e-7, 3e-5}) {
      Problem ref(rings, 11u + static_cast<unsigned>(rings), h), lane(rings, 11u + static_cast<unsigned>(rings), h);
      const auto v_star = ref.v;
      ASSERT_TRUE(ref.solve(1));
      ASSERT_TRUE(lane.solve(width));
      EXPECT_EQ(differing(ref.v, lane.v), 0) << rings << " rings, h " << h;
      EXPECT_EQ(differing(ref.d, lane.d), 0) << rings << " rings, h " << h;
      EXPECT_EQ(differing(ref.L, lane.L), 0) << rings << " rings, h " << h;
      EXPECT_EQ(differing(ref.inv, lane.inv), 0) << rings << " rings, h " << h;
      int moved = 0;
      for (int r = 0; r < rings; ++r)
        for (int j = 1; j + 1 < ref.n_ind; ++j) {
          const auto o = static_cast<std::size_t>((r * ref.n_ind + j) * 6 + 2);
          moved += ref.v[o] != v_star[o] && ref.v[o + 1] != v_star[o + 1] && ref.d[o] != 0.0;
        }
      EXPECT_EQ(moved, rings * (ref.n_ind - 2)) << rings << " rings, h " << h;
    }
}

}  // namespace

TEST(PolygonBandSolve, TwoRingsToAVectorEqualTheRingByRingSolve) { expect_same_as_ring_by_ring(2); }

TEST(PolygonBandSolve, FourRingsToAVectorEqualTheRingByRingSolve) {
  if (!band_lanes_avx2()) GTEST_SKIP() << "the CPU has no AVX2: the four-ring lanes do not run";
  expect_same_as_ring_by_ring(4);
}

// The comparison sees one ulp: C of the last ring changed by one ulp in one slot changes that
// ring's solution and no other ring's.
TEST(PolygonBandSolve, OneUlpInOneRingsBandIsSeen) {
  Problem ref(5, 3u, 3e-5), changed(5, 3u, 3e-5);
  const int S = band_lane_count(5);
  const auto slot = static_cast<std::size_t>((6 * (ref.n_ind + 1) + 1) * S + 4);
  ASSERT_NE(changed.C[slot], 0.0);
  changed.C[slot] = std::nextafter(changed.C[slot], 1e300);
  ASSERT_TRUE(ref.solve(1));
  ASSERT_TRUE(changed.solve(band_lanes_avx2() ? 4 : 2));
  int other = 0, own = 0;
  for (int r = 0; r < 5; ++r)
    for (int j = 0; j < ref.n_ind; ++j)
      for (int c = 2; c < 4; ++c) {
        const auto o = static_cast<std::size_t>((r * ref.n_ind + j) * 6 + c);
        (r == 4 ? own : other) += !same_bits(ref.v[o], changed.v[o]);
      }
  EXPECT_EQ(other, 0);
  EXPECT_GT(own, 0);
}

// A matrix that is not positive definite is reported (a negative mass on one node of the last
// ring: the solve takes a node's mass from its x row for both rows), on every lane width.
TEST(PolygonBandSolve, ReportsANonPositivePivotOnEveryWidth) {
  for (const int width : {1, 2, 4}) {
    Problem p(5, 7u, 3e-5);
    p.mu[static_cast<std::size_t>((4 * p.n_ind + 3) * 6 + 2)] = -1.0;
    EXPECT_FALSE(p.solve(width)) << "width " << width;
  }
}
#endif
