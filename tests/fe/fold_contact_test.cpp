// The inner wall at a flattened ring's side fold (README "FE dynamics", stability matrix): the
// two legs of a fold that closes near the side point C must meet in contact. Inner-wall points
// closer than ContactInput::self_contact_min_separation_rad of reference arc are never paired;
// with the old π/3 the legs within 30° of C passed through each other unseen, and a later node
// of the next ring sat where the folded ring's top and bottom outer surfaces coincided: 0.615 mm
// from an outer piece and from an inner-facing one, the closest switching and the force jumping
// (HHT half-step residual 1.5e6 N at 5.50 ms, welded, 50 m/s, ×4 mass, t/D 0.03).
//
// Geometry: one half ring (Test 30, 16 CPS8 per half, as the matrix), y → s·y (a flattened
// ellipse whose inner walls approach without touching, the fold at C as sharp as s makes it),
// then the upper half (y > 0) moved down by d: the inner walls cross where their gap
// 2 s √(r_i² − x²) is below d, i.e. within asin(d / (2 s r_i)) of C.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fe/chain/chain_mesh.hpp"
#include "fe/contact/ring_pair_contact.hpp"
#include "fe/contact/self_contact_taper.hpp"

using namespace ringcrush::fe;

namespace {

struct FoldResult {
  int active = 0;
  double max_penetration = 0, self_force = 0;
};

FoldResult fold_contact(double min_separation, double s, double d) {
  ChainInput in;
  in.rings = 1;
  in.mesh.elements_around = 16;
  in.mesh.half_ring = true;
  in.joints = JointKind::Free;
  const ChainTopology t = make_chain_topology(in);
  const double k_scale = in.material.youngs_modulus_pa * in.ring.width_m / t.ring.element_depth;
  const std::vector<ContactPass> passes = inner_wall_passes(t.ring, t.ring_node[0], 0, k_scale, in.ring.width_m,
                                                            in.contact.smoothing, min_separation,
                                                            kSelfContactTaperBandRad, true);
  std::vector<Eigen::Vector2d> x = t.mesh.nodes;
  for (auto& p : x) {
    p.y() *= s;
    if (p.y() > 1e-12) p.y() -= d;
  }
  SurfaceContact contact(passes, t.ring.element_depth);
  std::vector<ContactContribution> out;
  SurfaceContactState st;
  contact.evaluate(x, false, out, nullptr, st);
  return {st.active, st.max_penetration, st.self_force};
}

constexpr double kRi = 23.8e-3;

}  // namespace

TEST(FoldContact, FlattenedRingWithOpenFoldHasNoInnerContact) {
  // However sharp the fold (s down to 0.03: a crease of radius s² r_i ≈ 0.02 mm at C), walls
  // that do not overlap give no contact: the shorter exclusion pairs no point with its own
  // neighbourhood of the wall.
  const double sep = ContactInput{}.self_contact_min_separation_rad;
  for (double s : {1.0, 0.5, 0.2, 0.1, 0.05, 0.03}) {
    const FoldResult r = fold_contact(sep, s, 0.0);
    EXPECT_EQ(r.active, 0) << "s = " << s;
    EXPECT_EQ(r.self_force, 0.0) << "s = " << s;
  }
}

TEST(FoldContact, ClosedFoldNearTheSideIsInContact) {
  // s = 0.05, d = 0.8 mm: the legs overlap within asin(0.8 / (2·0.05·23.8)) = 19.6° of C,
  // up to d at C itself. The default separation pairs the legs there; π/3 (the old default)
  // left every one of those points unpaired.
  const double s = 0.05, d = 0.8e-3;
  const double zone = std::asin(d / (2 * s * kRi));
  ASSERT_LT(zone, std::numbers::pi / 6);  // inside the old exclusion on both sides of C
  const FoldResult old_rule = fold_contact(std::numbers::pi / 3, s, d);
  EXPECT_EQ(old_rule.active, 0);
  const FoldResult r = fold_contact(ContactInput{}.self_contact_min_separation_rad, s, d);
  EXPECT_GT(r.active, 0);
  EXPECT_GT(r.self_force, 0.0);
  // Penetration: at most the shift d, and at least that of the deepest paired point, whose
  // separation from its partner across C is at least the exclusion: the points at angle
  // ψ ≥ sep/2 from C on either leg overlap by d − 2 s r_i sin ψ.
  EXPECT_LE(r.max_penetration, 1.01 * d);
  const double sep = ContactInput{}.self_contact_min_separation_rad;
  // The deepest pair may sit one element (π/16) beyond the half-separation, as the nodes fall.
  const double psi = 0.5 * sep + std::numbers::pi / 16;
  EXPECT_GE(r.max_penetration, 0.9 * (d - 2 * s * kRi * std::sin(psi)));
}
