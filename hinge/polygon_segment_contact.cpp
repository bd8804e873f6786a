// Node–segment contact in the polygon chain's residual: ring–ring and each ring's inner wall
// (gap = distance − t, the wall thickness as offset; issue 7 item 1). Each slave node meets the
// closest master segment of the other ring (or of its own ring, skipping the bars within two
// nodes); the reaction goes to the segment ends with weights (1 − s, s). Both rings of a pair
// act as slave in turn.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "hinge/polygon_chain.hpp"
#include "hinge/polygon_closest_segment.hpp"
#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge {

int PolygonChain::contact_segments() const { return half_ ? n_ind_ - 1 : n_ind_; }

// Passes: ring r on itself (r), ring r on ring r + 1 (n + 2r) and ring r + 1 on ring r
// (n + 2r + 1).
int PolygonChain::contact_pass(int rs, int rm, bool self) const {
  if (self) return rs;
  return n_rings_ + 2 * std::min(rs, rm) + (rs > rm ? 1 : 0);
}

// A ring's own bars within two nodes of a node (either end) meet it at its hinges, not
// across the ring: they are no contact partners of it (the full ring counts around).
bool PolygonChain::near_own_segment(int j, int a) const {
  const int b = a + 1 == n_ind_ ? 0 : a + 1;
  const int da = std::abs(j - a), db = std::abs(j - b);
  const int dista = half_ ? da : std::min(da, n_ind_ - da);
  const int distb = half_ ? db : std::min(db, n_ind_ - db);
  return dista <= 2 || distb <= 2;
}

// Box of segment a of ring r grown by t, as {x_lo, y_lo, x_hi, y_hi} (the list builds).
void PolygonChain::segment_box(int r, int a, const double* y) {
  const auto oa = node_offset(r, a), ob = node_offset(r, a + 1 == n_ind_ ? 0 : a + 1);
  seg_box_[static_cast<std::size_t>(r * n_ind_ + a)] = {
      std::min(y[oa], y[ob]) - t_, std::min(y[oa + 1], y[ob + 1]) - t_,
      std::max(y[oa], y[ob]) + t_, std::max(y[oa + 1], y[ob + 1]) + t_};
}

void PolygonChain::update_contact_boxes(const double* y) {
  // The lists hold while every node is within half the margin (per coordinate) of where it
  // was: a segment left out had its end points' box, grown by t + margin, miss the node, so
  // its t-box still misses it. A node's (x, y) are one pair of the state (node_offset), so
  // the test runs on both at once, over all nodes without a branch. Between builds no box is
  // formed: node_segment_contact tests each listed segment's t-box from its end points
  // (≈ 180 listed pairs per evaluation on Test 30 welded against 144 segments' boxes, and
  // none on the plated chain).
  bool fresh = candidates_built_;
  if (fresh) {
    const double half_margin = 0.5 * candidate_margin_;
    const lanes::Pair reach = {half_margin, half_margin};
    lanes::PairMask stale = {0, 0};
    const double* reference = candidate_reference_.data();
    for (int g = 0; g < n_rings_ * n_ind_; ++g)
      stale |= ~(lanes::abs(lanes::load(y + 6 * static_cast<std::size_t>(g)) -
                            lanes::load(reference + 2 * static_cast<std::size_t>(g))) <= reach);
    fresh = !lanes::any(stale);
  }
  if (fresh) return;
  const int segs = contact_segments();
  for (int r = 0; r < n_rings_; ++r)
    for (int a = 0; a < segs; ++a) segment_box(r, a, y);
  build_candidates(y);
}

