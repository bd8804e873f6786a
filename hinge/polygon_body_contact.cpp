// The polygon chain's joints and rigid bodies in its residual: welded ties (stiff springs,
// the thesis's *MPC), node–plate contact of the rings with the impactor, the plates and the
// target, and plate–plate contact once the rings between are flat (issue 7 item 1: nothing
// passes through anything). Hunt–Crossley normal contact, PolygonChain::contact_force.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "hinge/polygon_chain.hpp"

namespace ringcrush::hinge {

// Welded point B(r) — A(r+1), c = p_B − p_A − (0, t), energy ½ w k |c|².
void PolygonChain::tie_forces(const double* y, double* phi, bool record, Tally& tally) {
  if (record) tie_pairs_.clear();
  const int jb = half_ ? n_ind_ - 1 : n_full_ / 2;
  const double w = half_ ? 0.5 : 1.0;
  for (int r = 0; r + 1 < n_rings_; ++r) {
    const auto ob = node_offset(r, jb), oa = node_offset(r + 1, 0);
    const double cx = y[ob] - y[oa], cy = y[ob + 1] - y[oa + 1] - t_;
    const double fx = w * k_tie_ * cx, fy = w * k_tie_ * cy;
    if (!half_) {
      phi[ob + 2] -= fx;
      phi[oa + 2] += fx;
    }
    phi[ob + 3] -= fy;
    phi[oa + 3] += fy;
    if (jac_) {  // −∂φ/∂y of the tie spring, both components (x only in the full model)
      const double kk = w * k_tie_;
      for (int c = half_ ? 1 : 0; c < 2; ++c) {
        const auto rb = ob + 2 + static_cast<std::size_t>(c), ra = oa + 2 + static_cast<std::size_t>(c);
        const auto cb = ob + static_cast<std::size_t>(c), ca = oa + static_cast<std::size_t>(c);
        jac(rb, cb, kk);
        jac(rb, ca, -kk);
        jac(ra, cb, -kk);
        jac(ra, ca, kk);
      }
    }
    if (record) {
      tally.elastic += 0.5 * w * k_tie_ * (cx * cx + cy * cy);
      tie_pairs_.push_back({r * n_ind_ + jb, (r + 1) * n_ind_});
    }
  }
}

// Gap = distance of the node to the face − t/2; `above`: the body is above the ring.
void PolygonChain::plate_contact(int r, int body, bool above, double t, const double* y, double* phi,
                                 bool record, Tally& tally) {
  const double h = body < 0 ? 0.0 : bodies_[body].half_thickness;
  const double face = body_y(body, y) + (above ? -h : h);
  const double vface = body_v(body, t, y);
  for (int j = 0; j < n_ind_; ++j) {
    const auto o = node_offset(r, j);
    const double pen = above ? y[o + 1] + 0.5 * t_ - face : face - (y[o + 1] - 0.5 * t_);
    if (pen <= -t_) continue;
    if (record) body_contacts_.push_back({r * n_ind_ + j, body});
    if (landing_depth_ > 0.0 && pen <= 0.0) note_landing(-pen, above ? y[o + 3] - vface : vface - y[o + 3]);
    // Near pairs (within t) keep their Jacobian entries, as zeros while apart, so that the
    // sparse pattern, and the direct solver's symbolic analysis, survive contact chatter.
    if (pen <= 0.0 && !jac_) continue;
    const bool touching = pen > 0.0;
    const double rate = above ? y[o + 3] - vface : vface - y[o + 3];
    const double w = node_weight(j);
    const double f = touching ? contact_load(w, pen, rate, tally) : 0.0;
    if (landing_depth_ > 0.0 && touching) note_landing(0.0, rate);  // at most `depth` deeper per step
    if (f > 0.0) {  // Gershgorin rows of the node–body block
      add_contact_rows(static_cast<std::size_t>(r * n_ind_ + j), 2.0 * w, pen, rate);
      if (body >= 0)
        add_contact_rows(static_cast<std::size_t>(n_rings_ * n_ind_ + body), 2.0 * w, pen, rate);
    }
    const double fy = above ? -f : f;  // on the node
    phi[o + 3] += fy;
    const bool body_free = body >= 0 && !(body == 0 && in_.driven_impactor);
    if (body_free) phi[body_offset(body) + 1] -= fy;
    if (jac_) {  // contact dissipation rate w (f − k p) ṗ, s = ±1 as below
      const double sg = above ? 1.0 : -1.0;
      double dp = 0.0, dr = 0.0;
      if (touching) diss_partials(pen, rate, dp, dr);
      jac(acc_base_ + 1, o + 1, -w * sg * dp);
      jac(acc_base_ + 1, o + 3, -w * sg * dr);
      if (body >= 0) jac(acc_base_ + 1, body_offset(body), w * sg * dp);
      if (body_free) jac(acc_base_ + 1, body_offset(body) + 1, w * sg * dr);
    }
    if (jac_) {
      // p = s (y_node − y_body) + const, ṗ = s (v_node − v_body), s = ±1 (above/below);
      // node force −s f, body force s f.
      const double fp = f > 0.0 ? w * k_n_ * (1.0 + chi_ * rate) : 0.0;
      const double fr = f > 0.0 ? w * k_n_ * pen * chi_ : 0.0;
      if (body == 0 && in_.driven_impactor) {  // external power f · V of the driven plate
        const double v = prescribed_speed(t);
        jac(acc_base_ + 3, o + 1, -v * fp);
        jac(acc_base_ + 3, o + 3, -v * fr);
        jac(acc_base_ + 3, body_offset(0), v * fp);
      }
      jac(o + 3, o + 1, fp);
      jac(o + 3, o + 3, fr);
      if (body >= 0) {
        const auto ob = body_offset(body);
        jac(o + 3, ob, -fp);
        if (body_free) jac(o + 3, ob + 1, -fr);
        if (body_free) {
          jac(ob + 1, o + 1, -fp);
          jac(ob + 1, o + 3, -fr);
          jac(ob + 1, ob, fp);
          jac(ob + 1, ob + 1, fr);
        }
      }
    }
    if (body == 0) tally.impactor_force -= fy;
    if (body < 0) tally.target_force += f;
  }
}

// The backstop once the rings between are flat.
void PolygonChain::body_body_contact(double t, const double* y, double* phi, Tally& tally) {
  const bool plates = in_.joint == PolygonJoint::Plates;
  for (const auto& bb : body_body_) {
    const int upper = bb[0], lower = bb[1];
    const double hu = bodies_[upper].half_thickness;
    const double hl = lower < 0 ? 0.0 : bodies_[lower].half_thickness;
    const int between = plates ? 1 : n_rings_;
    const double pen = (body_y(lower, y) + hl) - (body_y(upper, y) - hu) + between * t_;
    if (pen <= 0.0) continue;
    const double rate = body_v(lower, t, y) - body_v(upper, t, y);
    double diss = 0.0;
    const double f = contact_force(pen, rate, diss);
    if (f > 0.0) {
      add_contact_rows(static_cast<std::size_t>(n_rings_ * n_ind_ + upper), 2.0, pen, rate);
      if (lower >= 0) add_contact_rows(static_cast<std::size_t>(n_rings_ * n_ind_ + lower), 2.0, pen, rate);
    }
    tally.dissipation += diss;
    tally.contact_energy += 0.5 * k_n_ * pen * pen;
    tally.max_penetration = std::max(tally.max_penetration, pen);
    const bool upper_free = !(upper == 0 && in_.driven_impactor);
    if (upper_free) phi[body_offset(upper) + 1] += f;
    if (upper == 0) tally.impactor_force += f;
    if (lower >= 0) phi[body_offset(lower) + 1] -= f;
    else tally.target_force += f;
    if (jac_) {  // dissipation (f − k p) ṗ with p, ṗ rising with the lower body
      double dp = 0.0, dr = 0.0;
      diss_partials(pen, rate, dp, dr);
      jac(acc_base_ + 1, body_offset(upper), dp);
      if (upper_free) jac(acc_base_ + 1, body_offset(upper) + 1, dr);
      if (lower >= 0) {
        jac(acc_base_ + 1, body_offset(lower), -dp);
        jac(acc_base_ + 1, body_offset(lower) + 1, -dr);
      }
    }
    if (jac_ && f > 0.0) {
      // ∂f/∂y_lower = −∂f/∂y_upper = k(1 + χ ṗ); ∂f/∂v_lower = −∂f/∂v_upper = k p χ.
      const double fp = k_n_ * (1.0 + chi_ * rate), fr = k_n_ * pen * chi_;
      const auto ou = body_offset(upper);
      if (upper == 0 && in_.driven_impactor) {
        const double v = prescribed_speed(t);
        jac(acc_base_ + 3, ou, v * fp);
        if (lower >= 0) jac(acc_base_ + 3, body_offset(lower), -v * fp);
        if (lower >= 0) jac(acc_base_ + 3, body_offset(lower) + 1, -v * fr);
      }
      auto row = [&](std::size_t rrow, double sign) {
        jac(rrow, ou, sign * fp);
        if (upper_free) jac(rrow, ou + 1, sign * fr);
        if (lower >= 0) {
          jac(rrow, body_offset(lower), -sign * fp);
          jac(rrow, body_offset(lower) + 1, -sign * fr);
        }
      };
      if (upper_free) row(ou + 1, 1.0);    // −∂(+f)/∂y
      if (lower >= 0) row(body_offset(lower) + 1, -1.0);
    }
  }
}

}  // namespace ringcrush::hinge
