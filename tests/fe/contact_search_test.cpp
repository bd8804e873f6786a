// The contact search's shortcuts keep its answer (issue 4 performance; ring_pair_contact.hpp):
//  - the Verlet candidate list, the chord-frame distance bound that orders and stops the
//    closest-point projections, and the cubic formed once per piece and evaluation give
//    exactly (bitwise) the contributions of a full search that projects every slave on every
//    piece of its master surface and keeps the closest owned one within one element depth;
//  - nodes that approach fast — by just under the skin per evaluation, or by several skins at
//    once — are never missed: after every move the kept list gives what a list built on the
//    spot gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <numbers>
#include <random>

#include "fe/chain/chain_mesh.hpp"
#include "fe/chain/chain_model.hpp"
#include "fe/contact/ring_pair_contact.hpp"
#include "fe/contact/self_contact_taper.hpp"

using namespace ringcrush::fe;

namespace {
constexpr double kR = 25.4e-3;
// The chain model's inner-wall exclusion and taper (fe_input.hpp, self_contact_taper.hpp).
constexpr double kExclusion = 0.2;

struct Scene {
  ChainTopology t;
  std::vector<ContactPass> passes;
  double inner_radius = 0;
};
Scene scene(int rings, bool half, int around) {
  ChainInput in;
  in.rings = rings;
  in.mesh.elements_around = around;
  in.mesh.half_ring = half;
  in.joints = JointKind::Free;
  in.pitch_m = 2 * kR;
  Scene s{make_chain_topology(in), {}, in.ring.inner_radius_m};
  const double k_scale = in.material.youngs_modulus_pa * in.ring.width_m / s.t.ring.element_depth;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < rings; ++j)
      if (i != j) s.passes.push_back(outer_pass(s.t.ring, s.t.ring_node[i], i, s.t.ring_node[j], j, k_scale, 0.0125, 0.25));
  for (int i = 0; i < rings; ++i)
    for (auto& p : inner_wall_passes(s.t.ring, s.t.ring_node[i], i, k_scale, 0.0125, 0.25, kExclusion,
                                     kSelfContactTaperBandRad, true))
      s.passes.push_back(std::move(p));
  return s;
}

// Ring `moved` raised by dy towards the ring above it; the last ring flattened so that its
// inner wall crosses itself by 2δ at its centre (y − y_c → (y − y_c)(r − r_i − δ)/r, as
// RingPairContact.SqueezedRingContactsItsInnerWall); every node jittered.
std::vector<Eigen::Vector2d> configuration(const Scene& s, int moved, double dy, double delta, double jitter,
                                           unsigned seed) {
  std::vector<Eigen::Vector2d> x = s.t.mesh.nodes;
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-jitter, jitter);
  if (delta > 0) {
    const double yc = s.t.mesh.ring_centre_y.back(), ri = s.inner_radius;
    for (int n : s.t.ring_node.back()) {
      const Eigen::Vector2d rel(x[n].x(), x[n].y() - yc);
      x[n].y() = yc + rel.y() * (rel.norm() - ri - delta) / rel.norm();
    }
  }
  for (int n : s.t.ring_node[moved]) x[n].y() += dy;
  for (auto& p : x) {
    if (std::abs(p.x()) > 1e-15) p.x() += d(gen);
    p.y() += d(gen);
  }
  return x;
}

