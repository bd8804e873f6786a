// Ring↔ring and inner-wall contact (issue 4 item 2): the node-to-surface force is the
// gradient of ½ k g²; the apex node of a half ring finds the neighbour's surface even where
// it ends on the symmetry plane; the Verlet candidate list gives exactly the brute-force
// result however stale it is (within its skin); ring pairs that cannot touch have no
// candidates; a squeezed ring's inner wall contacts itself.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "fe/chain/chain_mesh.hpp"
#include "fe/contact/ring_pair_contact.hpp"

using namespace ringcrush::fe;

namespace {
constexpr double kR = 25.4e-3;

ChainInput chain(int rings, bool half = true) {
  ChainInput in;
  in.rings = rings;
  in.mesh.elements_around = 8;
  in.mesh.half_ring = half;
  in.joints = JointKind::Free;
  in.pitch_m = 2 * kR;
  return in;
}

struct ChainPasses {
  ChainTopology t;
  std::vector<ContactPass> passes;
  double k_scale = 0;
};
ChainPasses setup(const ChainInput& in, bool self) {
  ChainPasses s{make_chain_topology(in), {}, 0};
  s.k_scale = in.material.youngs_modulus_pa * in.ring.width_m / s.t.ring.element_depth;
  for (int i = 0; i < in.rings; ++i)
    for (int j = 0; j < in.rings; ++j)
      if (i != j) s.passes.push_back(outer_pass(s.t.ring, s.t.ring_node[i], i, s.t.ring_node[j], j, s.k_scale, 0.0125, 0.25));
  if (self)
    for (int i = 0; i < in.rings; ++i)
      for (auto& p : inner_wall_passes(s.t.ring, s.t.ring_node[i], i, s.k_scale, 0.0125, 0.25, std::numbers::pi / 3, 0.0, true))
        s.passes.push_back(p);
  return s;
}
std::vector<Eigen::Vector2d> positions(const ChainTopology& t, int ring_moved, double dy, double jitter, unsigned seed) {
  std::vector<Eigen::Vector2d> x = t.mesh.nodes;
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-jitter, jitter);
  for (int n : t.ring_node[ring_moved]) x[n].y() += dy;
  for (auto& p : x) {
    if (std::abs(p.x()) > 1e-15) p.x() += d(gen);
    p.y() += d(gen);
  }
  return x;
}
}  // namespace

TEST(RingPairContact, ForceIsTheGradientOfThePenaltyEnergy) {
  // A node under a curved quadratic piece (left normal up, toward the node's side).
  CurvePiece p;
  p.count = 3;
  p.nodes = {0, 1, 2, -1, -1};
  const PiecePolynomial poly(p);
  double xy[8] = {0.1, -0.02, -1.0, 0.0, 0.05, 0.1, 1.0, 0.05};
  double f = -2, gap = 0, force[8];
  ASSERT_TRUE(surface_gap(poly, xy, 0, true, f, gap));
  ASSERT_LT(gap, 0.0);
  const double k = 3.0;
  surface_force(poly, xy, k, f, gap, force);
  double sum_x = 0, sum_y = 0;
  for (int j = 0; j < 8; ++j) {
    (j % 2 ? sum_y : sum_x) += force[j];
    const double h = 1e-7, keep = xy[j];
    double fp = f, gp = 0, fm = f, gm = 0;
    xy[j] = keep + h;
    surface_gap(poly, xy, 0, false, fp, gp);
    xy[j] = keep - h;
    surface_gap(poly, xy, 0, false, fm, gm);
    xy[j] = keep;
    EXPECT_NEAR(force[j], (0.5 * k * gp * gp - 0.5 * k * gm * gm) / (2 * h), 1e-7) << "coordinate " << j;
  }
  EXPECT_NEAR(sum_x, 0.0, 1e-15);
  EXPECT_NEAR(sum_y, 0.0, 1e-15);
}

