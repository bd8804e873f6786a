#include "level3_mechanism.hpp"

#include "level3_chain.hpp"

#include <fmt/format.h>

#include "level3_ecb.hpp"
#include "level3_statics.hpp"
#include "level3_travelling_e.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace ringcrush::hinge {

using level3_detail::flat_load;
using level3_detail::kE;
using level3_detail::kL;
using level3_detail::kM;
using level3_detail::kU;
using level3_detail::kW;
using level3_detail::Level3Chain;
using level3_detail::segment;
using std::numbers::pi;

void Level3Ring::validate() const {
  if (!(outer_diameter_m > 0) || !(wall_thickness_m > 0) || !(wall_thickness_m < 0.25 * outer_diameter_m))
    throw std::invalid_argument("Level3Ring: need D > 0 and 0 < t < D/4");
  if (!(plastic_moment_nm > 0)) throw std::invalid_argument("Level3Ring: M0 must be > 0");
  if (!(hardening_k >= 0)) throw std::invalid_argument("Level3Ring: hardening k must be >= 0");
}

void Level3Input::validate() const {
  ring.validate();
  if (rings < 1) throw std::invalid_argument("Level3Input: rings must be >= 1");
  if (!(impactor_mass_kg > 0) || !(impactor_velocity_m_s > 0))
    throw std::invalid_argument("Level3Input: impactor mass and velocity must be > 0");
  if (theta_f >= 0 && !(theta_f > 0.5 * pi && theta_f < pi))
    throw std::invalid_argument("Level3Input: theta_F must lie in (90°, 180°)");
  if (theta_f >= 0 && hinge_f == Level3HingeF::ShearFree)
    throw std::invalid_argument(fmt::format("Level3Input: theta_F = {} rad fixes F, but hinge_f = shear_free makes it travel", theta_f));
  if (!(ring_mass_kg >= 0) || (inertia && !(ring_mass_kg > 0)))
    throw std::invalid_argument(fmt::format("Level3Input: ring_mass_kg = {} kg; ring inertia needs a ring mass > 0", ring_mass_kg));
  if (!(theta_e >= 0 && theta_e <= 89.0 * pi / 180.0))
    throw std::invalid_argument(fmt::format("Level3Input: theta_E = {} rad outside [0°, 89°]", theta_e));
}

std::string to_string(Level3RingUnder u) {
  switch (u) {
    case Level3RingUnder::Bottom: return "bottom";
    case Level3RingUnder::LeastLoad: return "least_load";
  }
  return "?";
}

std::string to_string(Level3HingeE h) {
  switch (h) {
    case Level3HingeE::Fixed: return "fixed";
    case Level3HingeE::ShearFree: return "shear_free";
  }
  return "?";
}

std::string to_string(Level3Mode m) {
  switch (m) {
    case Level3Mode::Uniform: return "uniform";
    case Level3Mode::Wrap: return "wrap";
    case Level3Mode::Bottom: return "bottom";
    case Level3Mode::Ecb: return "ecb";
  }
  return "?";
}


double level3_uniform_load(const Level3Ring& r, double crush) {
  const double phi = std::asin(std::clamp(crush / r.mean_diameter(), 0.0, 1.0));
  return flat_load(r.collapse_load(), r.hardening_k, phi);
}

double level3_uniform_energy(const Level3Ring& r, double crush) {
  const double phi = std::asin(std::clamp(crush / r.mean_diameter(), 0.0, 1.0));
  return 8.0 * r.plastic_moment_nm * (phi + 0.5 * r.hardening_k * phi * phi);
}

// ---------------------------------------------------------------------------------------
// Wrap mechanism geometry (ring frame: centre at the origin, C = (R, 0), B on x = 0).