// The full search: every slave of every pass projected on every piece; the closest owned
// point within one depth decides (its force as SurfaceContact forms it).
std::vector<ContactContribution> full_search(const std::vector<ContactPass>& passes, double depth,
                                             const std::vector<Eigen::Vector2d>& x) {
  std::vector<ContactContribution> out;
  for (const ContactPass& p : passes) {
    const ArcTaper taper(p.self ? p.min_separation : 0.0, p.self ? p.taper_band : 0.0);
    for (std::size_t s = 0; s < p.slaves.size(); ++s) {
      int best = -1;
      double best_abs = depth, best_f = 0, best_gap = 0;
      for (std::size_t q = 0; q < p.pieces.size(); ++q) {
        const PiecePolynomial poly(p.pieces[q]);
        double xy[12];
        xy[0] = x[p.slaves[s]].x();
        xy[1] = x[p.slaves[s]].y();
        for (int a = 0; a < p.pieces[q].count; ++a) {
          xy[2 + 2 * a] = x[p.pieces[q].nodes[a]].x();
          xy[3 + 2 * a] = x[p.pieces[q].nodes[a]].y();
        }
        double f = poly.lo - 1.0, gap = 0;
        if (!surface_gap(poly, xy, p.symmetric_end[q], true, f, gap)) continue;
        if (p.self && taper.weight(arc_to_closest_point(poly, p.piece_angle[q], p.slave_angle[s], f, nullptr)) == 0)
          continue;
        if (std::abs(gap) < best_abs) {
          best = static_cast<int>(q);
          best_abs = std::abs(gap);
          best_f = f;
          best_gap = gap;
        }
      }
      if (best < 0 || !(best_gap < 0)) continue;
      const CurvePiece& piece = p.pieces[static_cast<std::size_t>(best)];
      const PiecePolynomial poly(piece);
      ContactContribution& c = out.emplace_back();
      c.count = 1 + piece.count;
      c.nodes[0] = p.slaves[s];
      double xy[12];
      xy[0] = x[p.slaves[s]].x();
      xy[1] = x[p.slaves[s]].y();
      for (int a = 0; a < piece.count; ++a) {
        c.nodes[1 + a] = piece.nodes[a];
        xy[2 + 2 * a] = x[piece.nodes[a]].x();
        xy[3 + 2 * a] = x[piece.nodes[a]].y();
      }
      c.force.setZero();
      if (p.self)
        tapered_self_force(poly, xy, p.slave_k[s], best_f, best_gap, taper, p.slave_angle[s],
                           p.piece_angle[static_cast<std::size_t>(best)], c.force.data());
      else
        surface_force(poly, xy, p.slave_k[s], best_f, best_gap, c.force.data());
      c.gap = best_gap;
    }
  }
  return out;
}

void expect_same(const std::vector<ContactContribution>& got, const std::vector<ContactContribution>& ref,
                 const std::string& where) {
  ASSERT_EQ(got.size(), ref.size()) << where;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    EXPECT_EQ(got[i].count, ref[i].count) << where << ", contribution " << i;
    EXPECT_EQ(got[i].nodes, ref[i].nodes) << where << ", contribution " << i;
    EXPECT_EQ(got[i].gap, ref[i].gap) << where << ", contribution " << i;
    EXPECT_EQ(got[i].force, ref[i].force) << where << ", contribution " << i;
  }
}
}  // namespace

TEST(ContactSearch, PrunedSearchIsTheFullSearch) {
  int ring_ring = 0, self = 0;
  for (bool half : {true, false}) {
    const Scene s = scene(3, half, 16);
    const double depth = s.t.ring.element_depth;
    for (unsigned seed = 1; seed <= 6; ++seed) {
      // Ring 2 from 0.08 to 0.48 of the wall into ring 1; ring 3's inner wall crossing
      // itself by 0 to 0.5 of the wall.
      const double dy = 0.08 * seed * depth, delta = 0.05 * (seed - 1) * depth;
      const auto x = configuration(s, 1, dy, delta, 0.05 * depth, seed);
      SurfaceContact contact(s.passes, depth);
      std::vector<ContactContribution> out;
      SurfaceContactState st;
      contact.evaluate(x, false, out, nullptr, st);
      const auto ref = full_search(s.passes, depth, x);
      expect_same(out, ref, (half ? "half rings, seed " : "full rings, seed ") + std::to_string(seed));
      for (const auto& c : ref) {
        bool own = false;
        for (const auto& ring : s.t.ring_node)
          if (std::find(ring.begin(), ring.end(), c.nodes[0]) != ring.end())
            own = std::find(ring.begin(), ring.end(), c.nodes[1]) != ring.end();
        ++(own ? self : ring_ring);
      }
    }
  }
  // Both kinds of pass were compared where they act.
  EXPECT_GT(ring_ring, 20);
  EXPECT_GT(self, 10);
}

