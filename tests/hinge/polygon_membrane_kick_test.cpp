// The implicit membrane's kick in one call (PolygonChain::ring_damper_membrane_kick,
// hinge/polygon_implicit_membrane.cpp) and the square-root-free band LDLᵀ under it
// (hinge/polygon_implicit_dampers.cpp): the kick against the calls it fuses, to the bit; its
// solve against a dense LDLᵀ of μ + h C + h² K_m with C read off the explicit damper forces,
// to 1e-12, with the matrix's coupling strong enough that a term left out of the factor fails
// by orders of magnitude; bad input.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "hinge/polygon_chain.hpp"
#include "two_ring_chain.hpp"

using namespace ringcrush::hinge;

namespace {

using two_ring_chain::apart;
using two_ring_chain::distorted;

// Every ring's node velocity rows (6 per node from row 0), the axis x rows included.
std::vector<std::size_t> node_velocity_rows(const PolygonChain& chain) {
  std::vector<std::size_t> rows;
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < chain.independent_nodes(); ++j) {
      rows.push_back(chain.node_offset(r, j) + 2);
      rows.push_back(chain.node_offset(r, j) + 3);
    }
  return rows;
}

using two_ring_chain::velocity_rows;

using two_ring_chain::damping_matrix;

}  // namespace

// The kick is membrane_stiffness_product(y, w), v* += h² K_m w/μ, ring_damper_membrane_step and
// membrane_stiffness_product_again(v) in one call: K_m w, v, d and K_m v equal theirs to the
// bit on every node row of every ring, on two successive calls with different states and h;
// three half-model rings (the spare lane in use) and two full rings.
TEST(PolygonMembraneKick, EqualsTheSeparateCallsToTheBit) {
  for (const bool half : {true, false}) {
    const int rings = half ? 3 : 2;
    PolygonChain fused(apart(rings, half)), separate(apart(rings, half));
    fused.set_implicit_ring_dampers(true);
    separate.set_implicit_ring_dampers(true);
    fused.set_implicit_membrane(true);
    separate.set_implicit_membrane(true);
    const auto rows = node_velocity_rows(fused);
    std::mt19937 gen(23);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (const double h : {3e-6, 4e-8}) {
      const auto y = distorted(fused, gen);
      std::vector<double> w(y.size(), 0.0);
      for (const auto r : rows) w[r] = 10.0 * u(gen);
      std::vector<double> v1 = y, d1(y.size(), 0.0), kw1(y.size(), 0.0), kv1(y.size(), 0.0);
      fused.ring_damper_membrane_kick(y.data(), h, w.data(), v1.data(), d1.data(), kw1.data(), kv1.data());
      std::vector<double> v2 = y, d2(y.size(), 0.0), kw2(y.size(), 0.0), kv2(y.size(), 0.0);
      separate.membrane_stiffness_product(y.data(), w.data(), kw2.data());
      for (const auto r : rows) v2[r] += h * h * kw2[r] * (1.0 / separate.mass_row(r));
      separate.ring_damper_membrane_step(y.data(), h, v2.data(), d2.data());
      separate.membrane_stiffness_product_again(v2.data(), kv2.data());
      double largest = 0.0;
      for (const auto r : rows) {
        EXPECT_EQ(kw1[r], kw2[r]) << "half " << half << " h " << h << " row " << r;
        EXPECT_EQ(v1[r], v2[r]) << "half " << half << " h " << h << " row " << r;
        EXPECT_EQ(d1[r], d2[r]) << "half " << half << " h " << h << " row " << r;
        EXPECT_EQ(kv1[r], kv2[r]) << "half " << half << " h " << h << " row " << r;
        largest = std::max(largest, std::abs(kv1[r]));
      }
      EXPECT_GT(largest, 0.0);
    }
  }
}

