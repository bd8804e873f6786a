#include "level3_ecb.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ringcrush::hinge {

using std::numbers::pi;

namespace {

void check_state(double phi, double psi, double theta_e) {
  if (!(phi >= 0.0 && phi < 0.5 * pi)) throw std::invalid_argument(fmt::format("E-C-B: phi = {} rad outside [0, 90°)", phi));
  if (!(psi >= 0.0 && psi < 0.5 * pi)) throw std::invalid_argument(fmt::format("E-C-B: psi = {} rad outside [0, 90°)", psi));
  if (!(theta_e >= 0.0 && theta_e <= 89.0 * pi / 180.0))
    throw std::invalid_argument(fmt::format("E-C-B: theta_E = {} rad outside [0°, 89°]", theta_e));
}

// G(a, Δ): the work of a Redwood hinge M0 (1 + kθ) turning from a to a + Δ, per M0.
double hinge_work(double k, double a, double d) { return d + k * (a * d + 0.5 * d * d); }

// Index of the table interval holding x (clamped to the table).
std::size_t interval(const std::vector<double>& x, double v) {
  const auto it = std::upper_bound(x.begin(), x.end(), v);
  const std::size_t j = it == x.begin() ? 0 : static_cast<std::size_t>(it - x.begin()) - 1;
  return std::min(j, x.size() - 2);
}

double linear(const std::vector<double>& x, const std::vector<double>& y, double v) {
  const std::size_t j = interval(x, v);
  const double f = std::clamp((v - x[j]) / (x[j + 1] - x[j]), 0.0, 1.0);
  return y[j] + f * (y[j + 1] - y[j]);
}

}  // namespace

EcbPoints level3_ecb_points(const Level3Ring& r, double phi, double psi, double theta_e) {
  check_state(phi, psi, theta_e);
  const double R = r.mean_radius();
  EcbPoints p;
  // E on the DeRuntz–Hodge upper quadrant at φ (level3_ring_shape): on the top flat below φ,
  // on the quadrant rotated by φ about C beyond it.
  if (theta_e < phi) {
    p.e = {(R - R * std::cos(phi)) * theta_e / phi, R - R * std::sin(phi)};
  } else {
    const double x = R * std::sin(theta_e) - R, y = R * std::cos(theta_e);
    p.e = {R + x * std::cos(phi) - y * std::sin(phi), x * std::sin(phi) + y * std::cos(phi)};
  }
  p.c = {R, 0.0};
  p.b = {R - R * std::cos(psi), R * std::sin(psi) - R};  // the bottom flat's edge
  p.e_start = theta_e <= phi ? phi : 0.0;
  return p;
}

EcbPose level3_ecb_pose(const Level3Ring& r, const EcbPoints& p, double psi, double q) {
  EcbPose s;
  s.q = q;
  const double wx = p.c[0] - p.e[0], wy = p.c[1] - p.e[1];   // E → C₀
  const double v0x = p.b[0] - p.c[0], v0y = p.b[1] - p.c[1];  // C₀ → B′₀
  const double cq = std::cos(q), sq = std::sin(q);
  const double vx = v0x * cq + v0y * sq, vy = -v0x * sq + v0y * cq;  // Rot(−q)
  // x_C(β) = x_E + ρ cos(β + ζ) must put B′ back on x = x_B′₀; β + ζ ≤ 0 (C below E).
  const double rho = std::hypot(wx, wy), zeta = std::atan2(wy, wx);
  const double a = (p.b[0] - vx - p.e[0]) / rho;
  if (!(a <= 1.0) || !(vy < 0.0)) return s;
  s.beta = -zeta - std::acos(std::max(a, -1.0));
  const double cb = std::cos(s.beta), sb = std::sin(s.beta);
  const double cx = p.e[0] + wx * cb - wy * sb, cy = p.e[1] + wx * sb + wy * cb;
  if (!(cy < p.e[1])) return s;
  s.crush = cy + vy - p.b[1];
  s.dbeta = vy / (cy - p.e[1]);
  s.dcrush = (cx - p.e[0]) * s.dbeta - vx;
  if (!(s.dcrush > 0.0) || !(s.beta >= -1e-12)) return s;
  const double k = r.hardening_k, M0 = r.plastic_moment_nm, b = std::max(s.beta, 0.0);
  s.dissipation = 2.0 * M0 * (hinge_work(k, p.e_start, b) + hinge_work(k, psi, b + q) + hinge_work(k, psi, q));
  const double rate = 2.0 * M0 * ((1.0 + k * (p.e_start + b)) * s.dbeta + (1.0 + k * (psi + b + q)) * (s.dbeta + 1.0) + (1.0 + k * (psi + q)));
  s.load = rate / s.dcrush;
  s.valid = std::isfinite(s.load);
  return s;
}

double level3_ecb_onset_load(const Level3Ring& r, double phi, double psi, double theta_e) {
  const auto s = level3_ecb_pose(r, level3_ecb_points(r, phi, psi, theta_e), psi, 0.0);
  if (!s.valid) throw std::invalid_argument(fmt::format("E-C-B: no mechanism at phi = {}, psi = {}, theta_E = {}", phi, psi, theta_e));
  return s.load;
}