TEST(ContactSearch, FastApproachAcrossTheSkinIsNeverMissed) {
  const Scene s = scene(2, true, 16);
  const double depth = s.t.ring.element_depth, skin = SurfaceContact::kSkin * depth;
  SurfaceContact kept(s.passes, depth);
  std::vector<ContactContribution> out;
  SurfaceContactState st;
  // Ring 2 starts 3 depths below ring 1 (beyond every padded box: no candidates), then comes
  // up by just under one skin per evaluation, then by several skins at once, into contact.
  double dy = -3 * depth;
  kept.evaluate(configuration(s, 1, dy, 0.0, 0.0, 1), false, out, nullptr, st);
  auto ring_ring_candidates = [&] {
    std::size_t n = 0;
    for (std::size_t p = 0; p < s.passes.size(); ++p)
      if (!s.passes[p].self) n += kept.candidates(p);
    return n;
  };
  EXPECT_EQ(ring_ring_candidates(), 0u);
  // To 0.28 of the wall apart by just under one skin at a time, then 0.35 of the wall into
  // ring 1 at once (0.625 of the wall: 5 skins of 0.125), then just under a skin further.
  std::vector<double> moves(static_cast<std::size_t>(std::lround(2.7225 / (0.99 * skin / depth))), 0.99 * skin);
  moves.push_back(0.625 * depth);
  moves.push_back(0.99 * skin);
  int touching = 0;
  for (std::size_t k = 0; k < moves.size(); ++k) {
    dy += moves[k];
    const auto x = configuration(s, 1, dy, 0.0, 0.0, 1);
    out.clear();
    kept.evaluate(x, false, out, nullptr, st);
    SurfaceContact fresh(s.passes, depth);
    std::vector<ContactContribution> ref;
    SurfaceContactState sr;
    fresh.evaluate(x, false, ref, nullptr, sr);
    expect_same(out, ref, "move " + std::to_string(k));
    EXPECT_EQ(st.energy, sr.energy) << "move " << k;
    if (!ref.empty()) ++touching;
  }
  // The last two moves overlap the rings: contact found, by both lists.
  EXPECT_GE(touching, 2);
  EXPECT_GT(ring_ring_candidates(), 0u);
  EXPECT_GT(kept.rebuilds(), 2);  // the kept list was rebuilt on the way, not every time
  EXPECT_LT(kept.rebuilds(), static_cast<long>(moves.size()));
}

namespace {

// Three free rings, 16 selective CPS8 per half ring: the chain of the two-thread tests below.
ChainInput three_free_rings() {
  ChainInput in;
  in.rings = 3;
  in.mesh.elements_around = 16;
  in.joints = JointKind::Free;
  in.integration = Integration::Selective;
  return in;
}

ChainInput with_threads(ChainInput in, int threads) {
  in.threads = threads;
  return in;
}

// A configuration of that chain at `step`: every ring raised lift·step depths per ring into the
// one above, the impactor pushed 0.2·step depths into ring 1, every dof jittered by up to 0.02
// depth, fixed dofs at zero; with `inner_wall_through`, the last ring also flattened so that its
// inner wall crosses itself by 0.1·step depths (which inverts its elements there).
Eigen::VectorXd stacked_rings(const ChainModel& model, int step, double lift, bool inner_wall_through,
                              std::mt19937& gen) {
  const ChainMesh& mesh = model.mesh();
  const double depth = model.contact_depth();
  const int rings = model.input().rings;
  std::uniform_real_distribution<double> jitter(-0.02 * depth, 0.02 * depth);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
  for (std::size_t e = 0; e < mesh.elements.size(); ++e)
    for (int n : mesh.elements[e]) u(2 * n + 1) = lift * step * depth * mesh.element_ring[e];
  if (inner_wall_through) {
    const double yc = mesh.ring_centre_y.back(), ri = model.input().ring.inner_radius_m;
    const double delta = 0.1 * step * depth;
    for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
      if (mesh.element_ring[e] != rings - 1) continue;
      for (int n : mesh.elements[e]) {
        const Eigen::Vector2d rel(mesh.nodes[n].x(), mesh.nodes[n].y() - yc);
        u(2 * n + 1) = lift * step * depth * (rings - 1) + rel.y() * (rel.norm() - ri - delta) / rel.norm() - rel.y();
      }
    }
  }
  for (int i = 0; i < model.dofs(); ++i) u(i) += jitter(gen);
  u(model.impactor_dof()) = -0.2 * step * depth;
  for (int dof : model.fixed_dofs()) u(dof) = 0;
  return u;
}

}  // namespace