namespace {

struct WrapState {
  double fx, fy;   // F relative to B
  double alpha;    // angle of the chord F→C
  double yb;       // y of B
};

WrapState wrap_state(double R, double L, double S, double kappa) {
  WrapState w;
  const double ks = kappa * S;
  if (std::abs(kappa) * S < 1e-8) {
    w.fx = S;
    w.fy = 0.5 * kappa * S * S;
  } else {
    w.fx = std::sin(ks) / kappa;
    w.fy = (1.0 - std::cos(ks)) / kappa;
  }
  const double ca = std::clamp((R - w.fx) / L, -1.0, 1.0);
  w.alpha = std::acos(ca);
  w.yb = -L * std::sin(w.alpha) - w.fy;
  return w;
}

}  // namespace

WrapMechanism level3_wrap_mechanism(const Level3Ring& r, double theta_f, int samples) {
  r.validate();
  if (!(theta_f > 0.5 * pi && theta_f < pi)) throw std::invalid_argument("wrap: theta_F in (90°, 180°)");
  const double R = r.mean_radius(), t = r.wall_thickness_m, M0 = r.plastic_moment_nm;
  const double S = R * (pi - theta_f);                     // arc F–B
  const double L = 2.0 * R * std::sin(0.5 * (theta_f - 0.5 * pi));  // chord C–F
  const double k0 = 1.0 / R, k1 = -1.0 / (R + t);
  WrapMechanism w;
  w.theta_f = theta_f;
  const WrapState s0 = wrap_state(R, L, S, k0);
  double D = 0.0;
  WrapState prev = s0;
  double kprev = k0;
  for (int j = 0; j <= samples; ++j) {
    const double kappa = k0 + (k1 - k0) * j / samples;
    const WrapState s = wrap_state(R, L, S, kappa);
    if (j > 0) {
      const double da = s.alpha - prev.alpha, dk = kappa - kprev;
      D += M0 * (2.0 * std::abs(da) + 2.0 * std::abs(dk * S - da) + 2.0 * S * std::abs(dk));
    }
    w.curvature.push_back(kappa);
    w.crush.push_back(s.yb - s0.yb);
    w.dissipation.push_back(D);
    w.chord_angle.push_back(s.alpha);
    prev = s;
    kprev = kappa;
  }
  // The mechanism ends where B stops rising (its geometric limit) if before full inversion.
  for (std::size_t j = 1; j < w.crush.size(); ++j)
    if (!(w.crush[j] > w.crush[j - 1])) {
      if (j < 3) throw std::runtime_error(fmt::format("wrap mechanism: no travel at theta_F = {}", theta_f));
      w.curvature.resize(j);
      w.crush.resize(j);
      w.dissipation.resize(j);
      w.chord_angle.resize(j);
      break;
    }
  const std::size_t n = w.crush.size();
  w.load.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t a = j == 0 ? 0 : j - 1, b = j + 1 == n ? j : j + 1;
    w.load[j] = (w.dissipation[b] - w.dissipation[a]) / (w.crush[b] - w.crush[a]);
  }
  return w;
}


// Cubic Hermite interpolation of the load in δ (C¹, so the integrators see no kinks at the
// table nodes), node slopes by finite differences; the work is its exact integral.
namespace {
struct Hermite {
  std::size_t j;
  double h, tau, p0, p1, m0, m1;
};
Hermite hermite(const std::vector<double>& crush, const std::vector<double>& load, double q) {
  const std::size_t n = crush.size();
  Hermite c;
  c.j = segment(crush, q);
  const std::size_t j = c.j;
  c.h = crush[j + 1] - crush[j];
  c.tau = std::clamp((q - crush[j]) / c.h, 0.0, 1.0);
  auto slope = [&](std::size_t i) {
    const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 >= n ? n - 1 : i + 1;
    return (load[b] - load[a]) / (crush[b] - crush[a]);
  };
  c.p0 = load[j];
  c.p1 = load[j + 1];
  c.m0 = slope(j) * c.h;
  c.m1 = slope(j + 1) * c.h;
  return c;
}
double hermite_integral(const Hermite& c, double t) {
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
  return c.h * (c.p0 * (t - t3 + 0.5 * t4) + c.m0 * (0.5 * t2 - 2.0 * t3 / 3.0 + 0.25 * t4) +
                c.p1 * (t3 - 0.5 * t4) + c.m1 * (-t3 / 3.0 + 0.25 * t4));
}
}  // namespace

