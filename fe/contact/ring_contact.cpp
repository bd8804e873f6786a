#include "fe/contact/ring_contact.hpp"

#include "fe/contact/plate_friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ringcrush::fe {

namespace {

// Closest point of xs on the piece (Newton on (x(f) − xs)·x'(f) = 0 from the best sample).
// Returns false when the closest point is an end of the piece that is not a stationary point
// (the neighbouring piece or nobody owns the node).
bool project(const CurvePiece& p, const double* xy, double& f, bool strict) {
  // strict = false (tangent differencing): the piece's polynomial continues past its ends,
  // which matches the C¹ neighbour to second order.
  const double lo = strict ? p.lo : p.lo - 0.5, hi = strict ? p.hi : p.hi + 0.5;
  double c[5], dc[5], ddc[5];
  const double xs = xy[0], ys = xy[1];
  auto eval = [&](double t, double& px, double& py, double& tx, double& ty, double& kx, double& ky) {
    p.coefficients(t, c, dc, ddc);
    px = py = tx = ty = kx = ky = 0;
    for (int k = 0; k < p.count; ++k) {
      const double nx = xy[2 + 2 * k], ny = xy[3 + 2 * k];
      px += c[k] * nx; py += c[k] * ny;
      tx += dc[k] * nx; ty += dc[k] * ny;
      kx += ddc[k] * nx; ky += ddc[k] * ny;
    }
  };
  double px, py, tx, ty, kx, ky;
  if (!(f >= lo && f <= hi)) {
    double best = 1e300;
    for (int s = 0; s <= 4; ++s) {
      const double t = p.lo + (p.hi - p.lo) * s / 4.0;
      eval(t, px, py, tx, ty, kx, ky);
      const double d2 = (px - xs) * (px - xs) + (py - ys) * (py - ys);
      if (d2 < best) { best = d2; f = t; }
    }
  }
  for (int it = 0; it < 30; ++it) {
    eval(f, px, py, tx, ty, kx, ky);
    const double r = (px - xs) * tx + (py - ys) * ty;
    const double dr = tx * tx + ty * ty + (px - xs) * kx + (py - ys) * ky;
    double step = dr > 0 ? -r / dr : (r > 0 ? -0.25 : 0.25) * (p.hi - p.lo);
    double next = std::clamp(f + step, lo, hi);
    const double moved = std::abs(next - f);
    f = next;
    if (moved < 1e-14) break;
  }
  eval(f, px, py, tx, ty, kx, ky);
  const double r = (px - xs) * tx + (py - ys) * ty;
  const double scale = std::sqrt(tx * tx + ty * ty) * std::hypot(px - xs, py - ys);
  if (!strict) return true;
  const double tol = 1e-9 * (p.hi - p.lo);
  if (f <= p.lo + tol && r > 1e-9 * scale) return false;   // minimum lies before the piece
  if (f >= p.hi - tol && r < -1e-9 * scale) return false;  // minimum lies after the piece
  return true;
}

}  // namespace

bool self_contact_force(const CurvePiece& p, const double* xy, double k, double max_depth, double* force,
                        double& gap, double& f, bool strict) {
  const int n = 2 + 2 * p.count;
  std::fill(force, force + n, 0.0);
  if (!project(p, xy, f, strict)) return false;
  double c[5], dc[5], ddc[5];
  p.coefficients(f, c, dc, ddc);
  double px = 0, py = 0, tx = 0, ty = 0;
  for (int a = 0; a < p.count; ++a) {
    px += c[a] * xy[2 + 2 * a]; py += c[a] * xy[3 + 2 * a];
    tx += dc[a] * xy[2 + 2 * a]; ty += dc[a] * xy[3 + 2 * a];
  }
  const double tl = std::hypot(tx, ty);
  // Left normal of a counter-clockwise inner wall points into the hole.
  const double nx = -ty / tl, ny = tx / tl;
  gap = (xy[0] - px) * nx + (xy[1] - py) * ny;
  if (!(gap < 0 && gap > -max_depth)) return false;
  // Energy ½ k g²: ∂/∂x_s = k g n, ∂/∂x_a = −k g c_a n (the terms through f and n vanish
  // at the closest point since (x_s − x)·x' = 0 and n·∂n = 0).
  force[0] = k * gap * nx;
  force[1] = k * gap * ny;
  for (int a = 0; a < p.count; ++a) {
    force[2 + 2 * a] = -k * gap * c[a] * nx;
    force[3 + 2 * a] = -k * gap * c[a] * ny;
  }
  return true;
}

