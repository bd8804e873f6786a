// Node-to-surface contact between deformable surfaces of a ring chain (issue 4 item 2;
// thesis §3.6.3; DESIGN.md "Contact"): ring i's outer surface against ring j's, and every
// ring's inner wall against itself. Frictionless penalty, energy ½ k g² for g < 0, so the
// force is the gradient of a potential (action = reaction, momentum conserved) and the
// tangent symmetric. The master surfaces are the Hermite-smoothed quadratic edges of
// smoothed_surface.hpp (C¹, so the force varies continuously as a node slides over a
// junction).
//
// Symmetry (no master/slave bias): ring↔ring contact is two passes, i's nodes on j's surface
// and j's nodes on i's, with the same penalty rule on both sides; on the inner wall every
// node, the side point C included, is a slave against the whole wall (one C¹ surface through
// C) less its own neighbourhood, so each touching pair is seen from both sides.
//
// Broad phase (pairs that cannot touch cost nothing): a Verlet candidate list of
// (slave node, master piece) pairs, built from padded bounding boxes with a skin and rebuilt
// only when some surface node has moved more than the skin since the last build. Every
// evaluation applies the exact box test to the listed pairs, so the result does not depend
// on when the list was built: the list is a superset of what the test can accept. A pass
// whose rings' padded boxes do not overlap (ring i and ring i+3, or ring i and i+2 before a
// wrap-around) adds nothing to the list.
//
// Narrow phase (issue 4 performance; tests/fe/contact_search_test.cpp): a slave's candidate
// pieces are projected nearest-first by a lower bound of their |gap| — the distance to the
// piece's box in the frame of its chord, which hugs a slanted piece where an x–y box does not
// — and no further once the bound reaches the best |gap| found; each piece's cubic and box
// are formed once per evaluation, whichever slaves ask. The closest owned piece, and so every
// contribution, is bitwise that of projecting every slave on every piece (test).
//
// Open slaves (issue 4 performance; README "Session 11"): most listed slaves do not
// penetrate, and were projected only to learn it and whether they are within one depth (the
// contact-spring bound, near_omega2). On a piece whose tangent runs forward along its chord
// (x'·t ≥ a > 0, |x'·n| ≤ b over the piece, t and n the chord frame) a slave lying dv beyond
// the curve's range across the chord and at most du from it along the chord has, at any point
// x(f) where a projection can end, (x_s − x(f))·n(f) |x'| ≥ dv a − du b (n(f) the left unit
// normal): the gap is positive if dv a − du b > 0. A slave whose every candidate piece within
// one depth certifies this, that has no remembered pair, and whose ω² does not exceed the
// largest already found in its pass (so whether it is near changes nothing), adds nothing and
// changes nothing: it is not projected (bitwise the full search; test).
//
// Arrival rule (contact_arrival.hpp): a pair first seen deeper than the arrival depth is
// refused; an acting pair is remembered (committed with the accepted step, commit()) and keeps
// acting past the reach until its gap opens, its neighbourhood of pieces deciding over the
// closest piece while it is closed.
#pragma once

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

#include "fe/contact/contact_arrival.hpp"
#include "fe/contact/contact_element.hpp"
#include "fe/contact/smoothed_surface.hpp"
#include "fe/mesh/ring_mesh.hpp"

