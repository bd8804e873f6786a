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

// The field M = M_A + H h + g of least max |M| over the redundants (M_A, H): h_k = y_k − y_A,
// g_k the moment of the loads between A and point k; load_n the loads' size (the bracket).
Level3Statics least_peak_field(const Level3Shape& s, const std::vector<double>& h, const std::vector<double>& g,
                               double load_n, double M0) {
  const std::size_t n = s.points.size();
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
  return least_peak_field(s, h, g, load_n, M0);
}

std::array<double, 2> level3_uniform_relative_accel(double R, double theta, double phi, double w, double a) {
  // Upper quadrant, material angle θ' = min(θ, π − θ) (THEORY §1.3, mid-plane fixed): on the
  // flat (θ' < φ) x = Rθ', y = R(1 − sin φ); on the arc, ψ = θ' − φ,
  // x = Rφ + R sin ψ, y = R cos ψ − R sin φ; differentiated twice in time (ψ̇ = −φ̇).
  const bool lower = theta > 0.5 * std::numbers::pi;
  const double t = lower ? std::numbers::pi - theta : theta;
  std::array<double, 2> acc;
  if (t < phi) {
    acc = {0.0, -R * (std::cos(phi) * a - std::sin(phi) * w * w)};
  } else {
    const double psi = t - phi;
    acc = {R * a * (1.0 - std::cos(psi)) - R * w * w * std::sin(psi),
           R * a * (std::sin(psi) - std::cos(phi)) + R * w * w * (std::sin(phi) - std::cos(psi))};
  }
  if (lower) acc[1] = -acc[1];
  return acc;
}

Level3Statics level3_statics_check(const Level3Shape& s, const Level3RingLoads& L, double M0) {
  check_shape(s);
  // A contact force below zero (a tension no contact carries) is checked as given: the chain
  // reports it (level3_inertia.cpp throws on a rigid ring's), the statics need not refuse it.
  for (double v : {L.top_n, L.bottom_n})
    if (!std::isfinite(v)) throw std::invalid_argument(fmt::format("statics: contact force = {} N (need finite)", v));
  if (!(L.mass_kg >= 0.0) || !std::isfinite(L.mass_kg))
    throw std::invalid_argument(fmt::format("statics: ring mass = {} kg (need finite, >= 0)", L.mass_kg));
  for (double v : {L.centre_accel_m_s2, L.phi, L.phi_rate, L.phi_accel})
    if (!std::isfinite(v)) throw std::invalid_argument(fmt::format("statics: acceleration or rate = {} (need finite)", v));
  if (L.uniform_motion && !(L.radius_m > 0.0 && std::isfinite(L.radius_m)))
    throw std::invalid_argument(fmt::format("statics: radius = {} m for the relative motion (need > 0)", L.radius_m));
  if (!(M0 > 0.0) || !std::isfinite(M0)) throw std::invalid_argument(fmt::format("statics: M0 = {} N·m (need > 0)", M0));
  const double inertial = L.mass_kg * L.centre_accel_m_s2;
  const double scale = std::max({std::abs(L.top_n), std::abs(L.bottom_n), std::abs(inertial), 1e-300});
  if (std::abs(L.top_n - L.bottom_n - inertial) > 1e-9 * scale)
    throw std::invalid_argument(fmt::format("statics: loads out of balance (top {} N − bottom {} N ≠ m_r ẅ = {} N)",
                                            L.top_n, L.bottom_n, inertial));
  const auto c = level3_contact_edges(s);
  const std::size_t n = s.points.size();
  const auto& pa = s.points.front();
  // The mass per radian of material angle (inextensible mean line of length 2πR).
  const double per_rad = L.mass_kg / (2.0 * std::numbers::pi);
  std::vector<double> h(n), g(n, 0.0);
  double fx_sum = 0.0, fy_sum = 0.0, moment_sum = 0.0;  // Σ f, Σ r × f of the loads before k
  double spread = 0.0;                                  // Σ |f|
  for (std::size_t k = 0; k < n; ++k) {
    const auto& p = s.points[k];
    h[k] = p[1] - pa[1];
    if (k > c.top) g[k] -= (c.top_edge[0] - p[0]) * 0.5 * L.top_n;
    if (k >= c.bottom) g[k] += (c.bottom_edge[0] - p[0]) * 0.5 * L.bottom_n;
    // Σ_{q<k} (r_q − p) × f_q = Σ r_q × f_q − p × Σ f_q.
    g[k] += moment_sum - (p[0] * fy_sum - p[1] * fx_sum);
    const double lo = k == 0 ? s.theta[0] : 0.5 * (s.theta[k - 1] + s.theta[k]);
    const double hi = k + 1 == n ? s.theta[k] : 0.5 * (s.theta[k] + s.theta[k + 1]);
    const double m = per_rad * (hi - lo);
    double ax = 0.0, ay = -L.centre_accel_m_s2;  // toward the target is −y
    if (L.uniform_motion) {
      const auto rel = level3_uniform_relative_accel(L.radius_m, s.theta[k], L.phi, L.phi_rate, L.phi_accel);
      ax += rel[0];
      ay += rel[1];
    }
    const double fx = -m * ax, fy = -m * ay;
    fx_sum += fx;
    fy_sum += fy;
    moment_sum += p[0] * fy - p[1] * fx;
    spread += std::hypot(fx, fy);
  }
  return least_peak_field(s, h, g, std::max(std::abs(L.top_n), std::abs(L.bottom_n)) + 2.0 * spread, M0);
}

}  // namespace ringcrush::hinge
