// The half model's damper + membrane band two rings to a vector (assemble_ring_bands,
// hinge/polygon_band_lanes.cpp) against the ring-by-ring assembly (assemble_ring_band): every
// band slot and every bar direction to the bit, on distorted rings, with the lanes full and
// with a spare lane; and the chain's kick and damper step, whose band is the lane one, against
// the same calls with the lanes off (PolygonChain::set_ring_lanes(false): the per-ring band).
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "hinge/polygon_band_lanes.hpp"
#include "hinge/polygon_band_solve.hpp"
#include "hinge/polygon_chain.hpp"
#include "hinge/ring_lanes.hpp"
#include "two_ring_chain.hpp"

using namespace ringcrush::hinge;

#ifndef __FMA__  // a build with FMA keeps the ring-by-ring band (polygon_implicit_dampers.cpp)
namespace {

using two_ring_chain::distorted;

// `rings` Test 30 rings two diameters apart (half model), nothing touching.
PolygonChainInput apart(int rings) { return two_ring_chain::apart(rings, true); }

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct Band {
  std::vector<double> c, bar_e;
};

// The band of every ring, C(i, i − q) of ring r at (6 i + q) S + r, and the bars' e.
Band ring_by_ring(const PolygonChain& chain, const double* y, double c_bar, double c_hinge) {
  const int n_ind = chain.independent_nodes(), rings = chain.ring_count(), S = band_lane_count(rings);
  Band b{std::vector<double>(static_cast<std::size_t>(12 * n_ind * S), 0.0),
         std::vector<double>(static_cast<std::size_t>(2 * (n_ind - 1) * rings), 0.0)};
  std::vector<double> scratch(ring_band_scratch_size(n_ind), 0.0);
  for (int r = 0; r < rings; ++r)
    assemble_ring_band(y + chain.node_offset(r, 0), n_ind, c_bar, c_hinge, b.c.data() + r, S, scratch.data(),
                       b.bar_e.data() + 2 * (n_ind - 1) * r);
  return b;
}

Band in_lanes(const PolygonChain& chain, const double* y, double c_bar, double c_hinge, int width) {
  const int n_ind = chain.independent_nodes(), rings = chain.ring_count(), S = band_lane_count(rings);
  Band b{std::vector<double>(static_cast<std::size_t>(12 * n_ind * S), 0.0),
         std::vector<double>(static_cast<std::size_t>(2 * (n_ind - 1) * rings), 0.0)};
  std::vector<double> scratch(ring_band_scratch_size(n_ind), 0.0);
  assemble_ring_bands(y, chain.node_offset(1, 0) - chain.node_offset(0, 0), rings, n_ind, c_bar, c_hinge,
                      b.c.data(), scratch.data(), b.bar_e.data(), width);
  return b;
}

// The slots where the two bands differ in their bits.
int differing(const std::vector<double>& a, const std::vector<double>& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += !same_bits(a[i], b[i]);
  return n;
}

// `width` rings to a vector against ring by ring: three rings (a spare lane in use), four (the
// vectors full), five and seven (quads, then a pair or a quad with a spare lane), two successive
// states each (the scratch reused), with the bar and hinge coefficients of the kick: every slot
// of the interleaved band and every bar's e to the bit; each ring's lane non-trivial (a zero
// band would pass the comparison), the spare lane left 0; and one slot changed by one ulp is
// seen.
void expect_same_as_ring_by_ring(int width) {
  for (const int rings : {3, 4, 5, 7}) {
    PolygonChain chain(apart(rings));
    std::mt19937 gen(47 + rings);
    const int n_ind = chain.independent_nodes(), S = band_lane_count(rings);
    for (int state = 0; state < 2; ++state) {
      const auto y = distorted(chain, gen);
      const double c_bar = 3.7 + state, c_hinge = 1.3e-4 * (state + 1);
      const Band ref = ring_by_ring(chain, y.data(), c_bar, c_hinge);
      const Band lane = in_lanes(chain, y.data(), c_bar, c_hinge, width);
      EXPECT_EQ(differing(ref.c, lane.c), 0) << rings << " rings, state " << state;
      EXPECT_EQ(differing(ref.bar_e, lane.bar_e), 0) << rings << " rings, state " << state;
      for (int r = 0; r < S; ++r) {
        int nonzero = 0;
        for (int i = 0; i < 12 * n_ind; ++i) nonzero += lane.c[static_cast<std::size_t>(i * S + r)] != 0.0;
        if (r < rings)
          EXPECT_GT(nonzero, 9 * n_ind) << "ring " << r;  // ≈ 11 of a node's 12 slots
        else
          EXPECT_EQ(nonzero, 0) << "spare lane";
      }
      auto changed = ref.c;
      const auto slot = static_cast<std::size_t>((6 * (n_ind + 1) + 2) * S + rings - 1);
      ASSERT_NE(changed[slot], 0.0);
      changed[slot] = std::nextafter(changed[slot], 1.0);
      EXPECT_EQ(differing(changed, lane.c), 1);
    }
  }
}

}  // namespace

