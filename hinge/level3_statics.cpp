// Statics check of a Level 3 ring shape: the least max |M|/M0 over the redundants.
//
// Moment at shape point p (free body from the cut at A to p; anticlockwise positive):
//   M(p) = M_A + H (y_p − y_A) + Σ_loads before p of (r − p) × F,
// with F = (0, −P/2) at the top contact edge and (0, +P/2) at the bottom one. M is affine
// in (M_A, H); for a fixed H the best M_A centres the range, so max |M| = ½ (max − min) of
// H h + g, a convex piecewise-linear function of H: golden section finds its minimum.
#include "level3_statics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ringcrush::hinge {

namespace {

void check_shape(const Level3Shape& s) {
  if (s.points.size() < 3 || s.theta.size() != s.points.size())
    throw std::invalid_argument(fmt::format("statics: shape with {} points and {} angles (need >= 3, equal)",
                                            s.points.size(), s.theta.size()));
  for (std::size_t k = 1; k < s.theta.size(); ++k)
    if (!(s.theta[k] > s.theta[k - 1]))
      throw std::invalid_argument(fmt::format("statics: material angle not increasing at point {} ({} rad)", k, s.theta[k]));
}

// Indices of the vertices of the convex hull of the points (x_k, y_k) (Andrew's monotone
// chain; collinear points dropped).
std::vector<std::size_t> hull_vertices(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<std::size_t> idx(x.size());
  for (std::size_t k = 0; k < idx.size(); ++k) idx[k] = k;
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b] || (x[a] == x[b] && y[a] < y[b]); });
  auto cross = [&](std::size_t o, std::size_t a, std::size_t b) {
    return (x[a] - x[o]) * (y[b] - y[o]) - (y[a] - y[o]) * (x[b] - x[o]);
  };
  std::vector<std::size_t> h(2 * idx.size());
  std::size_t m = 0;
  for (std::size_t k : idx) {  // lower chain
    while (m >= 2 && cross(h[m - 2], h[m - 1], k) <= 0) --m;
    h[m++] = k;
  }
  const std::size_t lower = m + 1;
  for (std::size_t j = idx.size() - 1; j-- > 0;) {  // upper chain
    const std::size_t k = idx[j];
    while (m >= lower && cross(h[m - 2], h[m - 1], k) <= 0) --m;
    h[m++] = k;
  }
  h.resize(m > 1 ? m - 1 : m);
  return h;
}

}  // namespace

Level3Contacts level3_contact_edges(const Level3Shape& s) {
  check_shape(s);
  double ymin = s.points.front()[1], ymax = ymin, span = 0.0;
  for (const auto& p : s.points) {
    ymin = std::min(ymin, p[1]);
    ymax = std::max(ymax, p[1]);
  }
  span = std::max(ymax - ymin, 1e-300);
  const double tol = 1e-6 * span;  // a flat is drawn exactly level; a round top falls off as θ²
  const double half = 0.5 * std::numbers::pi;
  Level3Contacts c;
  double top = -1e300, bot = 1e300;
  for (std::size_t k = 0; k < s.points.size(); ++k)
    if (s.theta[k] <= half) top = std::max(top, s.points[k][1]);
    else bot = std::min(bot, s.points[k][1]);
  for (std::size_t k = 0; k < s.points.size(); ++k)  // outermost point of the top flat
    if (s.theta[k] <= half && s.points[k][1] >= top - tol) c.top = k;
  c.bottom = s.points.size() - 1;
  for (std::size_t k = s.points.size(); k-- > 0;)  // outermost point of the bottom flat
    if (s.theta[k] > half && s.points[k][1] <= bot + tol) c.bottom = k;
  c.top_edge = s.points[c.top];
  c.bottom_edge = s.points[c.bottom];
  // x₀ of the parabola through (x1, y1), (x2, y2) tangent to the flat y = yf beyond x_last.
  auto edge = [](double yf, double xl, const std::array<double, 2>& p1, const std::array<double, 2>& p2) {
    const double d1 = std::abs(yf - p1[1]), d2 = std::abs(yf - p2[1]);
    if (!(d2 > d1) || !(p1[0] > xl)) return xl;
    const double r = std::sqrt(d1 / d2);
    return std::clamp((p1[0] - r * p2[0]) / (1.0 - r), xl, p1[0]);
  };
  const std::size_t n = s.points.size();
  if (c.top > 0 && c.top + 2 < n)  // a flat of two or more points: the arc follows it
    c.top_edge[0] = edge(top, s.points[c.top][0], s.points[c.top + 1], s.points[c.top + 2]);
  if (c.bottom + 1 < n && c.bottom >= 2)
    c.bottom_edge[0] = edge(bot, s.points[c.bottom][0], s.points[c.bottom - 1], s.points[c.bottom - 2]);
  return c;
}