namespace {
// Σ_a w_a x_a over a piece's nodes (xy: slave then piece nodes): a point (w = c) or a
// tangent (w = dc/dξ) of the piece.
Eigen::Vector2d piece_combination(const CurvePiece& p, const double* w, const double* xy) {
  double x = 0, y = 0;
  for (int a = 0; a < p.count; ++a) {
    x += w[a] * xy[2 + 2 * a];
    y += w[a] * xy[3 + 2 * a];
  }
  return {x, y};
}
}  // namespace

bool self_contact_friction_force(const CurvePiece& p, const double* xy, double k, double kt, double mu,
                                 double anchor_n, double max_depth, double* force, double& gap, double& f,
                                 SurfaceFriction& fr, bool strict) {
  fr = SurfaceFriction{};
  if (!self_contact_force(p, xy, k, max_depth, force, gap, f, strict)) return false;
  double c[5], dc[5], ddc[5];
  p.coefficients(f, c, dc, ddc);
  const Eigen::Vector2d tangent = piece_combination(p, dc, xy);
  const double tx = tangent.x(), ty = tangent.y();
  const double tl = std::hypot(tx, ty);
  const double ux = tx / tl, uy = ty / tl;
  const double fn = -k * gap;
  fr.anchor = f;
  if (std::isnan(anchor_n)) return true;  // touch-down: stick here, no force yet
  // The stick point's current position on the (continued) piece.
  double ca[5], dca[5], ddca[5];
  p.coefficients(anchor_n, ca, dca, ddca);
  const Eigen::Vector2d stick = piece_combination(p, ca, xy);
  const double ax = stick.x(), ay = stick.y();
  const double slip = (xy[0] - ax) * ux + (xy[1] - ay) * uy;
  const double trial = -kt * slip;
  const double limit = mu * fn;
  double t = trial;
  fr.anchor = anchor_n;
  if (std::abs(trial) > limit) {
    t = trial > 0 ? limit : -limit;
    fr.slipping = true;
    fr.anchor = f + t / (kt * tl);
    fr.dissipation = limit * std::abs(trial - t) / kt;
  }
  fr.traction = t;
  fr.stored_energy = 0.5 * t * t / kt;
  // Residual = −(force on the node): the slave gets t τ, the piece nodes −c_a t τ.
  force[0] -= t * ux;
  force[1] -= t * uy;
  for (int a = 0; a < p.count; ++a) {
    force[2 + 2 * a] += c[a] * t * ux;
    force[3 + 2 * a] += c[a] * t * uy;
  }
  return true;
}

RingContact::RingContact(const RingMesh& mesh, const ContactInput& input, double e, double width)
    : mesh_(mesh), in_(input), width_(width), band_(1e-9 * mesh.element_depth) {
  const double kscale = input.penalty_scale * e * width / mesh.element_depth;
  const double ktscale = input.tangential_penalty_scale * e * width / mesh.element_depth;
  for (double w : mesh.outer_weight) {
    k_outer_.push_back(kscale * w);
    kt_outer_.push_back(ktscale * w);
    area_outer_.push_back(w * width);
  }
  // Every node starts anchored at its reference position on both plates.
  for (int node : mesh.outer_nodes)
    for (int plate = 0; plate < 2; ++plate) anchor_n_.push_back(mesh.nodes[node].x());
  anchor_trial_ = anchor_n_;
  if (!input.self_contact) return;
  const double pi = std::numbers::pi;
  // Lower (y < 0) and upper (y > 0) halves of the inner wall in the reference configuration.
  auto lower = [&](double phi) {
    const double y = -std::cos(phi);
    return y < -1e-12;
  };
  auto upper = [&](double phi) { return -std::cos(phi) > 1e-12; };
  auto chains = [&](auto pred) { return inner_wall_runs(mesh, pred); };
  auto make_pass = [&](auto slave_pred, auto master_pred) {
    Pass p;
    for (std::size_t i = 0; i < mesh.inner_nodes.size(); ++i) {
      const int node = mesh.inner_nodes[i];
      if (!slave_pred(mesh.node_angle[node])) continue;
      p.slaves.push_back(node);
      p.slave_k.push_back(kscale * mesh.inner_weight[i]);
      p.slave_kt.push_back(ktscale * mesh.inner_weight[i]);
      p.anchor_n.push_back(std::numeric_limits<double>::quiet_NaN());
      p.slave_area.push_back(mesh.inner_weight[i] * width);
    }
    double start = 0;
    for (const auto& ch : chains(master_pred)) {
      auto pieces = smoothed_chain(ch, input.smoothing);
      for (const CurvePiece& q : pieces) {
        p.piece_start.push_back(start);
        start += (q.hi - q.lo) * surface_speed(q);
      }
      start += 10;
      p.pieces.insert(p.pieces.end(), pieces.begin(), pieces.end());
    }
    return p;
  };
  passes_.push_back(make_pass(lower, upper));
  if (input.self_contact_two_pass) passes_.push_back(make_pass(upper, lower));
  for (Pass& p : passes_) p.anchor_trial = p.anchor_n;
  (void)pi;
}