void PolygonChain::build_candidates(const double* y) {
  const int segs = contact_segments();
  const bool plates = in_.joint == PolygonJoint::Plates;
  candidate_segment_.clear();
  std::fill(candidate_start_.begin(), candidate_start_.end(), 0);
  candidate_nodes_.clear();
  // On top of the t already in seg_box_: the margin, and with the contact landing its reach
  // beyond the t-box (node_segment_contact), so that carried lists still hold every segment
  // whose box grown by 2t can take the node.
  const double grow = candidate_margin_ + (landing_depth_ > 0.0 ? t_ : 0.0);
  // Each ring's box (its segments' boxes together): a node outside it, grown, has no
  // candidate on that ring — most nodes of a neighbouring ring, which meets it at one place.
  std::vector<std::array<double, 4>>& ring_box = candidate_ring_box_;
  ring_box.assign(static_cast<std::size_t>(n_rings_), {0.0, 0.0, 0.0, 0.0});
  for (int r = 0; r < n_rings_; ++r) {
    auto& rb = ring_box[static_cast<std::size_t>(r)];
    rb = seg_box_[static_cast<std::size_t>(r * n_ind_)];
    for (int a = 1; a < segs; ++a) {
      const auto& sb = seg_box_[static_cast<std::size_t>(r * n_ind_ + a)];
      rb = {std::min(rb[0], sb[0]), std::min(rb[1], sb[1]), std::max(rb[2], sb[2]), std::max(rb[3], sb[3])};
    }
  }
  auto build = [&](int rs, int rm, bool self) {
    const int pass = contact_pass(rs, rm, self);
    const auto base = static_cast<std::size_t>(pass * (n_ind_ + 1));
    candidate_node_start_[2 * static_cast<std::size_t>(pass)] = static_cast<int>(candidate_nodes_.size());
    for (int j = 0; j < n_ind_; ++j) {
      const auto first = candidate_segment_.size();
      candidate_start_[base + static_cast<std::size_t>(j)] = static_cast<int>(first);
      const auto os = node_offset(rs, j);
      const double sx = y[os], sy = y[os + 1];
      const auto& rb = ring_box[static_cast<std::size_t>(rm)];
      const bool near_ring = sx >= rb[0] - grow && sx <= rb[2] + grow && sy >= rb[1] - grow && sy <= rb[3] + grow;
      for (int a = 0; near_ring && a < segs; ++a) {
        const auto& sb = seg_box_[static_cast<std::size_t>(rm * n_ind_ + a)];
        if (sx >= sb[0] - grow && sx <= sb[2] + grow && sy >= sb[1] - grow && sy <= sb[3] + grow &&
            !(self && near_own_segment(j, a)))  // the own ring's near bars: never a candidate
          candidate_segment_.push_back(a);
      }
      if (candidate_segment_.size() > first) candidate_nodes_.push_back(j);
    }
    candidate_start_[base + static_cast<std::size_t>(n_ind_)] = static_cast<int>(candidate_segment_.size());
    candidate_node_start_[2 * static_cast<std::size_t>(pass) + 1] = static_cast<int>(candidate_nodes_.size());
  };
  for (int r = 0; r < n_rings_; ++r) {
    build(r, r, true);
    if (!plates && r + 1 < n_rings_) {
      build(r, r + 1, false);
      build(r + 1, r, false);
    }
  }
  for (int g = 0; g < n_rings_ * n_ind_; ++g) {
    candidate_reference_[2 * static_cast<std::size_t>(g)] = y[static_cast<std::size_t>(g) * 6];
    candidate_reference_[2 * static_cast<std::size_t>(g) + 1] = y[static_cast<std::size_t>(g) * 6 + 1];
  }
  candidates_built_ = true;
}

