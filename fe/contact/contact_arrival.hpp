// Arrival rule of the surface contact (issue 4, verification g; README "Stability matrix"):
// a (slave node, master surface) pair may only start acting at a small penetration, and once
// acting it keeps acting, from the side it arrived from, until its gap opens.
//
// Why: the penalty acts on a pair whose gap is negative and within the reach, one element
// depth through the wall (SurfaceContact). A real contact is first seen shallow — a step moves
// a node a small fraction of the wall depth (explicit steps ~10 ns; HHT steps are larger but
// still small against the wall) — so a pair that first appears deep is not a contact: a node
// of a wall creased back to back lies about one depth behind its own leg's piece (gap ≈ −1.0
// depth), and acting on it brings ½ k g² of energy from nothing (the MN force jumps of the
// ×4 100 m/s t/D 0.02 cases). And a real contact pushed past the reach lost its force and was
// then taken up from the wrong side (free 30 m/s ×4 t/D 0.02, a node 75 % of the depth inside
// its neighbour's outer surface): remembered, it is pushed back, not pulled through.
//
// Memory per (pass, slave): none, Active or Refused, with the master piece and gap of the pair. The
// pair is that piece's neighbourhood (the pieces sharing a node with it), so it survives the
// closest point sliding onto the next piece of the C¹ surface; the piece is updated at every
// commit. A refused pair is remembered as well, so that it stays refused — and never adds
// energy — while it stays closed (a crease opening would otherwise "arrive" it at the
// arrival depth). Committed and trial memory are kept apart like the J2 point states: an
// evaluation reads the committed memory and writes the trial only; commit() promotes it, so a
// rejected HHT step or a Newton iterate leaves no trace, and within one step the contact force
// is a function of the configuration alone (its tangent the finite differences of it).
#pragma once

#include <cstddef>
#include <vector>

namespace ringcrush::fe {

struct ContactPass;

// The deepest refused arrival (diagnosis: the rule acted, and where).
struct RefusedArrival {
  double depth = 0;     // −gap at first sight (m)
  int node = -1;        // slave node (global id)
  int master_ring = -1;
  bool self = false;    // on its own inner wall
};

class ContactArrival {
 public:
  enum class Kind : unsigned char { None, Active, Refused };

  ContactArrival() = default;
  // arrival_depth: deepest penetration (m) at which a new pair may start acting; ≤ 0 or not
  // finite throws std::invalid_argument naming it.
  ContactArrival(const std::vector<ContactPass>& passes, double arrival_depth);

  double arrival_depth() const { return arrival_depth_; }
  // Master piece of the committed pair of slave s of pass p, −1 for none.
  int remembered_piece(std::size_t pass, std::size_t slave) const { return committed_[pass][slave].piece; }
  bool remembered_refused(std::size_t pass, std::size_t slave) const {
    return committed_[pass][slave].kind == Kind::Refused;
  }
  // The pieces of the remembered pair's neighbourhood (piece included): those sharing a node.
  const std::vector<int>& neighbourhood(std::size_t pass, int piece) const { return neighbours_[pass][piece]; }
  bool near(std::size_t pass, int remembered, int piece) const;

  // Starts an evaluation: the trial memory is emptied (an unvisited slave has no pair).
  void begin();
  // A closed pair (gap < 0) of slave s on `piece`; continuing: it is the remembered pair,
  // re-found on its neighbourhood. Writes the trial memory; returns whether it acts: a
  // continuing pair as it was (Active acts, Refused does not), a new one if −gap is within
  // the arrival depth (else it is refused and noted). A remembered pair whose gap moved by
  // more than the arrival depth since the commit is judged as a first sight: its closest
  // point jumped (a node past the centre of curvature of its partner surface, e.g. behind a
  // crease), and taking the new gap would bring ½ k (g² − g_n²) of energy from nothing.
  bool admit(std::size_t pass, std::size_t slave, int piece, double gap, bool continuing, int node, int master_ring,
             bool self);
  // Promotes the trial memory of the last evaluation; its refusals join the run's count.
  void commit();

  // Committed: refused arrivals so far (one per pair refused, however long it stays closed)
  // and the deepest of them.
  long refused() const { return refused_; }
  const RefusedArrival& deepest_refused() const { return deepest_; }
  // Committed: new pairs admitted so far and the deepest first sight among them (m): the
  // margin the arrival depth leaves to real contacts.
  long admitted() const { return admitted_; }
  double deepest_admitted() const { return deepest_admitted_; }
  // Trial (last evaluation): refusals it made.
  int trial_refusals() const;

 private:
  struct Memory {
    int piece = -1;
    Kind kind = Kind::None;
    double gap = 0;
  };
  struct Entry {
    std::size_t pass, slave;
    Memory memory;
  };
  double arrival_depth_ = 0;
  std::vector<std::vector<Memory>> committed_;  // per pass, per slave
  std::vector<Entry> committed_list_;  // the pairs held (committed)
  std::vector<std::vector<std::vector<int>>> neighbours_;  // per pass, per piece
  // This evaluation, per pass: admit() on different passes may run on different threads
  // (SurfaceContact::search), so each writes only its own pass's trial; commit() reads them
  // in pass order, the order of the serial scan.
  struct Trial {
    std::vector<Entry> held;
    std::vector<RefusedArrival> refused;
    int admitted = 0;
    double deepest_admitted = 0;
  };
  std::vector<Trial> trial_;
  long refused_ = 0, admitted_ = 0;
  double deepest_admitted_ = 0;
  RefusedArrival deepest_;
};

}  // namespace ringcrush::fe