double level3_table_load(const std::vector<double>& crush, const std::vector<double>& load, double q) {
  const Hermite c = hermite(crush, load, q);
  const double t = c.tau, t2 = t * t, t3 = t2 * t;
  return c.p0 * (2 * t3 - 3 * t2 + 1) + c.m0 * (t3 - 2 * t2 + t) + c.p1 * (-2 * t3 + 3 * t2) + c.m1 * (t3 - t2);
}
double level3_table_slope(const std::vector<double>& crush, const std::vector<double>& load, double q) {
  const Hermite c = hermite(crush, load, q);
  const double t = c.tau, t2 = t * t;
  return (c.p0 * (6 * t2 - 6 * t) + c.m0 * (3 * t2 - 4 * t + 1) + c.p1 * (-6 * t2 + 6 * t) + c.m1 * (3 * t2 - 2 * t)) / c.h;
}
double level3_table_energy(const std::vector<double>& crush, const std::vector<double>& load, double q) {
  const Hermite c = hermite(crush, load, q);
  double e = 0.0;
  for (std::size_t i = 0; i < c.j; ++i) e += hermite_integral(hermite(crush, load, crush[i]), 1.0);
  return e + hermite_integral(c, c.tau);
}

double WrapMechanism::load_at(double q) const { return level3_table_load(crush, load, q); }
double WrapMechanism::slope_at(double q) const { return level3_table_slope(crush, load, q); }
double WrapMechanism::energy_at(double q) const { return level3_table_energy(crush, load, q); }

double level3_optimal_theta_f(const Level3Ring& r) {
  // Onset load of the fixed-F wrap: the table's loads are differences of its work, so the
  // first node's is the average over the first step (biased by half a step of the steeply
  // falling load, which moved this minimum by 1.4°); Richardson's extrapolation of the
  // one-, two- and four-step differences (errors a·kh + b·(kh)²) removes it to O(h³).
  auto onset = [&](double th) {
    const auto w = level3_wrap_mechanism(r, th, 40);
    auto diff = [&](std::size_t k) { return (w.dissipation[k] - w.dissipation[0]) / (w.crush[k] - w.crush[0]); };
    return (8.0 * diff(1) - 6.0 * diff(2) + diff(4)) / 3.0;
  };
  double a = 100.0 * pi / 180.0, b = 170.0 * pi / 180.0;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = onset(c), fd = onset(d);
  for (int it = 0; it < 40; ++it) {
    if (fc < fd) { b = d; d = c; fd = fc; c = b - g * (b - a); fc = onset(c); }
    else { a = c; c = d; fc = fd; d = a + g * (b - a); fd = onset(d); }
  }
  return 0.5 * (a + b);
}

// ---------------------------------------------------------------------------------------
// The chain.


double Level3Result::energy_balance_error() const {
  double e = 0.0;
  for (std::size_t k = 0; k < history.time_s.size(); ++k) {
    const double lock = k + 1 == history.time_s.size() ? lock_loss_j : 0.0;
    const double impacts = k < history.impact_loss_j.size() ? history.impact_loss_j[k] : 0.0;
    e = std::max(e, std::abs(history.kinetic_j[k] + history.plastic_j[k] + lock + impacts - initial_kinetic_energy_j) /
                        initial_kinetic_energy_j);
  }
  return e;
}

WrapMechanism level3_detail::level3_wrap_for(const Level3Input& in) {
  if (in.theta_f >= 0) return level3_wrap_mechanism(in.ring, in.theta_f);
  if (in.hinge_f == Level3HingeF::ShearFree) return level3_travelling_wrap_mechanism(in.ring);
  return level3_wrap_mechanism(in.ring, level3_optimal_theta_f(in.ring));
}