bool RingContact::self_pair(const Pass&, const Eigen::Vector2d& xs, int slave, const CurvePiece& piece,
                            const std::vector<Eigen::Vector2d>& x, double& f, double& gap, double& dist) const {
  // Broad phase: reference separation along the wall and a box around the piece.
  const double pi = std::numbers::pi;
  for (int a = 0; a < piece.count; ++a) {
    double d = std::abs(mesh_.node_angle[slave] - mesh_.node_angle[piece.nodes[a]]);
    d = std::min(d, 2 * pi - d);
    if (d < in_.self_contact_min_separation_rad) return false;
  }
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
  for (int a = 0; a < piece.count; ++a) {
    const auto& p = x[piece.nodes[a]];
    lo_x = std::min(lo_x, p.x()); hi_x = std::max(hi_x, p.x());
    lo_y = std::min(lo_y, p.y()); hi_y = std::max(hi_y, p.y());
  }
  const double pad = mesh_.element_depth + 0.1 * std::max(hi_x - lo_x, hi_y - lo_y);
  if (xs.x() < lo_x - pad || xs.x() > hi_x + pad || xs.y() < lo_y - pad || xs.y() > hi_y + pad) return false;
  double xy[12], force[12];
  xy[0] = xs.x(); xy[1] = xs.y();
  for (int a = 0; a < piece.count; ++a) { xy[2 + 2 * a] = x[piece.nodes[a]].x(); xy[3 + 2 * a] = x[piece.nodes[a]].y(); }
  f = piece.lo - 1.0;  // outside the range: start from samples
  const bool ok = self_contact_force(piece, xy, 1.0, mesh_.element_depth, force, gap, f, true);
  if (!ok) return false;
  dist = std::abs(gap);
  return true;
}