TEST(PolygonBandLanes, EqualsTheRingByRingAssemblyToTheBit) { expect_same_as_ring_by_ring(2); }

TEST(PolygonBandLanes, FourToAVectorEqualsTheRingByRingAssemblyToTheBit) {
  if (!band_lanes_avx2()) GTEST_SKIP() << "the CPU has no AVX2: the four-ring lanes do not run";
  expect_same_as_ring_by_ring(4);
}

// Eight to an AVX-512 vector (h63): three, four, five and seven rings are one vector with five,
// four, three and one spare lanes, whose band slots the masked stores leave alone.
TEST(PolygonBandLanes, EightToAVectorEqualsTheRingByRingAssemblyToTheBit) {
  if (ringcrush::hinge::lanes::wide_lanes_available() < 8)
    GTEST_SKIP() << "the CPU has no AVX-512F: the eight-ring lanes do not run";
  expect_same_as_ring_by_ring(8);
}

// The chain's band and solve are the lane ones: the kick and the plain damper step give v, d,
// K_m w and K_m v to the bit with the lanes on and off (ring by ring), on three rings (a spare
// lane) and five (with AVX2 a quad, then a pair with a spare lane; with AVX-512 the assembly one
// vector with three spare lanes).
TEST(PolygonBandLanes, ChainKickAndStepEqualTheRingByRingBand) {
  for (const int rings : {3, 5}) {
    PolygonChain on(apart(rings)), off(apart(rings));
    off.set_ring_lanes(false);
    for (auto* c : {&on, &off}) c->set_implicit_ring_dampers(true);
    std::mt19937 gen(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (const double h : {3e-6, 4e-8}) {
      const auto y = distorted(on, gen);
      std::vector<double> w(y.size(), 0.0);
      for (int r = 0; r < rings; ++r)
        for (int j = 1; j + 1 < on.independent_nodes(); ++j) {
          w[on.node_offset(r, j) + 2] = 10.0 * u(gen);
          w[on.node_offset(r, j) + 3] = 10.0 * u(gen);
        }
      std::vector<double> v1 = y, d1(y.size(), 0.0), v2 = y, d2(y.size(), 0.0);
      on.ring_damper_step(y.data(), h, v1.data(), d1.data());
      off.ring_damper_step(y.data(), h, v2.data(), d2.data());
      for (auto* c : {&on, &off}) c->set_implicit_membrane(true);
      std::vector<double> v3 = y, d3(y.size(), 0.0), kw3(y.size(), 0.0), kv3(y.size(), 0.0);
      std::vector<double> v4 = y, d4(y.size(), 0.0), kw4(y.size(), 0.0), kv4(y.size(), 0.0);
      on.ring_damper_membrane_kick(y.data(), h, w.data(), v3.data(), d3.data(), kw3.data(), kv3.data());
      off.ring_damper_membrane_kick(y.data(), h, w.data(), v4.data(), d4.data(), kw4.data(), kv4.data());
      for (auto* c : {&on, &off}) c->set_implicit_membrane(false);
      int compared = 0;
      for (std::size_t i = 0; i < y.size(); ++i) {
        EXPECT_TRUE(same_bits(v1[i], v2[i]) && same_bits(d1[i], d2[i])) << rings << " rings, step, h " << h << " row " << i;
        EXPECT_TRUE(same_bits(v3[i], v4[i]) && same_bits(d3[i], d4[i]) && same_bits(kw3[i], kw4[i]) &&
                    same_bits(kv3[i], kv4[i]))
            << rings << " rings, kick, h " << h << " row " << i;
        compared += v1[i] != y[i] && v3[i] != y[i] && kv3[i] != 0.0;
      }
      EXPECT_GT(compared, rings * 2 * (on.independent_nodes() - 2)) << "the step and the kick moved every inner row";
    }
  }
}
#endif