Level3Result simulate_level3(const Level3Input& in, const HybridOptions& options, bool record_history) {
  in.validate();
  if (in.inertia) return simulate_level3_inertial(in, options, record_history);
  Level3Result res;
  res.wrap = level3_detail::level3_wrap_for(in);
  res.theta_f = res.wrap.theta_f;
  Level3Chain chain(in, res.wrap);
  res.initial_kinetic_energy_j = 0.5 * in.impactor_mass_kg * in.impactor_velocity_m_s * in.impactor_velocity_m_s;
  std::vector<double> y(chain.size(), 0.0);
  y[1] = in.impactor_velocity_m_s;
  bool running = chain.select(0.0, y);
  std::vector<double> last;
  double t_last = 0.0;
  if (running) {
    res.outcome = run_hybrid(chain, 0.0, y, options, [&](double t, const std::vector<double>& s) {
      if (record_history || res.history.time_s.empty()) chain.record(t, s, res.history);
      last = s;
      t_last = t;
    });
  }
  if (!running) chain.record(0.0, y, res.history);
  else if (!record_history && !last.empty()) chain.record(t_last, last, res.history);
  chain.finish(y, res);
  level3_check_history(in, res);
  return res;
}

// ---------------------------------------------------------------------------------------
// Shapes (for the wrap measures and the polylines).

