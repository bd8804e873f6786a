#include "level3_travelling_e.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "level3_statics.hpp"

namespace ringcrush::hinge {

using std::numbers::pi;

namespace {

constexpr double kThetaEHi = 89.0 * pi / 180.0;  // E at C degenerates (E–C of zero length)

// Point of the polyline at material angle θ (linear between the shape's points).
std::array<double, 2> at_angle(const Level3Shape& s, double th) {
  const auto it = std::upper_bound(s.theta.begin(), s.theta.end(), th);
  std::size_t k = it == s.theta.begin() ? 0 : static_cast<std::size_t>(it - s.theta.begin()) - 1;
  k = std::min(k, s.theta.size() - 2);
  const double f = std::clamp((th - s.theta[k]) / (s.theta[k + 1] - s.theta[k]), 0.0, 1.0);
  return {s.points[k][0] + f * (s.points[k + 1][0] - s.points[k][0]),
          s.points[k][1] + f * (s.points[k + 1][1] - s.points[k][1])};
}

EHingeRate rate_on(const Level3Shape& s, const std::array<double, 2>& c, const std::array<double, 2>& b, double M0,
                   double th, double hard) {
  const auto e = at_angle(s, th);
  EHingeRate r;
  r.theta_e = th;
  // ω₁ = 1; closure ẋ_B′ = 0 gives ω₂ (B′ below C, so y_B′ − y_C ≠ 0 on any ring not flat).
  const double dy = b[1] - c[1];
  if (std::abs(dy) < 1e-12 * (std::abs(c[0]) + 1e-300)) {
    r.load = std::numeric_limits<double>::infinity();
    return r;
  }
  const double w1 = 1.0, w2 = -(c[1] - e[1]) / dy;
  const double crush = w1 * (c[0] - e[0]) + w2 * (b[0] - c[0]);
  const double sgn = crush >= 0.0 ? 1.0 : -1.0;  // the crushing sense
  r.omega_ec = sgn * w1;
  r.omega_cb = sgn * w2;
  const double diss = 2.0 * M0 * (std::abs(w1) + hard * (std::abs(w2 - w1) + std::abs(w2)));
  r.load = std::abs(crush) > 0.0 ? diss / std::abs(crush) : std::numeric_limits<double>::infinity();
  if (r.load < std::numeric_limits<double>::infinity()) {
    r.omega_ec /= std::abs(crush);
    r.omega_cb /= std::abs(crush);
  }
  return r;
}

double distance_to_polyline(const std::array<double, 2>& p, const Level3Shape& s) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < s.points.size(); ++k) {
    const auto& a = s.points[k];
    const auto& b = s.points[k + 1];
    const double ux = b[0] - a[0], uy = b[1] - a[1], l2 = ux * ux + uy * uy;
    const double t = l2 > 0 ? std::clamp(((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(p[0] - a[0] - t * ux, p[1] - a[1] - t * uy));
  }
  return best;
}

void check_hardening(double h) {
  if (!(h >= 1.0) || !std::isfinite(h))
    throw std::invalid_argument(fmt::format("E hinge: hardening factor = {} (need finite, >= 1)", h));
}

}  // namespace

EHingeRate level3_e_rate(const Level3Shape& s, double M0, double theta_e, double hard) {
  check_hardening(hard);
  const auto contacts = level3_contact_edges(s);  // validates the shape
  if (!(M0 > 0.0)) throw std::invalid_argument(fmt::format("E hinge: M0 = {} N·m (need > 0)", M0));
  if (!(theta_e >= 0.0 && theta_e <= kThetaEHi))
    throw std::invalid_argument(fmt::format("E hinge: theta_E = {} rad outside [0°, 89°]", theta_e));
  return rate_on(s, at_angle(s, 0.5 * pi), s.points[contacts.bottom], M0, theta_e, hard);
}

EHingeRate level3_shear_free_e(const Level3Shape& s, double M0, double theta_cap, double hard) {
  check_hardening(hard);
  if (!(theta_cap >= 0.0 && theta_cap <= kThetaEHi))
    throw std::invalid_argument(fmt::format("E hinge: held cap edge = {} rad outside [0°, 89°]", theta_cap));
  const auto contacts = level3_contact_edges(s);
  if (!(M0 > 0.0)) throw std::invalid_argument(fmt::format("E hinge: M0 = {} N·m (need > 0)", M0));
  const auto c = at_angle(s, 0.5 * pi);
  const auto b = s.points[contacts.bottom];
  auto f = [&](double th) { return rate_on(s, c, b, M0, th, hard); };
  // A scan (the load is piecewise smooth on the polyline) brackets the least load; golden
  // section refines it between the neighbouring scan points.
  constexpr int scan = 48;
  const double h = (kThetaEHi - theta_cap) / scan;
  EHingeRate best = f(theta_cap);
  int kb = 0;
  for (int k = 1; k <= scan; ++k) {
    const EHingeRate r = f(theta_cap + k * h);
    if (r.load < best.load) { best = r; kb = k; }
  }
  if (h <= 0.0) return best;
  double a = theta_cap + std::max(kb - 1, 0) * h, bb = theta_cap + std::min(kb + 1, scan) * h;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = bb - g * (bb - a), x2 = a + g * (bb - a);
  EHingeRate r1 = f(x1), r2 = f(x2);
  for (int it = 0; it < 40; ++it) {
    if (r1.load < r2.load) { bb = x2; x2 = x1; r2 = r1; x1 = bb - g * (bb - a); r1 = f(x1); }
    else { a = x1; x1 = x2; r1 = r2; x2 = a + g * (bb - a); r2 = f(x2); }
  }
  const EHingeRate& in = r1.load < r2.load ? r1 : r2;
  return in.load < best.load ? in : best;
}

double level3_held_cap(const Level3Shape& upper, const Level3Shape& lower, double gap) {
  level3_contact_edges(upper);  // validates both shapes
  level3_contact_edges(lower);
  if (!(gap > 0.0)) throw std::invalid_argument(fmt::format("held cap: gap = {} m (need > 0)", gap));
  double cap = 0.0;
  for (std::size_t k = 0; k < lower.points.size() && lower.theta[k] <= kThetaEHi; ++k) {
    if (distance_to_polyline(lower.points[k], upper) > gap) break;
    cap = lower.theta[k];
  }
  return cap;
}

}  // namespace ringcrush::hinge