// The kick's solve against the dense system, each ring of three far-apart ones (half model:
// the band LDLᵀ, rings interleaved, a spare lane; full ring: the profile Cholesky) against a
// dense LDLᵀ of that ring's μ + h C + h² K_m, C from the explicit damper forces and K_m from
// the product column by column: v to 1e-12 of |v|, K_m w to 1e-12, d = (C + h K_m) v and K_m v
// to 1e-10 (d = μ (v* − v)/h cancels), at h with h² k_m/μ ≈ 45–90 and h c/μ > 10, where every
// product in the factor carries O(1) of the result, and at a small h (μ dominant). Leaving one
// term out of the band LDLᵀ fails (measured: the last W term of a row — the factor then stops
// being definite; the l₁ term of a pivot, of the forward or of the backward substitution —
// |Δv|/|v| 0.2–1.4 at the large h, 2e-6–6e-4 at the small one).
TEST(PolygonMembraneKick, SolveEqualsTheDenseLdlt) {
  for (const bool half : {true, false}) {
    PolygonChain rings(apart(3, half));
    rings.set_implicit_ring_dampers(true);
    rings.set_implicit_membrane(true);
    PolygonChain lone(apart(1, half));  // the dense reference, one ring at a time
    const auto rows = velocity_rows(lone);
    const auto n = static_cast<Eigen::Index>(rows.size());
    std::mt19937 gen(31);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (const double h : {3e-6, 2e-9}) {
      const auto y = distorted(rings, gen);
      std::vector<double> w(y.size(), 0.0);
      for (const auto r : node_velocity_rows(rings)) w[r] = 10.0 * u(gen);
      for (int r = 0; r < 3; ++r)
        if (half) w[rings.node_offset(r, 0) + 2] = w[rings.node_offset(r, rings.independent_nodes() - 1) + 2] = 0.0;
      std::vector<double> v = y, d(y.size(), 0.0), kw(y.size(), 0.0), kv(y.size(), 0.0);
      rings.ring_damper_membrane_kick(y.data(), h, w.data(), v.data(), d.data(), kw.data(), kv.data());
      for (int r = 0; r < 3; ++r) {
        // Ring r moved onto the lone ring's place: the same C and K_m (the bars only).
        auto y1 = lone.initial_state();
        y1[lone.body_offset(0)] += 0.01;
        const double shift =
            lone.initial_state()[lone.node_offset(0, 0) + 1] - rings.initial_state()[rings.node_offset(r, 0) + 1];
        const std::size_t at = rings.node_offset(r, 0);
        for (std::size_t k = 0; k < rings.node_offset(1, 0); ++k) y1[k] = y[at + k] + (k % 6 == 1 ? shift : 0.0);
        const Eigen::MatrixXd C = damping_matrix(lone, y1, rows);
        Eigen::MatrixXd K(n, n);
        std::vector<double> e(y1.size(), 0.0), ke(y1.size(), 0.0);
        for (Eigen::Index m = 0; m < n; ++m) {
          e[rows[static_cast<std::size_t>(m)]] = 1.0;
          lone.membrane_stiffness_product(y1.data(), e.data(), ke.data());
          e[rows[static_cast<std::size_t>(m)]] = 0.0;
          for (Eigen::Index i = 0; i < n; ++i) K(i, m) = ke[rows[static_cast<std::size_t>(i)]];
        }
        Eigen::VectorXd mu(n), vstar(n), wr(n);
        for (Eigen::Index i = 0; i < n; ++i) {
          const auto k = rows[static_cast<std::size_t>(i)];
          mu(i) = lone.mass_row(k);
          vstar(i) = y[at + k];
          wr(i) = w[at + k];
        }
        if (h > 1e-6) {
          EXPECT_GT(h * h * K.diagonal().maxCoeff() / mu.minCoeff(), 30.0);
          EXPECT_GT(h * C.diagonal().maxCoeff() / mu.minCoeff(), 10.0);
        }
        Eigen::MatrixXd A = h * C + h * h * K;
        A.diagonal() += mu;
        const Eigen::VectorXd Kw = K * wr;
        const Eigen::VectorXd dense = A.ldlt().solve(mu.cwiseProduct(vstar) + h * h * Kw);
        const Eigen::VectorXd force = (C + h * K) * dense, Kv = K * dense;
        for (Eigen::Index i = 0; i < n; ++i) {
          const auto k = at + rows[static_cast<std::size_t>(i)];
          EXPECT_NEAR(v[k], dense(i), 1e-12 * dense.norm()) << "half " << half << " h " << h << " ring " << r;
          EXPECT_NEAR(kw[k], Kw(i), 1e-12 * Kw.norm()) << "half " << half << " h " << h << " ring " << r;
          EXPECT_NEAR(d[k], force(i), 1e-10 * force.norm()) << "half " << half << " h " << h << " ring " << r;
          EXPECT_NEAR(kv[k], Kv(i), 1e-10 * Kv.norm()) << "half " << half << " h " << h << " ring " << r;
        }
      }
    }
  }
}

TEST(PolygonMembraneKick, BadInputIsNamed) {
  PolygonChain chain(apart(1, true));
  chain.set_implicit_ring_dampers(true);
  auto y = chain.initial_state();
  std::vector<double> v = y, d(y.size()), kw(y.size()), kv(y.size());
  EXPECT_THROW(chain.ring_damper_membrane_kick(y.data(), 1e-7, y.data(), v.data(), d.data(), kw.data(), kv.data()),
               std::logic_error);  // the membrane not implicit
  chain.set_implicit_membrane(true);
  for (const double h : {0.0, -1e-7, std::nan("")})
    EXPECT_THROW(chain.ring_damper_membrane_kick(y.data(), h, y.data(), v.data(), d.data(), kw.data(), kv.data()),
                 std::invalid_argument);
}