Level3Shape level3_ring_shape(const Level3Ring& r, const WrapMechanism& w, const Level3RingResult& s,
                              double top_y, int n) {
  const double R = r.mean_radius();
  const double phi = s.uniform_angle;
  Level3Shape sh;
  auto rot = [](double a, double x, double y) { return std::array<double, 2>{x * std::cos(a) - y * std::sin(a), x * std::sin(a) + y * std::cos(a)}; };
  // Upper quadrant: DeRuntz–Hodge, rotated by φ about C, flattened above its tangent point.
  const double xc = R - R * std::cos(phi), ytop = R - R * std::sin(phi);
  std::vector<std::array<double, 2>> pts;
  std::vector<double> th;
  for (int k = 0; k <= n; ++k) {
    const double t = 0.5 * pi * k / n;
    if (t < phi) {
      pts.push_back({xc * t / std::max(phi, 1e-12), ytop});
    } else {
      const auto q = rot(phi, R * std::sin(t) - R, R * std::cos(t));
      pts.push_back({R + q[0], q[1]});
    }
    th.push_back(t);
  }
  double yb;
  if (s.wrap_started && w.travelling()) {
    // The traced lower quadrant between the two table nodes bracketing κ_B, integrated from
    // C = (R, 0); the midpoint-rule closure residual (O((h/R)²) R) is taken out linearly in u
    // so that B is drawn on the axis.
    const auto& k = w.curvature;  // decreasing
    std::size_t j = 0;
    while (j + 2 < k.size() && k[j + 1] > s.wrap_curvature) ++j;
    const double f = std::clamp((k[j] - s.wrap_curvature) / (k[j] - k[j + 1]), 0.0, 1.0);
    const auto& b0 = w.tangent[j];
    const auto& b1 = w.tangent[j + 1];
    const std::size_t cells = b0.size();
    const auto& e = w.cell_edges;
    std::vector<std::array<double, 2>> q(cells + 1, {R, 0.0});
    for (std::size_t c = 0; c < cells; ++c) {
      const double b = b0[c] + f * (b1[c] - b0[c]), h = e[c + 1] - e[c];
      q[c + 1] = {q[c][0] + h * std::cos(b), q[c][1] + h * std::sin(b)};
    }
    const double miss = q[cells][0];
    const int m = 2 * n;
    for (int p = 1; p <= m; ++p) {  // 2n points at material angles 90° … 180°
      const double u = 0.5 * pi * R * p / m;
      const std::size_t c = std::min(segment(e, u), cells - 1);
      const double fr = std::clamp((u - e[c]) / (e[c + 1] - e[c]), 0.0, 1.0);
      double x = q[c][0] + fr * (q[c + 1][0] - q[c][0]), y = q[c][1] + fr * (q[c + 1][1] - q[c][1]);
      x -= miss * u / (0.5 * pi * R);
      pts.push_back({x, y});
      th.push_back(0.5 * pi + u / R);
    }
    pts.back()[0] = 0.0;
    yb = q[cells][1];
    const double lift = R * std::sin(phi);  // the uniform crush done before the wrap (below)
    for (std::size_t k2 = 0; k2 < pts.size(); ++k2)
      if (th[k2] > 0.5 * pi) pts[k2][1] += lift * (th[k2] - 0.5 * pi) / (0.5 * pi);
    yb += lift;
  } else if (s.wrap_started) {
    const double tf = w.theta_f, S = R * (pi - tf);
    const double L = 2.0 * R * std::sin(0.5 * (tf - 0.5 * pi));
    const WrapState st = wrap_state(R, L, S, s.wrap_curvature);
    const WrapState s0 = wrap_state(R, L, S, 1.0 / R);
    const double da = st.alpha - s0.alpha;
    for (int k = 1; k <= n; ++k) {  // arc C–F turned rigidly about C
      const double t = 0.5 * pi + (tf - 0.5 * pi) * k / n;
      const auto q = rot(da, R * std::sin(t) - R, R * std::cos(t));
      pts.push_back({R + q[0], q[1]});
      th.push_back(t);
    }
    yb = st.yb;
    const double kap = s.wrap_curvature;
    for (int k = n - 1; k >= 0; --k) {  // arc F–B of curvature κ, B on the axis
      const double u = S * k / n;
      double x, y;
      if (std::abs(kap) * u < 1e-8) { x = u; y = 0.5 * kap * u * u; }
      else { x = std::sin(kap * u) / kap; y = (1.0 - std::cos(kap * u)) / kap; }
      pts.push_back({x, yb + y});
      th.push_back(pi - u / R);
    }
    // The chain superposes the wrap on the uniform crush done before it (δ = δ_u + δ_w), so
    // B also carries the uniform lower quadrant's rise R sin φ. The wrap table is built on
    // the undeformed arc and has no place for it: the drawing lifts the lower arc by a
    // vertical shear, 0 at C growing linearly in θ to R sin φ at B, which keeps the
    // loading-point approach equal to δ (a drawing device, not a mechanism).
    const double lift = R * std::sin(phi);
    for (std::size_t k = 0; k < pts.size(); ++k)
      if (th[k] > 0.5 * pi) pts[k][1] += lift * (th[k] - 0.5 * pi) / (0.5 * pi);
    yb += lift;
  } else {
    const double a = s.reinforced ? s.bottom_angle : phi;
    const double xcb = R - R * std::cos(a);
    yb = -(R - R * std::sin(a));
    for (int k = 1; k <= 2 * n; ++k) {
      const double t = 0.5 * pi + 0.5 * pi * k / (2 * n);
      const double m = pi - t;  // angle from B
      if (m < a) {
        pts.push_back({xcb * m / std::max(a, 1e-12), yb});
      } else {
        const auto q = rot(-a, R * std::sin(t) - R, R * std::cos(t));
        pts.push_back({R + q[0], q[1]});
      }
      th.push_back(t);
    }
    if (s.ecb_started) yb = level3_ecb_draw(r, s, pts, th);  // E–C–B on the bottom state
  }
  const double off = top_y - ytop;
  for (auto& p : pts) p[1] += off;
  sh.points = std::move(pts);
  sh.theta = std::move(th);
  sh.bottom_y = yb + off;
  return sh;
}

}  // namespace ringcrush::hinge