// The chain model's force with contacts active (ring↔ring, inner wall, impactor) is bitwise
// the same on one thread or two (the contact is searched on the calling thread while both
// deal the elements; the sums are formed in a fixed order, chain_model.hpp).
TEST(ContactSearch, ChainForceWithContactIsThreadIndependent) {
  const ChainInput in = three_free_rings();
  ChainModel serial(with_threads(in, 1)), threaded(with_threads(in, 2));
  std::mt19937 gen(11);
  for (int step = 1; step <= 3; ++step) {
    const Eigen::VectorXd u = stacked_rings(serial, step, 0.15, false, gen);
    SystemEvaluation a, b;
    serial.evaluate(u, false, a);
    threaded.evaluate(u, false, b);
    EXPECT_EQ(a.force, b.force) << "step " << step;
    EXPECT_EQ(a.contact_energy, b.contact_energy) << "step " << step;
    EXPECT_EQ(serial.contact_forces().active_set, threaded.contact_forces().active_set) << "step " << step;
    EXPECT_GT(serial.contact_forces().ring_ring_n, 0.0) << "step " << step;
    EXPECT_GT(serial.contact_forces().impactor_n, 0.0) << "step " << step;
    serial.commit(u);
    threaded.commit(u);
  }
}

// SurfaceContact::begin / search / finish (the passes searched on several threads,
// ChainModel): with the passes searched in any order — here reversed, as a second thread
// taking the last passes first would — the contributions (force and tangent), pressures and
// every sum and maximum of the state are bitwise those of evaluate().
TEST(ContactSearch, PassesSearchedInAnyOrderGiveTheSerialResult) {
  int compared = 0;
  for (bool half : {true, false}) {
    const Scene s = scene(3, half, 16);
    const double depth = s.t.ring.element_depth;
    for (unsigned seed = 1; seed <= 4; ++seed) {
      const auto x = configuration(s, 1, 0.12 * seed * depth, 0.12 * seed * depth, 0.05 * depth, seed);
      for (bool tangent : {false, true}) {
        const std::string where = (half ? "half, seed " : "full, seed ") + std::to_string(seed) +
                                  (tangent ? ", tangent" : "");
        SurfaceContact serial(s.passes, depth), split(s.passes, depth);
        std::vector<ContactContribution> a, b;
        std::vector<std::pair<int, double>> pa, pb;
        SurfaceContactState sa, sb;
        serial.evaluate(x, tangent, a, &pa, sa);
        split.begin(x);
        const auto& busy = split.busy_passes();
        EXPECT_GT(busy.size(), 1u) << where;
        for (auto it = busy.rbegin(); it != busy.rend(); ++it) split.search(static_cast<std::size_t>(*it), x);
        split.finish(x, tangent, b, &pb, sb);
        expect_same(b, a, where);
        for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
          EXPECT_EQ(b[i].stiffness, a[i].stiffness) << where;
          if (tangent) {
            EXPECT_EQ(b[i].tangent, a[i].tangent) << where << ", contribution " << i;
          }
        }
        EXPECT_EQ(pb, pa) << where;
        EXPECT_EQ(sb.energy, sa.energy) << where;
        EXPECT_EQ(sb.ring_ring_force, sa.ring_ring_force) << where;
        EXPECT_EQ(sb.self_force, sa.self_force) << where;
        EXPECT_EQ(sb.max_penetration, sa.max_penetration) << where;
        EXPECT_EQ(sb.deepest_node, sa.deepest_node) << where;
        EXPECT_EQ(sb.deepest_master_ring, sa.deepest_master_ring) << where;
        EXPECT_EQ(sb.deepest_self, sa.deepest_self) << where;
        EXPECT_EQ(sb.active, sa.active) << where;
        EXPECT_EQ(sb.near_omega2, sa.near_omega2) << where;
        EXPECT_EQ(sb.near_node, sa.near_node) << where;
        if (sa.ring_ring_force > 0 && sa.self_force > 0) ++compared;
      }
    }
  }
  EXPECT_GE(compared, 8);  // both kinds of contact acting in most of the 16 cases
}