EcbMechanism level3_ecb_mechanism(const Level3Ring& r, double phi, double psi, double theta_e, int samples) {
  r.validate();
  if (samples < 8) throw std::invalid_argument(fmt::format("E-C-B table: samples = {} (need >= 8)", samples));
  EcbMechanism m;
  m.phi = phi;
  m.psi = psi;
  m.theta_e = theta_e;
  m.points = level3_ecb_points(r, phi, psi, theta_e);
  auto valid = [&](double q) { return level3_ecb_pose(r, m.points, psi, q).valid; };
  if (!valid(0.0)) throw std::invalid_argument(fmt::format("E-C-B: no mechanism at phi = {}, psi = {}, theta_E = {}", phi, psi, theta_e));
  // The geometric limit: a scan brackets the first invalid q, bisection refines it.
  const int scan = 400;
  const double dq = 0.5 * pi / scan;
  double lo = 0.0, hi = 0.5 * pi;
  for (int i = 1; i <= scan; ++i)
    if (valid(i * dq)) lo = i * dq;
    else { hi = i * dq; break; }
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (lo + hi);
    (valid(mid) ? lo : hi) = mid;
  }
  // Close to the limit dδ/dq → 0 or β′ → ∞ and the load runs away; the last 1 % of the
  // rotation is left out (the chain's lock there is the mechanism's geometric limit).
  const double qmax = 0.99 * lo;
  for (int j = 0; j <= samples; ++j) {
    const double q = qmax * j / samples;
    const auto s = level3_ecb_pose(r, m.points, psi, q);
    m.q.push_back(q);
    m.beta.push_back(s.beta);
    m.crush.push_back(s.crush);
    m.dissipation.push_back(s.dissipation);
    m.load.push_back(s.load);
  }
  m.crush.front() = 0.0;  // exact at q = 0 (the closure leaves a round-off residual)
  m.beta.front() = 0.0;
  return m;
}

double level3_ecb_draw(const Level3Ring& r, const Level3RingResult& s, std::vector<std::array<double, 2>>& pts,
                       std::vector<double>& th) {
  const double psi = s.ecb_psi;
  const EcbPoints p = level3_ecb_points(r, s.uniform_angle, psi, s.ecb_theta_e);
  EcbPose pose = level3_ecb_pose(r, p, psi, s.ecb_rotation_cb);
  if (!pose.valid) pose.beta = s.ecb_rotation_e;  // at the limit itself: β of the table
  const double cb = std::cos(pose.beta), sb = std::sin(pose.beta);
  const double cq = std::cos(s.ecb_rotation_cb), sq = std::sin(s.ecb_rotation_cb);
  const std::array<double, 2> c{p.e[0] + (p.c[0] - p.e[0]) * cb - (p.c[1] - p.e[1]) * sb,
                                p.e[1] + (p.c[0] - p.e[0]) * sb + (p.c[1] - p.e[1]) * cb};
  const double yb = c[1] + (p.b[0] - p.c[0]) * -sq + (p.b[1] - p.c[1]) * cq;  // B′ (x stays)
  // E as a point of its own, so the corner is drawn where the hinge is.
  const auto at = std::lower_bound(th.begin(), th.end(), s.ecb_theta_e);
  if (at != th.end() && std::abs(*at - s.ecb_theta_e) > 1e-12 && at != th.begin()) {
    const auto k = at - th.begin();
    pts.insert(pts.begin() + k, p.e);
    th.insert(at, s.ecb_theta_e);
  }
  const double half = 0.5 * pi, flat_from = pi - psi;  // material angle where the flat B′–B starts
  for (std::size_t k = 0; k < pts.size(); ++k) {
    auto& q = pts[k];
    if (th[k] <= s.ecb_theta_e) continue;
    if (th[k] <= half) {  // E–C: turned by β about E
      const double x = q[0] - p.e[0], y = q[1] - p.e[1];
      q = {p.e[0] + x * cb - y * sb, p.e[1] + x * sb + y * cb};
    } else if (th[k] < flat_from - 1e-12 || psi <= 0.0) {  // C–B′: turned by −q, carried with C
      const double x = q[0] - p.c[0], y = q[1] - p.c[1];
      q = {c[0] + x * cq + y * sq, c[1] - x * sq + y * cq};
    } else {
      q[1] = yb;  // the flat, raised with B′
    }
  }
  return yb;
}

double EcbMechanism::load_at(double d) const { return level3_table_load(crush, load, d); }
double EcbMechanism::slope_at(double d) const { return level3_table_slope(crush, load, d); }
double EcbMechanism::energy_at(double d) const { return level3_table_energy(crush, load, d); }
double EcbMechanism::q_at(double d) const { return linear(crush, q, d); }
double EcbMechanism::beta_at(double d) const { return linear(crush, beta, d); }

}  // namespace ringcrush::hinge