TEST(RingPairContact, ApexNodeOnTheSymmetryPlaneFindsTheNeighbour) {
  // Ring 2 pushed into ring 1 and its top tilted (the mid-side node next to the apex lifted),
  // so the master's end tangent at x = 0 is not horizontal: the apex of ring 1 must still be
  // in contact.
  const ChainInput in = chain(2);
  ChainPasses s = setup(in, false);
  auto x = positions(s.t, 1, 0.2e-3, 0.0, 1);
  const auto& outer = s.t.mesh.ring_outer_nodes[1];
  x[outer[1]].y() += 0.05e-3;
  SurfaceContact contact(s.passes, s.t.ring.element_depth);
  std::vector<ContactContribution> out;
  SurfaceContactState st;
  contact.evaluate(x, false, out, nullptr, st);
  const int apex = s.t.mesh.ring_outer_nodes[0].back();  // θ = π: ring 1's bottom
  bool found = false;
  for (const auto& c : out)
    if (c.nodes[0] == apex) {
      found = true;
      EXPECT_LT(c.force(1), 0.0);  // residual ∂E/∂y < 0: the overlap shrinks as the apex rises
    }
  EXPECT_TRUE(found);
}

TEST(RingPairContact, CandidateListGivesTheBruteForceResult) {
  ChainInput in = chain(3);
  in.mesh.elements_around = 16;
  ChainPasses s = setup(in, true);
  SurfaceContact stale(s.passes, s.t.ring.element_depth);
  std::vector<ContactContribution> out;
  SurfaceContactState st;
  // Build the list at a first configuration, then move every node by less than the skin
  // (SurfaceContact::kSkin = 0.125 of the wall depth, 0.2 mm): at most 0.05 mm across and
  // 0.1 + 0.05 mm up.
  ASSERT_GT(SurfaceContact::kSkin * s.t.ring.element_depth, std::hypot(0.05e-3, 0.15e-3));
  stale.evaluate(positions(s.t, 1, 0.25e-3, 0.0, 2), false, out, nullptr, st);
  const long builds = stale.rebuilds();
  const auto x = positions(s.t, 1, 0.35e-3, 0.05e-3, 3);
  out.clear();
  stale.evaluate(x, true, out, nullptr, st);
  EXPECT_EQ(stale.rebuilds(), builds) << "moved less than the skin: no rebuild";
  SurfaceContact fresh(s.passes, s.t.ring.element_depth);
  std::vector<ContactContribution> ref;
  SurfaceContactState sr;
  fresh.evaluate(x, true, ref, nullptr, sr);
  ASSERT_GT(ref.size(), 2u);
  ASSERT_EQ(out.size(), ref.size());
  for (std::size_t i = 0; i < ref.size(); ++i) {
    EXPECT_EQ(out[i].nodes, ref[i].nodes);
    EXPECT_EQ(out[i].force, ref[i].force);
    EXPECT_EQ(out[i].tangent, ref[i].tangent);
  }
  EXPECT_EQ(st.energy, sr.energy);
  // Ring 1 and ring 3 cannot touch: their passes hold no candidates.
  for (std::size_t p = 0; p < s.passes.size(); ++p)
    if (!s.passes[p].self && std::abs(s.passes[p].slave_ring - s.passes[p].master_ring) == 2) {
      EXPECT_EQ(fresh.candidates(p), 0u);
    }
  EXPECT_LT(fresh.candidates(), 200u);
}

TEST(RingPairContact, SqueezedRingContactsItsInnerWall) {
  // A full ring squeezed to an ellipse whose inner walls overlap at the centre: every pass of
  // the inner wall finds contact there and none between the rings' outer surfaces.
  for (bool half : {true, false}) {
    const ChainInput in = chain(1, half);
    ChainPasses s = setup(in, true);
    std::vector<Eigen::Vector2d> x = s.t.mesh.nodes;
    // y → y (r − ri − δ)/r: the inner wall (r = ri) goes to y = ∓δ cos φ, so the inner
    // crowns cross by 2δ at the centre.
    const double ri = in.ring.inner_radius_m, delta = 0.2e-3;
    for (auto& p : x) p.y() *= (p.norm() - ri - delta) / p.norm();
    SurfaceContact contact(s.passes, s.t.ring.element_depth);
    std::vector<ContactContribution> out;
    SurfaceContactState st;
    contact.evaluate(x, false, out, nullptr, st);
    EXPECT_GT(st.active, 0) << (half ? "half" : "full");
    EXPECT_GT(st.self_force, 0.0);
    EXPECT_EQ(st.ring_ring_force, 0.0);
    EXPECT_LE(st.max_penetration, 1.01 * 2 * delta);
    EXPECT_GE(st.max_penetration, 0.99 * 2 * delta);
  }
}