// The chain model deals the contact passes' searches to both threads with the elements
// (chain_model.hpp): with ring↔ring, inner-wall and impactor contact all active, the force,
// energies, contact sums, the deepest point, the active set and the pressures are bitwise
// those of one thread, configuration after configuration (the helper and the caller take
// different passes from call to call; the answer must not notice). Ring 3's inner wall is
// pushed through itself (as configuration() above), which inverts its elements there: each
// configuration is evaluated as an increment from the undeformed x_n, never committed.
TEST(ContactSearch, ChainContactDealtToTwoThreadsIsTheOneThreadContact) {
  const ChainInput in = three_free_rings();
  ChainModel serial(with_threads(in, 1)), threaded(with_threads(in, 2));
  std::mt19937 gen(5);
  for (int step = 1; step <= 4; ++step) {
    const Eigen::VectorXd u = stacked_rings(serial, step, 0.12, true, gen);
    SystemEvaluation a, b;
    serial.evaluate(u, false, a);
    threaded.evaluate(u, false, b);
    const std::string where = "step " + std::to_string(step);
    EXPECT_EQ(a.force, b.force) << where;
    EXPECT_EQ(a.contact_energy, b.contact_energy) << where;
    EXPECT_EQ(a.elastic_energy, b.elastic_energy) << where;
    const ChainContactForces &ca = serial.contact_forces(), &cb = threaded.contact_forces();
    EXPECT_EQ(ca.active_set, cb.active_set) << where;
    EXPECT_EQ(ca.active, cb.active) << where;
    EXPECT_EQ(ca.ring_ring_n, cb.ring_ring_n) << where;
    EXPECT_EQ(ca.self_n, cb.self_n) << where;
    EXPECT_EQ(ca.impactor_n, cb.impactor_n) << where;
    EXPECT_EQ(ca.max_penetration_m, cb.max_penetration_m) << where;
    EXPECT_EQ(ca.deepest_node, cb.deepest_node) << where;
    EXPECT_EQ(serial.contact_pressure(), threaded.contact_pressure()) << where;
    EXPECT_GT(ca.ring_ring_n, 0.0) << where;
    EXPECT_GT(ca.self_n, 0.0) << where;
    EXPECT_GT(ca.impactor_n, 0.0) << where;
  }
}

