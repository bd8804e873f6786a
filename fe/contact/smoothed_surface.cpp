#include "fe/contact/smoothed_surface.hpp"

#include <stdexcept>

namespace ringcrush::fe {

namespace {
inline void quad(double g, double* n, double* dn, double* ddn) {
  n[0] = 0.5 * g * (g - 1);
  n[1] = 1 - g * g;
  n[2] = 0.5 * g * (g + 1);
  dn[0] = g - 0.5;
  dn[1] = -2 * g;
  dn[2] = g + 0.5;
  ddn[0] = 1;
  ddn[1] = -2;
  ddn[2] = 1;
}
}  // namespace

void CurvePiece::coefficients(double f, double* c, double* dc, double* ddc) const {
  if (count == 3) {
    quad(f, c, dc, ddc);
    return;
  }
  const double f2 = f * f, f3 = f2 * f;
  const double h[4] = {(2 - 3 * f + f3) / 4, (2 + 3 * f - f3) / 4, (1 - f - f2 + f3) / 4, (-1 - f + f2 + f3) / 4};
  const double dh[4] = {(-3 + 3 * f2) / 4, (3 - 3 * f2) / 4, (-1 - 2 * f + 3 * f2) / 4, (-1 + 2 * f + 3 * f2) / 4};
  const double ddh[4] = {1.5 * f, -1.5 * f, (-2 + 6 * f) / 4, (2 + 6 * f) / 4};
  double na[3], dna[3], dd[3], nb[3], dnb[3];
  quad(1 - 2 * alpha, na, dna, dd);
  quad(-1 + 2 * alpha, nb, dnb, dd);
  for (int k = 0; k < 5; ++k) c[k] = dc[k] = ddc[k] = 0;
  for (int k = 0; k < 3; ++k) {
    // x_a, x_a' from the first segment (nodes 0..2), x_b, x_b' from the second (2..4).
    const double a0 = na[k], a1 = 2 * alpha * dna[k], b0 = nb[k], b1 = 2 * alpha * dnb[k];
    c[k] += h[0] * a0 + h[2] * a1;
    dc[k] += dh[0] * a0 + dh[2] * a1;
    ddc[k] += ddh[0] * a0 + ddh[2] * a1;
    c[k + 2] += h[1] * b0 + h[3] * b1;
    dc[k + 2] += dh[1] * b0 + dh[3] * b1;
    ddc[k + 2] += ddh[1] * b0 + ddh[3] * b1;
  }
}

std::vector<CurvePiece> smoothed_chain(const std::vector<SurfaceSegment>& chain, double alpha) {
  if (!(alpha >= 0 && alpha < 0.5)) throw std::invalid_argument("contact smoothing must lie in [0, 0.5)");
  std::vector<CurvePiece> out;
  const std::size_t n = chain.size();
  for (std::size_t s = 0; s < n; ++s) {
    if (s > 0 && chain[s].nodes[0] != chain[s - 1].nodes[2])
      throw std::invalid_argument("smoothed_chain: segments are not consecutive");
    CurvePiece q;
    q.count = 3;
    q.nodes = {chain[s].nodes[0], chain[s].nodes[1], chain[s].nodes[2], -1, -1};
    q.lo = (s > 0 && alpha > 0) ? -1 + 2 * alpha : -1;
    q.hi = (s + 1 < n && alpha > 0) ? 1 - 2 * alpha : 1;
    out.push_back(q);
    if (s + 1 < n && alpha > 0) {
      CurvePiece h;
      h.count = 5;
      h.alpha = alpha;
      h.nodes = {chain[s].nodes[0], chain[s].nodes[1], chain[s].nodes[2], chain[s + 1].nodes[1], chain[s + 1].nodes[2]};
      h.lo = -1;
      h.hi = 1;
      out.push_back(h);
    }
  }
  return out;
}

std::vector<std::vector<SurfaceSegment>> inner_wall_runs(const RingMesh& ring, const std::function<bool(double)>& in_set) {
  const auto& segs = ring.inner_segments;
  const std::size_t n = segs.size();
  auto member = [&](std::size_t s) { return in_set(ring.node_angle[segs[s].nodes[1]]); };
  std::size_t start = 0;
  if (!ring.half_ring)
    for (std::size_t s = 0; s < n; ++s)
      if (member(s) && !member((s + n - 1) % n)) { start = s; break; }
  std::vector<std::vector<SurfaceSegment>> out;
  std::vector<SurfaceSegment> cur;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t s = (start + i) % n;
    if (member(s)) cur.push_back(segs[s]);
    else if (!cur.empty()) { out.push_back(cur); cur.clear(); }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

}  // namespace ringcrush::fe