namespace ringcrush::fe {

// One set of slave nodes against one master surface (global node ids).
struct ContactPass {
  bool self = false;            // inner wall against itself (else outer ring↔ring)
  int slave_ring = 0, master_ring = 0;
  std::vector<int> slaves;
  std::vector<double> slave_k;     // penalty stiffness per slave (N/m)
  std::vector<double> slave_area;  // tributary area per slave (pressure output)
  // Master pieces; the left normal of x'(f) points out of the master material, toward the
  // side the slaves come from.
  std::vector<CurvePiece> pieces;
  // Per piece: bit 0 = its lo end, bit 1 = its hi end lies on the x = 0 symmetry plane of a
  // half ring. There the surface continues as its mirror image, so a projection onto that
  // end is the closest point of the whole surface and is accepted.
  std::vector<unsigned char> symmetric_end;
  // Self contact: reference angle of each slave and piece node; points closer than
  // min_separation along the wall are joined by the wall and never paired, and the penalty
  // ramps up over the next taper_band of arc (self_contact_taper.hpp: no force jump at the
  // exclusion's edge).
  std::vector<double> slave_angle;
  std::vector<std::array<double, 5>> piece_angle;
  double min_separation = 0;
  double taper_band = 0;
};

// Passes of one ring's outer surface (ring `slave`) against another's (ring `master`).
// map_*: local → global node of each ring; k_scale: penalty per unit tributary length.
ContactPass outer_pass(const RingMesh& ring, const std::vector<int>& slave_map, int slave,
                       const std::vector<int>& master_map, int master, double k_scale, double width,
                       double smoothing);
// The inner-wall pass of one ring: two_pass (ContactInput::self_contact_two_pass, the
// default) every inner node against the whole inner wall, symmetric; otherwise the lower
// half's nodes (y < 0) against the upper half only, as RingContact's first pass (one-sided).
// min_separation: ContactInput::self_contact_min_separation_rad; taper_band: the arc over
// which the penalty ramps up beyond it (kSelfContactTaperBandRad, self_contact_taper.hpp).
std::vector<ContactPass> inner_wall_passes(const RingMesh& ring, const std::vector<int>& map, int ring_index,
                                           double k_scale, double width, double smoothing,
                                           double min_separation, double taper_band, bool two_pass);

// A piece's shape functions as cubic polynomials in f, c_k(f) = Σ_p a[k][p] f^p (exact:
// quadratic edges and Hermite junctions are at most cubic). Precomputed once, so the closest-
// point Newton iteration costs a few flops per step.
struct PiecePolynomial {
  int count = 3;
  double lo = -1, hi = 1;
  double a[5][4] = {};
  PiecePolynomial() = default;
  explicit PiecePolynomial(const CurvePiece& piece);
};

struct SurfaceContactState {
  double ring_ring_force = 0;   // Σ |normal force| of ring↔ring contacts
  double self_force = 0;        // Σ |normal force| of inner-wall contacts
  double energy = 0;            // penalty energy
  double max_penetration = 0;
  // Where the deepest penetration is: slave node (global id), master ring, self contact.
  int deepest_node = -1, deepest_master_ring = -1;
  bool deepest_self = false;
  int active = 0;
  // Largest k (1/m_slave + 1.25 max 1/m_master) over slaves within one element depth of a
  // master surface (the contact spring's frequency bound, stable_step) and its node.
  double near_omega2 = 0;
  int near_node = -1;
};

class SurfaceContact {
 public:
  // Verlet skin of the candidate list, in element depths. Every evaluation applies the exact
  // test, so the skin sets only the cost: a list padded by 3 skins is refreshed and filtered
  // on every evaluation and rebuilt when a node has moved a skin. Thesis scene explicit, first
  // 0.2 ms (callgrind, README "Session 11"): 0.25 → 0.125 halved the piece refreshes (204 → 100
  // per evaluation) and cut the contact's instructions by 26 % for 35 rebuilds instead of 18;
  // 0.0625 gained nothing more in a 4 ms perf profile (the rebuilds doubled again).
  static constexpr double kSkin = 0.125;

  // depth: element size through the wall (largest penetration counted, box padding).
  // arrival_depth: deepest first sight at which a pair may start acting (m; contact_arrival.hpp);
  // without it the reach, so only the memory acts (a pair keeps acting past the reach).
  SurfaceContact(std::vector<ContactPass> passes, double depth, double arrival_depth);
  SurfaceContact(std::vector<ContactPass> passes, double depth) : SurfaceContact(std::move(passes), depth, depth) {}

  // Mass per dof (lumped) for the frequency bound of the contact springs.
  void set_mass(const Eigen::VectorXd& mass);

  // x: current coordinates of all nodes. Appends the active contributions; pressure (if not
  // null) gets (node, contact pressure) of each active slave.
  void evaluate(const std::vector<Eigen::Vector2d>& x, bool want_tangent, std::vector<ContactContribution>& out,
                std::vector<std::pair<int, double>>* pressure, SurfaceContactState& state);

  // evaluate() in three parts, for searching the passes on several threads (ChainModel):
  // begin(x) on one thread (the list kept or rebuilt, the evaluation stamped), then
  // search(pass, x) for every pass — each touches only its own pass's pieces and results, so
  // different passes may run at once on different threads — then finish() on one thread,
  // which forms the contributions and sums pass by pass in the serial order: bitwise
  // evaluate(), whichever thread searched which pass.
  void begin(const std::vector<Eigen::Vector2d>& x);
  void search(std::size_t pass, const std::vector<Eigen::Vector2d>& x);
  void finish(const std::vector<Eigen::Vector2d>& x, bool want_tangent, std::vector<ContactContribution>& out,
              std::vector<std::pair<int, double>>* pressure, SurfaceContactState& state) const;
  // Slaves of the last evaluation whose projections were spared because none of their
  // candidate pieces can give them a negative gap (certified_open(); all passes).
  long spared_slaves() const;
  // Off: every listed slave is projected (the reference path of the tests); on by default.
  void set_spare_open_slaves(bool on) { spare_open_ = on; }
  // Passes that have candidates in the current list (the others find nothing), ascending.
  const std::vector<int>& busy_passes() const { return busy_passes_; }
  // Makes the pairs of the last evaluate() the remembered ones (contact_arrival.hpp; call it
  // with the other history, after evaluating the accepted configuration).
  void commit() { arrival_.commit(); }
  const ContactArrival& arrival() const { return arrival_; }