// Open slaves (ring_pair_contact.hpp): a slave whose every candidate piece within one depth
// certifies a positive gap, that has no remembered pair and whose ω² does not exceed the
// largest already found in its pass, is not projected. Ring 2 pushed into ring 1 and pulled
// back out, ring 3's inner wall through itself, every node jittered (random configurations),
// random nodal masses (so that the slaves' ω² differ and the contact-spring bound's first
// maximum moves), committed after every evaluation (so that remembered pairs act and then
// open): the sparing search is bitwise the search that projects every listed slave and the
// full search — contributions, pressures, every sum and maximum of the state, the spring
// bound (near_omega2, near_node), the arrival memory — and it did spare slaves.
TEST(ContactSearch, SparedOpenSlavesChangeNothing) {
  long spared = 0, spared_by_reference = 0;
  int touching = 0, remembered = 0;
  for (bool half : {true, false}) {
    const Scene s = scene(3, half, 48);
    const double depth = s.t.ring.element_depth;
    std::mt19937 gen(half ? 7 : 8);
    std::uniform_real_distribution<double> unit(0.5, 1.5);
    Eigen::VectorXd mass(2 * static_cast<Eigen::Index>(s.t.mesh.nodes.size()));
    for (Eigen::Index i = 0; i < mass.size(); ++i) mass(i) = 1e-3 * unit(gen);
    SurfaceContact sparing(s.passes, depth), every(s.passes, depth);
    every.set_spare_open_slaves(false);
    sparing.set_mass(mass);
    every.set_mass(mass);
    // Ring 2's lift into ring 1 (depths): in to 0.45 of the wall, then out to 0.3 apart.
    const std::vector<double> lift = {-0.30, -0.10, 0.05, 0.15, 0.25, 0.35, 0.45, 0.30, 0.10, -0.05, -0.30};
    for (std::size_t k = 0; k < lift.size(); ++k) {
      const std::string where = (half ? "half rings, move " : "full rings, move ") + std::to_string(k);
      const auto x = configuration(s, 1, lift[k] * depth, 0.04 * static_cast<double>(k) * depth,
                                   (k % 3 == 0 ? 0.15 : 0.05) * depth, static_cast<unsigned>(100 * k + 1));
      std::vector<ContactContribution> a, b;
      std::vector<std::pair<int, double>> pa, pb;
      SurfaceContactState sa, sb;
      sparing.evaluate(x, false, a, &pa, sa);
      every.evaluate(x, false, b, &pb, sb);
      spared += sparing.spared_slaves();
      spared_by_reference += every.spared_slaves();
      expect_same(a, b, where);
      if (k == 0) expect_same(a, full_search(s.passes, depth, x), where + " (full search)");
      EXPECT_EQ(pa, pb) << where;
      EXPECT_EQ(sa.energy, sb.energy) << where;
      EXPECT_EQ(sa.ring_ring_force, sb.ring_ring_force) << where;
      EXPECT_EQ(sa.self_force, sb.self_force) << where;
      EXPECT_EQ(sa.max_penetration, sb.max_penetration) << where;
      EXPECT_EQ(sa.deepest_node, sb.deepest_node) << where;
      EXPECT_EQ(sa.active, sb.active) << where;
      EXPECT_EQ(sa.near_omega2, sb.near_omega2) << where;
      EXPECT_EQ(sa.near_node, sb.near_node) << where;
      EXPECT_GT(sa.near_omega2, 0.0) << where;
      if (sa.ring_ring_force > 0) ++touching;
      sparing.commit();
      every.commit();
      EXPECT_EQ(sparing.arrival().admitted(), every.arrival().admitted()) << where;
      EXPECT_EQ(sparing.arrival().refused(), every.arrival().refused()) << where;
      for (std::size_t p = 0; p < s.passes.size(); ++p)
        for (std::size_t sl = 0; sl < s.passes[p].slaves.size(); ++sl) {
          EXPECT_EQ(sparing.arrival().remembered_piece(p, sl), every.arrival().remembered_piece(p, sl)) << where;
          if (every.arrival().remembered_piece(p, sl) >= 0) ++remembered;
        }
    }
  }
  EXPECT_GE(touching, 8);      // ring↔ring contact acted on the way in and out
  EXPECT_GT(remembered, 50);   // and was remembered (the spared slaves have no memory)
  EXPECT_GT(spared, 100);      // slaves were spared (173 of 1 246 ring↔ring slaves): not vacuous
  EXPECT_EQ(spared_by_reference, 0);
}
