// The half model's band assembly (hinge/polygon_band_lanes.cpp) reuses its element scratch from
// call to call; an element whose coefficient is 0 must not leave there what an earlier call with
// a positive one wrote (the membrane kick's bars carry c_b + h k_m, a plain damper step at
// c_b = 0 none). Every call order gives the band of a fresh scratch, to the bit: the assembly
// ring by ring and in lanes with the coefficients switched off one at a time after a call with
// both on, and the chain's plain damper step after a membrane kick at c_b = 0 against a fresh
// chain's step, lanes on and off.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include "hinge/polygon_band_lanes.hpp"
#include "hinge/polygon_chain.hpp"
#include "two_ring_chain.hpp"

using namespace ringcrush::hinge;

namespace {

using two_ring_chain::distorted;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

int differing(const std::vector<double>& a, const std::vector<double>& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += !same_bits(a[i], b[i]);
  return n;
}

// The interleaved band (and the bars' e) of every ring with `scratch`: ring by ring (width 1)
// or `width` rings to a vector.
std::vector<double> band(const PolygonChain& chain, const double* y, double c_bar, double c_hinge, int width,
                         std::vector<double>& scratch) {
  const int n_ind = chain.independent_nodes(), rings = chain.ring_count(), S = band_lane_count(rings);
  std::vector<double> c(static_cast<std::size_t>(12 * n_ind * S), 0.0);
  std::vector<double> bar_e(static_cast<std::size_t>(2 * (n_ind - 1) * rings), 0.0);
  if (width == 1)
    for (int r = 0; r < rings; ++r)
      assemble_ring_band(y + chain.node_offset(r, 0), n_ind, c_bar, c_hinge, c.data() + r, S, scratch.data(),
                         bar_e.data() + 2 * (n_ind - 1) * r);
  else
    assemble_ring_bands(y, chain.node_offset(1, 0) - chain.node_offset(0, 0), rings, n_ind, c_bar, c_hinge,
                        c.data(), scratch.data(), bar_e.data(), width);
  c.insert(c.end(), bar_e.begin(), bar_e.end());
  return c;
}

// The chain of the kick and the step: c_b = 0 (membrane ratio 0), the hinge dampers on, the
// dampers and the membrane implicit as the central-difference driver sets them.
PolygonChain zero_bar_damping_chain(int rings, bool ring_lanes) {
  PolygonChainInput in = two_ring_chain::apart(rings, true);
  in.membrane_damping_ratio = 0.0;
  in.hinge_damping_ratio = 0.3;
  PolygonChain chain(in);
  chain.set_ring_lanes(ring_lanes);
  chain.set_implicit_ring_dampers(true);
  chain.set_implicit_membrane(true);
  return chain;
}

}  // namespace

// Five rings (with AVX2 a quad, then a pair with a spare lane): after a call with both
// coefficients on, a call with the bars' off, then one with the hinges' off, each against a
// fresh scratch; and the band of the bars-off call differs from the both-on one (the test sees
// stale bar entries).
TEST(PolygonBandCallOrder, ACoefficientOfZeroAfterAPositiveOneGivesTheFreshBand) {
  PolygonChain chain(two_ring_chain::apart(5, true));
  std::mt19937 gen(11);
  const auto y = distorted(chain, gen);
  const double c_bar = 3.7e3, c_hinge = 1.3e-4;
  for (const int width : {1, 2, 4}) {
    std::vector<double> reused(ring_band_scratch_size(chain.independent_nodes()), 0.0);
    const auto both = band(chain, y.data(), c_bar, c_hinge, width, reused);
    for (const auto& [cb, ch] : {std::pair{0.0, c_hinge}, std::pair{c_bar, 0.0}, std::pair{0.0, 0.0}}) {
      std::vector<double> fresh(reused.size(), 0.0);
      const auto expected = band(chain, y.data(), cb, ch, width, fresh);
      const auto got = band(chain, y.data(), cb, ch, width, reused);
      EXPECT_EQ(differing(expected, got), 0) << "width " << width << ", c_b " << cb << ", c_θ " << ch;
      EXPECT_GT(differing(expected, both), 0) << "width " << width << ", c_b " << cb << ", c_θ " << ch;
      band(chain, y.data(), c_bar, c_hinge, width, reused);  // both on again before the next
    }
  }
}

// The driver's two calls in the order it never makes (a membrane kick, then a plain damper step)
// at c_b = 0: the step's v and d equal a fresh chain's to the bit, ring lanes on and off; the
// step moves every inner velocity row (a non-trivial comparison).
TEST(PolygonBandCallOrder, DamperStepAfterAMembraneKickEqualsAFreshChain) {
  for (const bool ring_lanes : {true, false}) {
    PolygonChain kicked = zero_bar_damping_chain(3, ring_lanes), fresh = zero_bar_damping_chain(3, ring_lanes);
    std::mt19937 gen(23);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const auto y = distorted(kicked, gen);
    std::vector<double> w(y.size(), 0.0);
    for (int r = 0; r < kicked.ring_count(); ++r)
      for (int j = 1; j + 1 < kicked.independent_nodes(); ++j) {
        w[kicked.node_offset(r, j) + 2] = 10.0 * u(gen);
        w[kicked.node_offset(r, j) + 3] = 10.0 * u(gen);
      }
    const double h = 3e-6;
    std::vector<double> v0 = y, d0(y.size(), 0.0), kw(y.size(), 0.0), kv(y.size(), 0.0);
    kicked.ring_damper_membrane_kick(y.data(), h, w.data(), v0.data(), d0.data(), kw.data(), kv.data());
    std::vector<double> v1 = y, d1(y.size(), 0.0), v2 = y, d2(y.size(), 0.0);
    kicked.ring_damper_step(y.data(), h, v1.data(), d1.data());
    fresh.ring_damper_step(y.data(), h, v2.data(), d2.data());
    int moved = 0;
    for (std::size_t i = 0; i < y.size(); ++i) {
      EXPECT_TRUE(same_bits(v1[i], v2[i]) && same_bits(d1[i], d2[i])) << "lanes " << ring_lanes << ", row " << i;
      moved += v2[i] != y[i];
    }
    EXPECT_GT(moved, kicked.ring_count() * 2 * (kicked.independent_nodes() - 2)) << "lanes " << ring_lanes;
  }
}
