#include "fe/contact/ring_pair_contact.hpp"

#include "fe/contact/self_contact_taper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace ringcrush::fe {

namespace {

// Position, tangent and curvature vector of a piece at f (coords: slave first), through the
// geometric polynomial x(f) = A0 + A1 f + A2 f² + A3 f³.
struct Cubic {
  double a[4][2];
  explicit Cubic(const double (&coefficients)[4][2]) { std::copy(&coefficients[0][0], &coefficients[0][0] + 8, &a[0][0]); }
  Cubic(const PiecePolynomial& p, const double* xy) {
    for (int q = 0; q < 4; ++q) {
      a[q][0] = a[q][1] = 0;
      for (int k = 0; k < p.count; ++k) {
        a[q][0] += p.a[k][q] * xy[2 + 2 * k];
        a[q][1] += p.a[k][q] * xy[3 + 2 * k];
      }
    }
  }
  void at(double f, double* pos, double* tan, double* curv) const {
    for (int d = 0; d < 2; ++d) {
      pos[d] = a[0][d] + f * (a[1][d] + f * (a[2][d] + f * a[3][d]));
      tan[d] = a[1][d] + f * (2 * a[2][d] + 3 * f * a[3][d]);
      curv[d] = 2 * a[2][d] + 6 * f * a[3][d];
    }
  }
};

// Range [lo, hi] over f ∈ [p_lo, p_hi] of the cubic c0 + c1 f + c2 f² + c3 f³ (ends and the
// interior extrema).
void cubic_range(double c0, double c1, double c2, double c3, double p_lo, double p_hi, double& lo, double& hi) {
  auto value = [&](double f) { return c0 + f * (c1 + f * (c2 + f * c3)); };
  lo = std::min(value(p_lo), value(p_hi));
  hi = std::max(value(p_lo), value(p_hi));
  auto consider = [&](double f) {
    if (f > p_lo && f < p_hi) {
      const double v = value(f);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  };
  // x'(f) = a1 + 2 a2 f + 3 a3 f² = 0
  const double a = 3 * c3, b = 2 * c2, k = c1;
  if (std::abs(a) > 1e-12 * (std::abs(b) + std::abs(k))) {
    const double disc = b * b - 4 * a * k;
    if (disc >= 0) {
      const double r = std::sqrt(disc);
      consider((-b + r) / (2 * a));
      consider((-b - r) / (2 * a));
    }
  } else if (b != 0) {
    consider(-k / b);
  }
}

// Bounding box {lo x, hi x, lo y, hi y} of the curve itself over [lo, hi] (ends and the
// interior extrema of each coordinate's cubic): an exact lower bound of the distance from
// a point to the piece is its distance to this box.
void curve_box(const PiecePolynomial& p, const Cubic& c, double* box) {
  for (int d = 0; d < 2; ++d) cubic_range(c.a[0][d], c.a[1][d], c.a[2][d], c.a[3][d], p.lo, p.hi, box[2 * d], box[2 * d + 1]);
}
void curve_box(const PiecePolynomial& p, const double* xy, double* box) { curve_box(p, Cubic(p, xy), box); }

// Closest point of (xs, ys) on the cubic (surface_gap's iteration; the cubic formed once per
// piece and evaluation by SurfaceContact).
bool closest_point(const Cubic& cubic, double p_lo, double p_hi, double xs, double ys, unsigned char symmetric_end,
                   bool strict, double& f, double& gap) {
  // strict = false: the piece's polynomial continues past its ends (it matches the C¹
  // neighbour to second order), for finite differences about an accepted closest point.
  const double lo = strict ? p_lo : p_lo - 0.5, hi = strict ? p_hi : p_hi + 0.5;
  double pos[2], tan[2], curv[2];
  if (!(f >= lo && f <= hi)) {
    double best = 1e300;
    for (int s = 0; s <= 4; ++s) {
      const double t = p_lo + (p_hi - p_lo) * s / 4.0;
      cubic.at(t, pos, tan, curv);
      const double d2 = (pos[0] - xs) * (pos[0] - xs) + (pos[1] - ys) * (pos[1] - ys);
      if (d2 < best) { best = d2; f = t; }
    }
  }
  // Newton on (x(f) − x_s)·x'(f) = 0.
  for (int it = 0; it < 30; ++it) {
    cubic.at(f, pos, tan, curv);
    const double r = (pos[0] - xs) * tan[0] + (pos[1] - ys) * tan[1];
    const double dr = tan[0] * tan[0] + tan[1] * tan[1] + (pos[0] - xs) * curv[0] + (pos[1] - ys) * curv[1];
    const double step = dr > 0 ? -r / dr : (r > 0 ? -0.25 : 0.25) * (p_hi - p_lo);
    const double next = std::clamp(f + step, lo, hi);
    const double moved = std::abs(next - f);
    f = next;
    if (moved < 1e-14) break;
  }
  cubic.at(f, pos, tan, curv);
  const double tl = std::sqrt(tan[0] * tan[0] + tan[1] * tan[1]);
  if (!(tl > 0)) return false;
  const double nx = -tan[1] / tl, ny = tan[0] / tl;
  gap = (xs - pos[0]) * nx + (ys - pos[1]) * ny;
  if (!strict) return true;
  const double r = (pos[0] - xs) * tan[0] + (pos[1] - ys) * tan[1];
  const double scale = tl * std::sqrt((pos[0] - xs) * (pos[0] - xs) + (pos[1] - ys) * (pos[1] - ys));
  const double tol = 1e-9 * (p_hi - p_lo);
  if (f <= p_lo + tol && r > 1e-9 * scale && !(symmetric_end & 1)) return false;  // minimum before the piece
  if (f >= p_hi - tol && r < -1e-9 * scale && !(symmetric_end & 2)) return false;  // minimum after it
  return true;
}

// A pieces chain from segments; closed: the last segment joins the first (full ring).
// Returns the pieces and the symmetric-end flags.
void add_chain(const std::vector<SurfaceSegment>& chain, bool closed, bool lo_symmetric, bool hi_symmetric,
               double smoothing, ContactPass& p) {
  if (chain.empty()) return;
  std::vector<CurvePiece> pieces;
  if (closed && smoothing > 0) {
    // Smooth the wrap junction too: chain + first segment again, then the duplicate of the
    // first segment is dropped and the first piece starts after the junction.
    std::vector<SurfaceSegment> loop(chain);
    loop.push_back(chain.front());
    pieces = smoothed_chain(loop, smoothing);
    pieces.pop_back();
    pieces.front().lo = -1 + 2 * smoothing;
  } else {
    pieces = smoothed_chain(chain, smoothing);
  }
  for (std::size_t q = 0; q < pieces.size(); ++q) {
    unsigned char flag = 0;
    if (!closed && q == 0 && lo_symmetric) flag |= 1;
    if (!closed && q + 1 == pieces.size() && hi_symmetric) flag |= 2;
    p.pieces.push_back(pieces[q]);
    p.symmetric_end.push_back(flag);
  }
}

double wrapped_angle(double a, double b) {
  const double pi = std::numbers::pi;
  double d = std::abs(a - b);
  d = std::fmod(d, 2 * pi);
  return std::min(d, 2 * pi - d);
}

}  // namespace

PiecePolynomial::PiecePolynomial(const CurvePiece& piece) : count(piece.count), lo(piece.lo), hi(piece.hi) {
  // c(0) = a0, c'(0) = a1, c''(0) = 2 a2, c''(1) − c''(0) = 6 a3.
  double c0[5], d0[5], dd0[5], c1[5], d1[5], dd1[5];
  piece.coefficients(0.0, c0, d0, dd0);
  piece.coefficients(1.0, c1, d1, dd1);
  for (int k = 0; k < count; ++k) {
    a[k][0] = c0[k];
    a[k][1] = d0[k];
    a[k][2] = 0.5 * dd0[k];
    a[k][3] = (dd1[k] - dd0[k]) / 6.0;
  }
}

bool surface_gap(const PiecePolynomial& p, const double* xy, unsigned char symmetric_end, bool strict, double& f,
                 double& gap) {
  return closest_point(Cubic(p, xy), p.lo, p.hi, xy[0], xy[1], symmetric_end, strict, f, gap);
}

void surface_force(const PiecePolynomial& p, const double* xy, double k, double f, double gap, double* force) {
  const int n = 2 + 2 * p.count;
  std::fill(force, force + n, 0.0);
  if (!(gap < 0)) return;
  double pos[2], tan[2], curv[2];
  Cubic(p, xy).at(f, pos, tan, curv);
  const double tl = std::sqrt(tan[0] * tan[0] + tan[1] * tan[1]);
  const double nx = -tan[1] / tl, ny = tan[0] / tl;
  // ∂(½ k g²)/∂x_s = k g n and ∂/∂x_a = −k g c_a n: the terms through f and n vanish at the
  // closest point ((x_s − x)·x' = 0, n·∂n = 0). Σ over all nodes is zero: action = reaction.
  double c[5];
  for (int a = 0; a < p.count; ++a) c[a] = p.a[a][0] + f * (p.a[a][1] + f * (p.a[a][2] + f * p.a[a][3]));
  force[0] = k * gap * nx;
  force[1] = k * gap * ny;
  for (int a = 0; a < p.count; ++a) {
    force[2 + 2 * a] = -k * gap * c[a] * nx;
    force[3 + 2 * a] = -k * gap * c[a] * ny;
  }
}

ContactPass outer_pass(const RingMesh& ring, const std::vector<int>& slave_map, int slave,
                       const std::vector<int>& master_map, int master, double k_scale, double width,
                       double smoothing) {
  ContactPass p;
  p.self = false;
  p.slave_ring = slave;
  p.master_ring = master;
  // Slaves: the slave ring's outer nodes that are not also master nodes (a welded node lies
  // on both surfaces by construction).
  std::vector<int> master_nodes(master_map);
  std::sort(master_nodes.begin(), master_nodes.end());
  for (std::size_t i = 0; i < ring.outer_nodes.size(); ++i) {
    const int g = slave_map[ring.outer_nodes[i]];
    if (std::binary_search(master_nodes.begin(), master_nodes.end(), g)) continue;
    p.slaves.push_back(g);
    p.slave_k.push_back(k_scale * ring.outer_weight[i]);
    p.slave_area.push_back(ring.outer_weight[i] * width);
  }
  // Master: the outer edges in clockwise order (reversed), so that the left normal points
  // out of the ring.
  const std::size_t columns = ring.outer_nodes.size();
  const std::size_t segments = ring.half_ring ? (columns - 1) / 2 : columns / 2;
  std::vector<SurfaceSegment> chain;
  for (std::size_t s = segments; s-- > 0;) {
    const int a = master_map[ring.outer_nodes[2 * s]], b = master_map[ring.outer_nodes[2 * s + 1]],
              c = master_map[ring.outer_nodes[(2 * s + 2) % columns]];
    chain.push_back({{c, b, a}, -1});
  }
  add_chain(chain, !ring.half_ring, ring.half_ring, ring.half_ring, smoothing, p);
  return p;
}

std::vector<ContactPass> inner_wall_passes(const RingMesh& ring, const std::vector<int>& map, int ring_index,
                                           double k_scale, double width, double smoothing,
                                           double min_separation, double taper_band, bool two_pass) {
  const auto& segs = ring.inner_segments;
  auto base = [&] {
    ContactPass p;
    p.self = true;
    p.slave_ring = p.master_ring = ring_index;
    p.min_separation = min_separation;
    p.taper_band = taper_band;
    return p;
  };
  auto add_slaves = [&](ContactPass& p, auto slave_pred) {
    for (std::size_t i = 0; i < ring.inner_nodes.size(); ++i) {
      const int node = ring.inner_nodes[i];
      if (!slave_pred(ring.node_angle[node])) continue;
      p.slaves.push_back(map[node]);
      p.slave_k.push_back(k_scale * ring.inner_weight[i]);
      p.slave_area.push_back(ring.inner_weight[i] * width);
      p.slave_angle.push_back(ring.node_angle[node]);
    }
  };
  // A run of consecutive segments as master pieces (closed: the whole wall of a full ring),
  // with the reference angles of their nodes, then the nodes mapped to global ids.
  auto add_master = [&](ContactPass& p, const std::vector<SurfaceSegment>& run, bool closed) {
    const bool lo_sym = !closed && ring.half_ring && std::abs(ring.nodes[run.front().nodes[0]].x()) < 1e-14;
    const bool hi_sym = !closed && ring.half_ring && std::abs(ring.nodes[run.back().nodes[2]].x()) < 1e-14;
    const std::size_t first = p.pieces.size();
    add_chain(run, closed, lo_sym, hi_sym, smoothing, p);
    for (std::size_t q = first; q < p.pieces.size(); ++q) {
      std::array<double, 5> ang{};
      for (int a = 0; a < p.pieces[q].count; ++a) {
        ang[a] = ring.node_angle[p.pieces[q].nodes[a]];
        p.pieces[q].nodes[a] = map[p.pieces[q].nodes[a]];
      }
      p.piece_angle.push_back(ang);
    }
  };
  std::vector<ContactPass> out;
  if (two_pass) {
    // Symmetric (no master/slave bias, issue 4 item 2): every inner node, the side point C
    // included, is a slave against the whole inner wall, one C¹ surface through C; only its
    // own neighbourhood of the wall is left out (the exclusion and its taper). Each touching
    // pair of wall points is then seen from both sides, as the former two half passes did
    // away from C; but the former split at C (lower half y < 0 on the upper y > 0 and back)
    // left the node at C (y = 0) a slave of neither, ended both master surfaces at C (a
    // node whose closest point ran past C lost its whole force at once) and never paired two
    // points of the same half, however far apart along the wall (README "FE dynamics",
    // stability matrix; tests/fe/side_point_contact_test.cpp).
    ContactPass p = base();
    add_slaves(p, [](double) { return true; });
    add_master(p, segs, !ring.half_ring);
    out.push_back(std::move(p));
    return out;
  }
  // One-sided (two_pass = false): the lower half's nodes (y < 0) against the upper half
  // (y > 0) only, as RingContact's first pass; kept for tests that need a pure slave.
  auto lower = [](double phi) { return -std::cos(phi) < -1e-12; };
  auto upper = [](double phi) { return -std::cos(phi) > 1e-12; };
  ContactPass p = base();
  add_slaves(p, lower);
  for (const auto& run : inner_wall_runs(ring, upper)) add_master(p, run, false);
  out.push_back(std::move(p));
  return out;
}

SurfaceContact::SurfaceContact(std::vector<ContactPass> passes, double depth, double arrival_depth)
    : passes_(std::move(passes)), depth_(depth), skin_(kSkin * depth) {
  if (!(depth > 0)) throw std::invalid_argument("SurfaceContact: element depth must be positive");
  arrival_ = ContactArrival(passes_, arrival_depth);
  for (const auto& p : passes_) {
    if (p.self) ArcTaper(p.min_separation, p.taper_band);  // throws on a bad exclusion or band
    for (int s : p.slaves) tracked_.push_back(s);
    for (const auto& q : p.pieces)
      for (int a = 0; a < q.count; ++a) tracked_.push_back(q.nodes[a]);
  }
  std::sort(tracked_.begin(), tracked_.end());
  tracked_.erase(std::unique(tracked_.begin(), tracked_.end()), tracked_.end());
  x_build_.resize(tracked_.size());
  start_.resize(passes_.size());
  near_slaves_.resize(passes_.size());
  for (const auto& p : passes_) {
    auto& polys = poly_.emplace_back();
    for (const auto& q : p.pieces) polys.emplace_back(q);
    cache_.emplace_back(p.pieces.size());
    auto& unwrapped = unwrapped_.emplace_back();
    if (p.self)
      for (std::size_t q = 0; q < p.pieces.size(); ++q)
        unwrapped.push_back(unwrapped_piece_angles(p.piece_angle[q], p.pieces[q].count));
  }
  slave_omega2_.resize(passes_.size());
  for (std::size_t p = 0; p < passes_.size(); ++p) slave_omega2_[p].assign(passes_[p].slaves.size(), 0.0);
}

void SurfaceContact::set_mass(const Eigen::VectorXd& mass) {
  for (std::size_t p = 0; p < passes_.size(); ++p) {
    const auto& pass = passes_[p];
    double inv_master = 0;
    for (const auto& q : pass.pieces)
      for (int a = 0; a < q.count; ++a) inv_master = std::max(inv_master, 1.0 / mass(2 * q.nodes[a] + 1));
    // Rank-one contact element k G Gᵀ, G = [n; −c_a n]: its frequency² over the lumped mass
    // is k (1/m_s + Σ c_a²/m_a); Σ c_a² ≤ 1 on the quadratic and Hermite pieces (smoothing
    // up to 0.49), 1.25 keeps a margin.
    for (std::size_t s = 0; s < pass.slaves.size(); ++s)
      slave_omega2_[p][s] = pass.slave_k[s] * (1.0 / mass(2 * pass.slaves[s] + 1) + 1.25 * inv_master);
  }
}

void SurfaceContact::rebuild(const std::vector<Eigen::Vector2d>& x) {
  ++rebuilds_;
  built_ = true;
  for (std::size_t i = 0; i < tracked_.size(); ++i) x_build_[i] = x[tracked_[i]];
  candidate_piece_.clear();
  busy_passes_.clear();
  std::vector<std::array<double, 4>> box;  // padded piece boxes (lo x, hi x, lo y, hi y)
  // Runs of kRun consecutive pieces share a box (the union of theirs): a slave outside it
  // skips the run's pieces, in the same order otherwise, so the list is the same.
  constexpr std::size_t kRun = 8;
  std::vector<std::array<double, 4>> run_box;
  for (std::size_t pi = 0; pi < passes_.size(); ++pi) {
    const ContactPass& p = passes_[pi];
    auto& start = start_[pi];
    start.assign(p.slaves.size() + 1, static_cast<int>(candidate_piece_.size()));
    near_slaves_[pi].clear();
    box.resize(p.pieces.size());
    double m_lo_x = 1e300, m_hi_x = -1e300, m_lo_y = 1e300, m_hi_y = -1e300;
    for (std::size_t q = 0; q < p.pieces.size(); ++q) {
      double xy[12], cb[4];
      for (int a = 0; a < p.pieces[q].count; ++a) {
        xy[2 + 2 * a] = x[p.pieces[q].nodes[a]].x();
        xy[3 + 2 * a] = x[p.pieces[q].nodes[a]].y();
      }
      curve_box(poly_[pi][q], xy, cb);
      const double lx = cb[0], hx = cb[1], ly = cb[2], hy = cb[3];
      // Wider than the evaluation pad by 3 skins: until the next build the slave moves less
      // than one skin and the curve less than two (Σ|c_k| ≤ 1.5 on every piece, smoothing
      // up to 0.49).
      const double pad = depth_ + 3 * skin_;
      box[q] = {lx - pad, hx + pad, ly - pad, hy + pad};
      m_lo_x = std::min(m_lo_x, box[q][0]); m_hi_x = std::max(m_hi_x, box[q][1]);
      m_lo_y = std::min(m_lo_y, box[q][2]); m_hi_y = std::max(m_hi_y, box[q][3]);
    }
    run_box.assign((p.pieces.size() + kRun - 1) / kRun, {1e300, -1e300, 1e300, -1e300});
    for (std::size_t q = 0; q < p.pieces.size(); ++q) {
      auto& r = run_box[q / kRun];
      r = {std::min(r[0], box[q][0]), std::max(r[1], box[q][1]), std::min(r[2], box[q][2]), std::max(r[3], box[q][3])};
    }
    for (std::size_t s = 0; s < p.slaves.size(); ++s) {
      start[s] = static_cast<int>(candidate_piece_.size());
      const auto& xs = x[p.slaves[s]];
      const bool in_box = !(xs.x() < m_lo_x || xs.x() > m_hi_x || xs.y() < m_lo_y || xs.y() > m_hi_y);
      for (std::size_t q = 0; in_box && q < p.pieces.size(); ++q) {
        if (q % kRun == 0) {
          const auto& r = run_box[q / kRun];
          if (xs.x() < r[0] || xs.x() > r[1] || xs.y() < r[2] || xs.y() > r[3]) {
            q += kRun - 1;  // the loop's ++q moves to the next run
            continue;
          }
        }
        const auto& b = box[q];
        if (xs.x() < b[0] || xs.x() > b[1] || xs.y() < b[2] || xs.y() > b[3]) continue;
        if (p.self) {
          // A piece wholly inside the exclusion is joined to the slave by the wall; one that
          // straddles its edge stays a candidate, the taper weighs its closest point.
          bool joined = true;
          for (int a = 0; a < p.pieces[q].count && joined; ++a)
            joined = wrapped_angle(p.slave_angle[s], p.piece_angle[q][a]) < p.min_separation;
          if (joined) continue;
        }
        candidate_piece_.push_back(static_cast<int>(q));
      }
      // A remembered pair stays listed however deep it was pushed (contact_arrival.hpp).
      if (const int kept = arrival_.remembered_piece(pi, s);
          kept >= 0 && std::find(candidate_piece_.begin() + start[s], candidate_piece_.end(), kept) == candidate_piece_.end())
        candidate_piece_.push_back(kept);
      if (static_cast<int>(candidate_piece_.size()) > start[s]) near_slaves_[pi].push_back(static_cast<int>(s));
    }
    start[p.slaves.size()] = static_cast<int>(candidate_piece_.size());
    if (!near_slaves_[pi].empty()) busy_passes_.push_back(static_cast<int>(pi));
  }
}

void SurfaceContact::refresh(std::size_t pass, int piece, const std::vector<Eigen::Vector2d>& x) {
  const CurvePiece& q = passes_[pass].pieces[piece];
  const PiecePolynomial& poly = poly_[pass][piece];
  PieceCache& pc = cache_[pass][piece];
  double xy[12] = {};
  for (int a = 0; a < q.count; ++a) { xy[2 + 2 * a] = x[q.nodes[a]].x(); xy[3 + 2 * a] = x[q.nodes[a]].y(); }
  const Cubic cubic(poly, xy);
  std::copy(&cubic.a[0][0], &cubic.a[0][0] + 8, &pc.a[0][0]);
  if (passes_[pass].symmetric_end[piece]) curve_box(poly, cubic, pc.box);  // only they use it
  // The chord frame: t from the end at lo to the end at hi; a piece shrunk to a point
  // (never on a valid mesh) gets the x–y frame, whose box is then the x–y box.
  double pos0[2], pos1[2], tan[2], curv[2];
  cubic.at(poly.lo, pos0, tan, curv);
  cubic.at(poly.hi, pos1, tan, curv);
  const double cx = pos1[0] - pos0[0], cy = pos1[1] - pos0[1], chord = std::sqrt(cx * cx + cy * cy);
  pc.t[0] = chord > 0 ? cx / chord : 1.0;
  pc.t[1] = chord > 0 ? cy / chord : 0.0;
  const double tx = pc.t[0], ty = pc.t[1];
  auto along = [&](int k) { return cubic.a[k][0] * tx + cubic.a[k][1] * ty; };
  auto across = [&](int k) { return cubic.a[k][1] * tx - cubic.a[k][0] * ty; };
  cubic_range(along(0), along(1), along(2), along(3), poly.lo, poly.hi, pc.range[0], pc.range[1]);
  cubic_range(across(0), across(1), across(2), across(3), poly.lo, poly.hi, pc.range[2], pc.range[3]);
  // Tangent bounds for the open-gap certificate: x'·t = A1 + 2 A2 f + 3 A3 f² over |f| ≤ F
  // is at least A1 − 2|A2| F − 3|A3| F², and |x'·n| at most the sum of the magnitudes (no
  // root to find; the pieces are nearly straight, A1 dominates).
  const double F = std::max(std::abs(poly.lo), std::abs(poly.hi));
  pc.along_min = along(1) - (2 * std::abs(along(2)) + 3 * std::abs(along(3)) * F) * F;
  pc.across_max = std::abs(across(1)) + (2 * std::abs(across(2)) + 3 * std::abs(across(3)) * F) * F;
  pc.stamp = stamp_;
}

bool SurfaceContact::certified_open(const PieceCache& pc, double x, double y, double depth) {
  // (x_s − x(f))·n(f) |x'(f)| = (x'·t)(v_s − v(f)) − (x'·n)(u_s − u(f)) in the chord frame
  // (u along t, v along its left normal n): with x'·t ≥ a > 0 and v_s − v(f) ≥ dv > 0 it is at
  // least dv a − du b, du the farthest the slave lies from the piece along the chord.
  const double a = pc.along_min, b = pc.across_max;
  if (!(a > 0)) return false;
  const double along = x * pc.t[0] + y * pc.t[1], across = y * pc.t[0] - x * pc.t[1];
  const double dv = across - pc.range[3];
  if (!(dv > 0)) return false;
  const double du = std::max(along - pc.range[0], pc.range[1] - along);
  return dv * a - du * b > 1e-9 * depth * (a + b);
}

void SurfaceContact::evaluate(const std::vector<Eigen::Vector2d>& x, bool want_tangent,
                              std::vector<ContactContribution>& out, std::vector<std::pair<int, double>>* pressure,
                              SurfaceContactState& st) {
  begin(x);
  for (std::size_t pi = 0; pi < passes_.size(); ++pi) search(pi, x);
  finish(x, want_tangent, out, pressure, st);
}

void SurfaceContact::begin(const std::vector<Eigen::Vector2d>& x) {
  bool stale = !built_;
  const double skin2 = skin_ * skin_;
  for (std::size_t i = 0; i < tracked_.size() && !stale; ++i)
    stale = (x[tracked_[i]] - x_build_[i]).squaredNorm() >= skin2;
  if (stale) rebuild(x);
  ++stamp_;
  if (found_.size() != passes_.size()) found_.resize(passes_.size());
  for (auto& r : found_) {
    r.hits.clear();
    r.near_omega2 = 0;
    r.near_node = -1;
    r.spared = 0;
  }
  arrival_.begin();
}

void SurfaceContact::search(std::size_t pi, const std::vector<Eigen::Vector2d>& x) {
  const ContactPass& p = passes_[pi];
  const auto& start = start_[pi];
  PassFound& found = found_[pi];
  const ArcTaper taper(p.self ? p.min_separation : 0.0, p.self ? p.taper_band : 0.0);
  double xy[12];
  for (const int si : near_slaves_[pi]) {
    const auto s = static_cast<std::size_t>(si);
    const int node = p.slaves[s];
    const Eigen::Vector2d& xs = x[node];
    int best = -1;
    double best_abs = depth_, best_f = 0, best_gap = 0;
    // Candidates within one depth of the curve's box, with that distance as a lower bound
    // of their |gap|; projected nearest-first, and no further once the bound exceeds the
    // best |gap| found: the result is the same, most projections are not made. At a
    // symmetry-plane end the accepted gap can be shorter than the distance, so such pieces
    // get no bound.
    struct Near { double bound; int piece; };
    std::array<Near, 64> near;
    int count = 0;
    // Every candidate within one depth certifies an open gap (header: "Open slaves").
    bool open = spare_open_;
    auto project = [&](int q) {
      const PiecePolynomial& poly = poly_[pi][q];
      double f = poly.lo - 1.0, gap = 0;
      // surface_gap() on the cubic formed once this evaluation (the same arithmetic).
      if (!closest_point(Cubic(cache_[pi][q].a), poly.lo, poly.hi, xs.x(), xs.y(), p.symmetric_end[q], true, f, gap))
        return;
      // Self contact: a closest point inside the exclusion is the slave's own wall, not a
      // partner (its weight is zero, so dropping it is continuous).
      const auto qi = static_cast<std::size_t>(q);
      if (p.self && taper.weight(arc_to_closest_point(poly, p.piece_angle[qi], unwrapped_[pi][qi], p.slave_angle[s],
                                                      f, nullptr)) == 0)
        return;
      // The closest owned piece decides (a node behind the wall of another piece is not
      // "penetrating" it).
      if (std::abs(gap) < best_abs) { best = q; best_abs = std::abs(gap); best_f = f; best_gap = gap; }
    };
    for (int c = start[s]; c < start[s + 1]; ++c) {
      const int q = candidate_piece_[c];
      PieceCache& pc = cache_[pi][q];
      if (pc.stamp != stamp_) refresh(pi, q, x);
      double bound = -1.0;
      if (p.symmetric_end[q]) {
        const double* cb = pc.box;
        const double dx = std::max({cb[0] - xs.x(), 0.0, xs.x() - cb[1]}), dy = std::max({cb[2] - xs.y(), 0.0, xs.y() - cb[3]});
        if (dx >= depth_ || dy >= depth_) continue;
      } else {
        // Distance to the chord-frame box: no more than the distance to the curve, which
        // is |gap| at an accepted closest point; a piece at one depth or more can never be
        // the closest within one depth.
        const double along = xs.x() * pc.t[0] + xs.y() * pc.t[1], across = xs.y() * pc.t[0] - xs.x() * pc.t[1];
        const double du = std::max({pc.range[0] - along, 0.0, along - pc.range[1]});
        const double dv = std::max({pc.range[2] - across, 0.0, across - pc.range[3]});
        if (du >= depth_ || dv >= depth_) continue;
        bound = std::sqrt(du * du + dv * dv);
      }
      if (open) open = certified_open(pc, xs.x(), xs.y(), depth_);
      if (count < static_cast<int>(near.size())) near[count++] = {bound, q};
      else project(q);
    }
    if (open && count > 0 && arrival_.remembered_piece(pi, s) < 0 && !(slave_omega2_[pi][s] > found.near_omega2)) {
      ++found.spared;
      continue;
    }
    while (count > 0) {
      int k = 0;
      for (int i = 1; i < count; ++i)
        if (near[i].bound < near[k].bound || (near[i].bound == near[k].bound && near[i].piece < near[k].piece)) k = i;
      if (near[k].bound >= best_abs) break;
      project(near[k].piece);
      near[k] = near[--count];
    }
    // Arrival rule (contact_arrival.hpp): a remembered pair is found again on its
    // neighbourhood of the surface, past the reach if need be, and decides while closed.
    bool continuing = false;
    if (const int kept = arrival_.remembered_piece(pi, s); kept >= 0) {
      if (best >= 0 && arrival_.near(pi, kept, best)) {
        continuing = best_gap < 0;
      } else if (!(best >= 0 && best_gap < 0 && arrival_.remembered_refused(pi, s))) {
        // (A refused pair blocks nothing elsewhere: a closed pair found on another piece
        // is judged as an arrival.)
        const int found_piece = best;
        const double found_f = best_f, found_gap = best_gap;
        best = -1;
        best_abs = std::numeric_limits<double>::infinity();
        for (const int q : arrival_.neighbourhood(pi, kept)) {
          if (cache_[pi][q].stamp != stamp_) refresh(pi, q, x);
          project(q);
        }
        continuing = best >= 0 && best_gap < 0;
        if (!continuing) { best = found_piece; best_f = found_f; best_gap = found_gap; }
      }
    }
    if (best < 0) continue;
    if (slave_omega2_[pi][s] > found.near_omega2) { found.near_omega2 = slave_omega2_[pi][s]; found.near_node = node; }
    if (!(best_gap < 0)) continue;
    if (!arrival_.admit(pi, s, best, best_gap, continuing, node, p.master_ring, p.self)) continue;
    const CurvePiece& piece = p.pieces[best];
    const PiecePolynomial& poly = poly_[pi][best];
    const double k = p.slave_k[s];
    Hit& h = found.hits.emplace_back();
    h.slave = si;
    h.piece = best;
    h.f = best_f;
    h.gap = best_gap;
    xy[0] = xs.x(); xy[1] = xs.y();
    for (int a = 0; a < piece.count; ++a) {
      xy[2 + 2 * a] = x[piece.nodes[a]].x();
      xy[3 + 2 * a] = x[piece.nodes[a]].y();
    }
    std::fill(h.force, h.force + 12, 0.0);
    // The local force (self contact: tapered at the exclusion's edge; weight 1 elsewhere).
    if (p.self) {
      h.weight = tapered_self_force(poly, xy, k, best_f, best_gap, taper, p.slave_angle[s],
                                    p.piece_angle[static_cast<std::size_t>(best)], h.force);
    } else {
      surface_force(poly, xy, k, best_f, best_gap, h.force);
      h.weight = 1.0;
    }
  }
}

long SurfaceContact::spared_slaves() const {
  long n = 0;
  for (const auto& r : found_) n += r.spared;
  return n;
}

void SurfaceContact::finish(const std::vector<Eigen::Vector2d>& x, bool want_tangent,
                            std::vector<ContactContribution>& out, std::vector<std::pair<int, double>>* pressure,
                            SurfaceContactState& st) const {
  st = SurfaceContactState{};
  double xy[12];
  // Pass by pass, slave by slave in the order of the serial scan: the sums and the first
  // maximum are those of one loop, whichever thread searched which pass.
  for (std::size_t pi = 0; pi < passes_.size(); ++pi) {
    const ContactPass& p = passes_[pi];
    const PassFound& found = found_[pi];
    if (found.near_omega2 > st.near_omega2) { st.near_omega2 = found.near_omega2; st.near_node = found.near_node; }
    const ArcTaper taper(p.self ? p.min_separation : 0.0, p.self ? p.taper_band : 0.0);
    for (const Hit& h : found.hits) {
      const auto s = static_cast<std::size_t>(h.slave);
      const int node = p.slaves[s];
      const CurvePiece& piece = p.pieces[h.piece];
      const PiecePolynomial& poly = poly_[pi][h.piece];
      const double k = p.slave_k[s];
      ContactContribution& c = out.emplace_back();
      c.count = 1 + piece.count;
      c.nodes[0] = node;
      for (int a = 0; a < piece.count; ++a) c.nodes[1 + a] = piece.nodes[a];
      std::copy(h.force, h.force + 12, c.force.data());
      // The full penalty k, not k·weight: the stable-step bound must not underrate the spring.
      c.stiffness = k;
      c.gap = h.gap;
      if (want_tangent) {
        xy[0] = x[node].x(); xy[1] = x[node].y();
        for (int a = 0; a < piece.count; ++a) {
          xy[2 + 2 * a] = x[piece.nodes[a]].x();
          xy[3 + 2 * a] = x[piece.nodes[a]].y();
        }
        const std::array<double, 5>* angles = p.self ? &p.piece_angle[static_cast<std::size_t>(h.piece)] : nullptr;
        auto local_force = [&](double at, double g, double* force) {
          if (angles) {
            tapered_self_force(poly, xy, k, at, g, taper, p.slave_angle[s], *angles, force);
            return;
          }
          surface_force(poly, xy, k, at, g, force);
        };
        // Central differences of the exact local force (12×12 at most), symmetrised: the
        // force is the gradient of the penalty energy.
        const int n = 2 * c.count;
        const double step = 1e-7 * depth_;
        double fp[12], fm[12];
        c.tangent.setZero();
        for (int j = 0; j < n; ++j) {
          const double keep = xy[j];
          double ff = h.f, gg = 0;
          xy[j] = keep + step;
          surface_gap(poly, xy, 0, false, ff, gg);
          local_force(ff, gg, fp);
          ff = h.f;
          xy[j] = keep - step;
          surface_gap(poly, xy, 0, false, ff, gg);
          local_force(ff, gg, fm);
          xy[j] = keep;
          for (int i = 0; i < n; ++i) c.tangent(i, j) = (fp[i] - fm[i]) / (2 * step);
        }
        const Eigen::Matrix<double, 12, 12> t = c.tangent;
        c.tangent = 0.5 * (t + t.transpose());
      }
      const double fn = -h.weight * k * h.gap;
      (p.self ? st.self_force : st.ring_ring_force) += fn;
      st.energy += 0.5 * h.weight * k * h.gap * h.gap;
      if (-h.gap > st.max_penetration) {
        st.max_penetration = -h.gap;
        st.deepest_node = node;
        st.deepest_master_ring = p.master_ring;
        st.deepest_self = p.self;
      }
      ++st.active;
      if (pressure) pressure->emplace_back(node, fn / p.slave_area[s]);
    }
  }
}

}  // namespace ringcrush::fe