void PolygonChain::node_segment_contact(int rs, int rm, bool self, const double* y, double* phi,
                                        bool record, Tally& tally) {
  const int pass = contact_pass(rs, rm, self);
  const auto base = static_cast<std::size_t>(pass * (n_ind_ + 1));
  // Only the slave nodes with candidates (in their order): the others meet no segment.
  const int* node_first = candidate_nodes_.data() + candidate_node_start_[2 * static_cast<std::size_t>(pass)];
  const int* node_last = candidate_nodes_.data() + candidate_node_start_[2 * static_cast<std::size_t>(pass) + 1];
  const double* master = y + node_offset(rm, 0);
  // The box each listed segment is tested against: grown by t, the touching pairs' reach —
  // and by 2t with the contact landing, whose closing pairs are those within a gap of t
  // (best < 2t below, polygon_contact_landing.cpp). With the t-box those were seen only once
  // touching, so a pair closing fast was first seen deep: on the welded chain at 50 m/s a
  // ring's inner walls met at 0.03 t and 32 m/s after a 2 µs step, 1e-3 of KE0 in one sample
  // at safety 1 (README, h51).
  const double reach = landing_depth_ > 0.0 ? 2.0 * t_ : t_;
  // The box shrinks to the closest segment found so far (polygon_closest_segment.hpp): the
  // same choice to the bit, fewer projections. The half model's segments end at a + 1
  // (a ≤ n_ind − 2), the full ring's last one wraps: one loop for each.
  const double shrink_margin = 1e-6 * t_;
  const int wrap = n_ind_ - 1;
  for (const int* jt = node_first; jt != node_last; ++jt) {
    const int j = *jt;
    const auto os = node_offset(rs, j);
    const lanes::Pair slave = lanes::load(y + os);
    const double sx = slave[0], sy = slave[1];
    const int* first = candidate_segment_.data() + candidate_start_[base + static_cast<std::size_t>(j)];
    const int* last = candidate_segment_.data() + candidate_start_[base + static_cast<std::size_t>(j) + 1];
    double best = t_ * 2.0, best_s = 0.0;
    int best_a = -1;
    if (half_)
      closest_segment<false>(slave, master, wrap, first, last, reach, shrink_margin, best, best_a, best_s);
    else
      closest_segment<true>(slave, master, wrap, first, last, reach, shrink_margin, best, best_a, best_s);
    if (best_a < 0) continue;
    const int a = best_a, b = a + 1 == n_ind_ ? 0 : a + 1;
    if (record) pairs_.push_back({rs * n_ind_ + j, rm * n_ind_ + a, rm * n_ind_ + b});
    const double pen = t_ - best;
    if (landing_depth_ > 0.0 && pen <= 0.0 && best < 2.0 * t_) {  // closing speed −(v − v_q)·n
      const auto oa = node_offset(rm, a), ob = node_offset(rm, b);
      const double s = best_s;
      // The normal's two quotients as one divpd (the divider's slot, not its width, is the cost).
      const lanes::Pair n = lanes::Pair{sx - ((1 - s) * y[oa] + s * y[ob]), sy - ((1 - s) * y[oa + 1] + s * y[ob + 1])} / best;
      const double nx = n[0], ny = n[1];
      const double vqx = (1 - s) * y[oa + 2] + s * y[ob + 2], vqy = (1 - s) * y[oa + 3] + s * y[ob + 3];
      note_landing(-pen, -((y[os + 2] - vqx) * nx + (y[os + 3] - vqy) * ny));
    }
    if (pen <= 0.0 && !jac_) continue;  // near pairs keep their (zero) Jacobian entries
    const bool touching = pen > 0.0;
    const auto oa = node_offset(rm, a), ob = node_offset(rm, b);
    const double s = best_s;
    const double qx = (1 - s) * y[oa] + s * y[ob], qy = (1 - s) * y[oa + 1] + s * y[ob + 1];
    const lanes::Pair n = lanes::Pair{sx - qx, sy - qy} / best;  // one divpd, as above
    const double nx = n[0], ny = n[1];
    const double vqx = (1 - s) * y[oa + 2] + s * y[ob + 2];
    const double vqy = (1 - s) * y[oa + 3] + s * y[ob + 3];
    const double rate = -((y[os + 2] - vqx) * nx + (y[os + 3] - vqy) * ny);
    const double w = node_weight(j);
    const double f = touching ? contact_load(w, pen, rate, tally) : 0.0;
    if (landing_depth_ > 0.0 && touching) note_landing(0.0, rate);  // at most `depth` deeper per step
    if (f > 0.0) {  // Gershgorin rows of the contact block c cᵀ, c = (1, −(1 − s), −s)
      add_contact_rows(static_cast<std::size_t>(rs * n_ind_ + j), 2.0 * w, pen, rate);
      add_contact_rows(static_cast<std::size_t>(rm * n_ind_ + a), 2.0 * w * (1 - s), pen, rate);
      add_contact_rows(static_cast<std::size_t>(rm * n_ind_ + b), 2.0 * w * s, pen, rate);
    }
    phi[os + 2] += f * nx;
    phi[os + 3] += f * ny;
    phi[oa + 2] -= (1 - s) * f * nx;
    phi[oa + 3] -= (1 - s) * f * ny;
    phi[ob + 2] -= s * f * nx;
    phi[ob + 3] -= s * f * ny;
    if (jac_) {  // dissipation w (f − k p) ṗ; ∂p/∂p_m = ∂ṗ/∂v_m = −c_m n (c as below)
      double dp = 0.0, dr = 0.0;
      if (touching) diss_partials(pen, rate, dp, dr);
      const std::array<std::size_t, 3> off{os, oa, ob};
      const std::array<double, 3> cw{1.0, -(1.0 - s), -s};
      for (int i = 0; i < 3; ++i) {
        jac(acc_base_ + 1, off[i], w * cw[i] * nx * dp);
        jac(acc_base_ + 1, off[i] + 1, w * cw[i] * ny * dp);
        jac(acc_base_ + 1, off[i] + 2, w * cw[i] * nx * dr);
        jac(acc_base_ + 1, off[i] + 3, w * cw[i] * ny * dr);
      }
    }
    if (jac_) {
      // Forces (f n, −(1 − s) f n, −s f n) on (slave, a, b) with the gap d = |p − q| and
      // ṗ = −n·(v − v_q): ∂F_i/∂p_m = −c_i c_m f_p n nᵀ, ∂F_i/∂v_m = −c_i c_m f_v n nᵀ,
      // c = (1, −(1 − s), −s). s and n are held: their rates (the slide along the segment)
      // move the force sideways, a small term next to the normal stiffness.
      const double fp = f > 0.0 ? w * k_n_ * (1.0 + chi_ * rate) : 0.0;
      const double fr = f > 0.0 ? w * k_n_ * pen * chi_ : 0.0;
      const std::array<std::size_t, 3> off{os, oa, ob};
      const std::array<double, 3> cw{1.0, -(1.0 - s), -s};
      const double nn[2][2] = {{nx * nx, nx * ny}, {ny * nx, ny * ny}};
      for (int i = 0; i < 3; ++i)
        for (int m = 0; m < 3; ++m) {
          const double c = cw[i] * cw[m];
          for (int a1 = 0; a1 < 2; ++a1)
            for (int b1 = 0; b1 < 2; ++b1) {
              jac(off[i] + 2 + static_cast<std::size_t>(a1), off[m] + static_cast<std::size_t>(b1), c * fp * nn[a1][b1]);
              jac(off[i] + 2 + static_cast<std::size_t>(a1), off[m] + 2 + static_cast<std::size_t>(b1),
                  c * fr * nn[a1][b1]);
            }
        }
    }
  }
}

}  // namespace ringcrush::hinge