  const std::vector<ContactPass>& passes() const { return passes_; }
  long rebuilds() const { return rebuilds_; }
  std::size_t candidates() const { return candidate_piece_.size(); }
  // Candidate (slave, piece) pairs of one pass in the current list (0 before the first build).
  std::size_t candidates(std::size_t pass) const {
    return start_[pass].empty() ? 0 : static_cast<std::size_t>(start_[pass].back() - start_[pass].front());
  }

 private:
  void rebuild(const std::vector<Eigen::Vector2d>& x);
  // Forms cache_[pass][piece] at x for the current evaluation.
  void refresh(std::size_t pass, int piece, const std::vector<Eigen::Vector2d>& x);

  std::vector<ContactPass> passes_;
  double depth_, skin_;
  std::vector<int> tracked_;                  // every node of every pass
  std::vector<Eigen::Vector2d> x_build_;      // their positions at the last build
  bool built_ = false;
  long rebuilds_ = 0;
  // Candidates: pass p, slave s → candidate_piece_[start_[p][s] .. start_[p][s + 1]).
  std::vector<std::vector<int>> start_;
  // Per pass, the slaves with at least one candidate, ascending (the evaluation visits only
  // these, in the order of the full scan: most slaves have none, and of the thesis chain's
  // 36 passes the 20 between rings that are not neighbours hold none until a wrap-around).
  std::vector<std::vector<int>> near_slaves_;
  std::vector<int> candidate_piece_;
  std::vector<std::vector<double>> slave_omega2_;  // per pass, per slave
  std::vector<std::vector<PiecePolynomial>> poly_; // per pass, per piece
  // Self passes, per piece: its node angles unwrapped about its first (self_contact_taper.hpp).
  std::vector<std::vector<std::array<double, 5>>> unwrapped_;
  // What the current evaluation knows of a piece, formed once per piece and evaluation
  // (stamp = evaluation), when a slave first needs it: its geometric cubic x(f) = Σ A_q f^q,
  // and a box of the curve in the frame of its chord (t along, n across, the curve's range
  // of x·t and x·n). The distance to that box is the lower bound of |gap| that orders the
  // projections; a slanted piece's box in x and y is much wider than the curve, the chord
  // frame's is not, so fewer projections are made (same closest piece). A piece ending on a
  // symmetry plane keeps its x–y box (the filter of those pieces, whose gap is no distance).
  struct PieceCache {
    double a[4][2];
    double box[4];          // x–y box of the curve (symmetry-plane pieces)
    double t[2];            // chord direction (unit)
    double range[4];        // lo, hi of x·t; lo, hi of x·n over the piece
    // Bounds of the tangent x'(f) in the chord frame over the piece: x'·t ≥ along_min,
    // |x'·n| ≤ across_max (the certificate of an open gap, certified_open()).
    double along_min, across_max;
    unsigned stamp = 0;
  };
  // Whether a slave at (x, y) provably has a positive gap wherever its projection on the
  // piece ends (header: "Open slaves"); 1e-9 depth of margin over the rounding.
  static bool certified_open(const PieceCache& pc, double x, double y, double depth);
  std::vector<std::vector<PieceCache>> cache_;
  unsigned stamp_ = 0;
  std::vector<int> busy_passes_;
  // What search() found in one pass: per slave with a penetrating closest point, in scan
  // order, its piece, closest point, gap, taper weight and local force; and the largest
  // contact-spring ω² of the slaves within one depth (the first of them if several).
  struct Hit {
    int slave = 0, piece = 0;
    double f = 0, gap = 0, weight = 1;
    double force[12];
  };
  struct PassFound {
    std::vector<Hit> hits;
    double near_omega2 = 0;
    int near_node = -1;
    long spared = 0;  // slaves not projected (certified open)
  };
  std::vector<PassFound> found_;
  bool spare_open_ = true;
  ContactArrival arrival_;
};

// Gap and force of a slave node against one piece: coords = [x_s, y_s, x_1, y_1, …] (slave
// then the piece's nodes). strict: the closest point must lie on the piece (or on an end at
// a symmetry plane, `symmetric_end` bits); otherwise the piece's polynomial is continued
// past its ends (finite differences of the tangent). On entry f is a start guess (outside
// [lo, hi] to start from samples); on exit the closest-point parameter. Returns false if no
// closest point is owned. force (2 + 2·count values) = ∂(½ k g²)/∂coords when g < 0, else 0.
bool surface_gap(const PiecePolynomial& piece, const double* coords, unsigned char symmetric_end, bool strict,
                 double& f, double& gap);
void surface_force(const PiecePolynomial& piece, const double* coords, double k, double f, double gap, double* force);

}  // namespace ringcrush::fe