void RingContact::evaluate(const std::vector<Eigen::Vector2d>& x, double y_top, double y_bottom, bool want_tangent,
                           bool want_pressure, std::vector<ContactContribution>& out, ContactState& st) {
  st = ContactState{};
  const bool friction = frictional();
  dissipation_trial_ = dissipation_n_;
  if (want_pressure) st.node_pressure.assign(mesh_.nodes.size(), 0.0);
  // Rigid plates (node to plane; the plate is flat, so the gap is exact).
  for (std::size_t i = 0; i < mesh_.outer_nodes.size(); ++i) {
    const int node = mesh_.outer_nodes[i];
    const double k = k_outer_[i];
    for (int plate = 0; plate < 2; ++plate) {
      const double sign = plate == 0 ? -1.0 : 1.0;  // outward normal of the plate into the ring
      const double gap = plate == 0 ? y_top - x[node].y() : x[node].y() - y_bottom;
      const std::size_t slot = 2 * i + static_cast<std::size_t>(plate);
      if (friction) anchor_trial_[slot] = x[node].x();  // re-anchored unless in contact below
      if (gap >= band_) continue;
      ContactContribution c;
      c.count = 1;
      c.nodes[0] = node;
      if (gap < 0) {
        // Energy ½ k g², g = sign·(y − y_plate): force k g sign on u_y.
        c.force(1) = k * gap * sign;
        const double f = -k * gap;
        (plate == 0 ? st.top_force : st.bottom_force) += f;
        st.energy += 0.5 * k * gap * gap;
        st.max_plate_penetration = std::max(st.max_plate_penetration, -gap);
        ++st.plate_contacts;
        if (want_pressure) st.node_pressure[node] += f / area_outer_[i];
        if (friction) {
          // f_n = −k g with ∂g/∂y = sign, so ∂f_n/∂y = −k sign.
          const PlateFriction fr =
              plate_friction(x[node].x(), f, -k * sign, kt_outer_[i], in_.friction_coefficient, anchor_n_[slot]);
          anchor_trial_[slot] = fr.anchor;
          c.force(0) = -fr.traction;
          if (want_tangent) {
            c.tangent(0, 0) = fr.dr_dx;
            c.tangent(0, 1) = fr.dr_dy;
          }
          st.energy += fr.stored_energy;
          dissipation_trial_ += fr.dissipation;
          (plate == 0 ? st.top_friction_force : st.bottom_friction_force) += std::abs(fr.traction);
          if (fr.slipping) ++st.slipping_contacts;
        }
      }
      if (want_tangent) c.tangent(1, 1) = k;
      out.push_back(c);
    }
  }
  // Inner wall against itself.
  for (Pass& p : passes_) {
    for (std::size_t s = 0; s < p.slaves.size(); ++s) {
      if (friction) p.anchor_trial[s] = std::numeric_limits<double>::quiet_NaN();  // unless in contact below
      const int node = p.slaves[s];
      const Eigen::Vector2d& xs = x[node];
      int best = -1;
      double best_dist = 1e300, best_f = 0, gap = 0;
      for (std::size_t q = 0; q < p.pieces.size(); ++q) {
        double f, g, dist;
        if (self_pair(p, xs, node, p.pieces[q], x, f, g, dist) && dist < best_dist) {
          best = static_cast<int>(q); best_dist = dist; best_f = f; gap = g;
        }
      }
      if (best < 0) continue;
      const CurvePiece& piece = p.pieces[best];
      const double k = p.slave_k[s];
      ContactContribution c;
      c.count = 1 + piece.count;
      c.nodes[0] = node;
      double xy[12];
      xy[0] = xs.x(); xy[1] = xs.y();
      for (int a = 0; a < piece.count; ++a) {
        c.nodes[1 + a] = piece.nodes[a];
        xy[2 + 2 * a] = x[piece.nodes[a]].x();
        xy[3 + 2 * a] = x[piece.nodes[a]].y();
      }
      const int n = 2 * c.count;
      double f = best_f, g;
      // Friction: the committed stick point as a parameter of this piece (from the surface
      // coordinate S, continued linearly past the piece's ends).
      const double kt = p.slave_kt[s];
      const double lo = piece.lo, w = surface_speed(piece), s0 = p.piece_start[static_cast<std::size_t>(best)];
      const double anchor_n = std::isnan(p.anchor_n[s]) ? p.anchor_n[s] : lo + (p.anchor_n[s] - s0) / w;
      SurfaceFriction fr;
      if (friction) {
        self_contact_friction_force(piece, xy, k, kt, in_.friction_coefficient, anchor_n, mesh_.element_depth,
                                    c.force.data(), g, f, fr, true);
        p.anchor_trial[s] = s0 + (fr.anchor - lo) * w;
      } else {
        self_contact_force(piece, xy, k, mesh_.element_depth, c.force.data(), g, f, true);
      }
      if (want_tangent) {
        // Tangent by central differences of the exact local force (a 12×12 block at most,
        // the committed stick point held fixed).
        const double h = 1e-7 * mesh_.element_depth;
        double fp[12], fm[12];
        for (int j = 0; j < n; ++j) {
          const double keep = xy[j];
          double gg, ff = best_f;
          SurfaceFriction unused;
          auto local = [&](double* result) {
            if (friction)
              self_contact_friction_force(piece, xy, k, kt, in_.friction_coefficient, anchor_n,
                                          10 * mesh_.element_depth, result, gg, ff, unused, false);
            else
              self_contact_force(piece, xy, k, 10 * mesh_.element_depth, result, gg, ff, false);
          };
          xy[j] = keep + h;
          local(fp);
          ff = best_f;
          xy[j] = keep - h;
          local(fm);
          xy[j] = keep;
          for (int i = 0; i < n; ++i) c.tangent(i, j) = (fp[i] - fm[i]) / (2 * h);
        }
        // Frictionless, the force is the gradient of the penalty energy: symmetrise away the
        // differencing noise. With friction the tangent is genuinely non-symmetric.
        if (!friction) {
          const Eigen::Matrix<double, 12, 12> t = c.tangent;
          c.tangent = 0.5 * (t + t.transpose());
        }
      }
      const double fn = -k * gap;
      st.self_force += fn;
      st.energy += 0.5 * k * gap * gap + fr.stored_energy;
      dissipation_trial_ += fr.dissipation;
      st.self_friction_force += std::abs(fr.traction);
      if (fr.slipping) ++st.slipping_contacts;
      st.max_self_penetration = std::max(st.max_self_penetration, -gap);
      ++st.self_contacts;
      if (want_pressure) st.node_pressure[node] += fn / p.slave_area[s];
      out.push_back(c);
    }
  }
  st.friction_dissipation = dissipation_trial_;
}

void RingContact::commit() {
  if (!frictional()) return;
  anchor_n_ = anchor_trial_;
  for (Pass& p : passes_) p.anchor_n = p.anchor_trial;
  dissipation_n_ = dissipation_trial_;
}

}  // namespace ringcrush::fe