Level3Statics level3_statics_check(const Level3Shape& s, double load_n, double M0) {
  check_shape(s);
  if (!(load_n >= 0.0) || !std::isfinite(load_n))
    throw std::invalid_argument(fmt::format("statics: load = {} N (need finite, >= 0)", load_n));
  if (!(M0 > 0.0) || !std::isfinite(M0)) throw std::invalid_argument(fmt::format("statics: M0 = {} N·m (need > 0)", M0));
  const auto c = level3_contact_edges(s);
  const std::size_t n = s.points.size();
  const auto& pa = s.points.front();
  std::vector<double> h(n), g(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const auto& p = s.points[k];
    h[k] = p[1] - pa[1];
    if (k > c.top) g[k] -= (c.top_edge[0] - p[0]) * 0.5 * load_n;
    if (k >= c.bottom) g[k] += (c.bottom_edge[0] - p[0]) * 0.5 * load_n;  // edge lies before point c.bottom
  }
  // max_k (H h_k + g_k) is attained on the convex hull of the points (h_k, g_k), so the
  // search only visits its vertices (a few dozen of a few hundred points).
  const auto hull = hull_vertices(h, g);
  auto range = [&](double H, double& lo, double& hi) {
    lo = 1e300;
    hi = -1e300;
    for (std::size_t k : hull) {
      const double m = H * h[k] + g[k];
      lo = std::min(lo, m);
      hi = std::max(hi, m);
    }
    return 0.5 * (hi - lo);
  };
  // |H| beyond P + M0/extent only widens the range: a generous bracket, then golden section.
  double extent = 0.0;
  for (double v : h) extent = std::max(extent, std::abs(v));
  const double bound = 4.0 * (load_n + M0 / std::max(extent, 1e-12));
  double a = -bound, b = bound, lo = 0.0, hi = 0.0;
  const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - gr * (b - a), x2 = a + gr * (b - a);
  double f1 = range(x1, lo, hi), f2 = range(x2, lo, hi);
  for (int it = 0; it < 48; ++it) {  // 0.618^48 of the bracket: H to 1e-10 (P + M0/extent)
    if (f1 < f2) { b = x2; x2 = x1; f2 = f1; x1 = b - gr * (b - a); f1 = range(x1, lo, hi); }
    else { a = x1; x1 = x2; f1 = f2; x2 = a + gr * (b - a); f2 = range(x2, lo, hi); }
  }
  Level3Statics out;
  out.horizontal_force_n = 0.5 * (a + b);
  const double half_range = range(out.horizontal_force_n, lo, hi);
  out.moment_a_nm = -0.5 * (lo + hi);
  out.moment_nm.resize(n);
  std::size_t kmax = 0;
  for (std::size_t k = 0; k < n; ++k) {
    out.moment_nm[k] = out.moment_a_nm + out.horizontal_force_n * h[k] + g[k];
    if (std::abs(out.moment_nm[k]) > std::abs(out.moment_nm[kmax])) kmax = k;
  }
  out.peak_ratio = half_range / M0;
  out.angle_deg = s.theta[kmax] * 180.0 / std::numbers::pi;
  const double top = std::abs(out.moment_nm[kmax]);
  bool in_run = false;
  for (std::size_t k = 0; k < n; ++k) {
    const bool at = std::abs(out.moment_nm[k]) >= top * (1.0 - 1e-6);
    if (at && !in_run) out.peak_angles_deg.push_back(s.theta[k] * 180.0 / std::numbers::pi);
    in_run = at;
  }
  return out;
}

}  // namespace ringcrush::hinge
