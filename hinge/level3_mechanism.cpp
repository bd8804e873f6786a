#include "level3_mechanism.hpp"

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

namespace {

// Redwood-hardened flattening law in terms of the quadrant angle: P0 (1 + kφ)/cos φ.
double flat_load(double p0, double k, double phi) { return p0 * (1.0 + k * phi) / std::cos(phi); }
double flat_load_dphi(double p0, double k, double phi) {
  const double c = std::cos(phi);
  return p0 * (k / c + (1.0 + k * phi) * std::sin(phi) / (c * c));
}

}  // namespace

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

namespace {
std::size_t segment(const std::vector<double>& x, double q) {
  const auto it = std::upper_bound(x.begin(), x.end(), q);
  std::size_t j = it == x.begin() ? 0 : static_cast<std::size_t>(it - x.begin()) - 1;
  return std::min(j, x.size() - 2);
}
}  // namespace

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

namespace {

// Mechanism slots of ring i: kM·i + {uniform, wrap, bottom, E–C–B} (the Level3Mode order) for
// the roots and the mode logic; state 4 + 3i + {uniform, wrap, bottom or E–C–B}: the bottom
// and the E–C–B of a ring never flow together (the switch is one-way), so they share one crush
// state (zero components would change IDA's error norm, and its steps: 151 against 101 at
// 27.7 m/s with a state of their own).
constexpr int kU = 0, kW = 1, kL = 2, kE = 3, kM = 4;

class Level3Chain final : public HybridSystem {
 public:
  Level3Chain(const Level3Input& in, WrapMechanism wrap)
      : in_(in), r_(in.ring), w_(std::move(wrap)), n_(in.rings), m_(kM * in.rings) {
    p0_ = r_.collapse_load();
    d_ = r_.mean_diameter();
    R_ = r_.mean_radius();
    active_.assign(m_, false);
    locked_.assign(m_, false);
    first_.assign(m_, -1.0);
    psi0_.assign(n_, 0.0);
    theta_e_.assign(n_, in.theta_e);
    ecb_.resize(static_cast<std::size_t>(n_));
    ecb_started_.assign(n_, false);
    bottom_frozen_.assign(n_, 0.0);
    wrap_started_.assign(n_, false);
    reinforced_.assign(n_, false);
  }

  std::size_t size() const override { return static_cast<std::size_t>(4 + 3 * n_); }
  // State index of mechanism slot j, and the mechanism's own crush.
  static int state(int j) { return 4 + 3 * (j / kM) + std::min(j % kM, kL); }
  double crush_of(const double* y, int j) const {
    const int i = j / kM;
    switch (j % kM) {
      case kL: return ecb_started_[i] ? bottom_frozen_[i] : y[state(j)];
      case kE: return ecb_started_[i] ? y[state(j)] - bottom_frozen_[i] : 0.0;
      default: return y[state(j)];
    }
  }
  std::size_t root_count() const override { return m_ + 2; }

  // --- mechanism laws -------------------------------------------------------------
  double uniform_phi(const double* y, int i) const {
    return std::asin(std::clamp(crush_of(y, kM * i + kU) / d_, 0.0, 1.0));
  }
  double bottom_psi(const double* y, int i) const {
    return std::asin(std::clamp(std::sin(psi0_[i]) + crush_of(y, kM * i + kL) / R_, 0.0, 1.0));
  }
  double load(const double* y, int j) const {
    const int i = j / kM;
    switch (j % kM) {
      case kU: return flat_load(p0_, r_.hardening_k, uniform_phi(y, i));
      case kW: return w_.load_at(crush_of(y, j));
      case kL: return flat_load(p0_, r_.hardening_k, bottom_psi(y, i));
      default: return ecb_load(y, i);
    }
  }
  // E–C–B of ring i: its table once E has turned, else the onset load on the current bottom
  // state (the candidate held against the bottom mechanism while that one flows).
  double ecb_load(const double* y, int i) const {
    if (ecb_started_[i]) return ecb(i).load_at(crush_of(y, kM * i + kE));
    const double psi = bottom_psi(y, i);
    const auto s = level3_ecb_pose(r_, level3_ecb_points(r_, psi0_[i], psi, ecb_theta_e(i)), psi, 0.0);
    return s.valid ? s.load : std::numeric_limits<double>::infinity();  // no mechanism: never selected
  }
  const EcbMechanism& ecb(int i) const { return ecb_[static_cast<std::size_t>(i)]; }
  // E–C–B replaces a flowing bottom mechanism only when it is cheaper by a margin: at the
  // reinforcement the two loads are equal (E on the flat's edge carries the uniform
  // mechanism's hardening, level3_ecb.hpp), and a tie must not be decided by round-off. The
  // candidate's root fires at a full margin below F, the selection asks for half of it, so
  // the event that finds E–C–B cheaper also selects it.
  static constexpr double kEcbSwitchMargin = 1e-6;
  double switch_margin(int j) const { return j % kM == kE && !ecb_started_[j / kM] ? kEcbSwitchMargin : 0.0; }
  // E of ring i's E–C–B: the chosen θ_E, but not inside the top flat (material angles below
  // the uniform angle φ = psi0_): that flat is pressed flat-on-flat by the ring above over its
  // length, and an E inside it would lift its outer part into that ring at first order in β
  // (1.0 mm at the E–C–B limit for E = 45° on Test 30's φ = 60.6°); from the flat's edge the
  // arc beyond E rises only by ≈ Rβ²/2, like the arc beside B′ dips (level3_ecb.hpp).
  double ecb_theta_e(int i) const { return std::max(theta_e_[i], psi0_[i]); }
  double slope(const double* y, int j) const {
    const int i = j / kM;
    switch (j % kM) {
      case kU: {
        const double phi = uniform_phi(y, i);
        return flat_load_dphi(p0_, r_.hardening_k, phi) / (d_ * std::cos(phi));
      }
      case kW: return w_.slope_at(crush_of(y, j));
      case kL: {
        const double psi = bottom_psi(y, i);
        return flat_load_dphi(p0_, r_.hardening_k, psi) / (R_ * std::cos(psi));
      }
      default: return ecb_started_[i] ? ecb(i).slope_at(crush_of(y, j)) : 0.0;  // flows only from its table
    }
  }
  double energy(const double* y, int j) const {
    const int i = j / kM;
    const double M0 = r_.plastic_moment_nm, k = r_.hardening_k;
    switch (j % kM) {
      case kU: return level3_uniform_energy(r_, crush_of(y, j));
      case kW: return w_.energy_at(crush_of(y, j));
      case kL: {
        const double a = psi0_[i], b = bottom_psi(y, i);
        return 4.0 * M0 * ((b - a) + 0.5 * k * (b * b - a * a));
      }
      default: return ecb_started_[i] ? ecb(i).energy_at(crush_of(y, j)) : 0.0;
    }
  }
  double ring_crush(const double* y, int i) const {
    return y[state(kM * i + kU)] + y[state(kM * i + kW)] + y[state(kM * i + kL)];
  }
  // Remaining travel of mechanism j: its own geometric limit and the ring's lock-up d − t.
  double margin(const double* y, int j) const {
    const int i = j / kM;
    const double ring_left = (d_ - r_.wall_thickness_m) - ring_crush(y, i);
    double own;
    switch (j % kM) {
      case kU: own = ring_left; break;
      case kW: own = w_.capacity() - crush_of(y, j); break;
      case kL: own = (R_ - r_.wall_thickness_m) - R_ * std::sin(bottom_psi(y, i)); break;
      default: own = ecb_started_[i] ? ecb(i).capacity() - crush_of(y, j) : ring_left; break;
    }
    return std::min(own, ring_left);
  }
  bool available(int j) const {
    const int i = j / kM;
    if (locked_[j]) return false;
    switch (j % kM) {
      case kU: return !reinforced_[i];
      case kW: return !in_.plates && i + 1 < n_ && !reinforced_[i] && !wrap_started_[i + 1];
      // Once E has turned the bottom mechanism's DeRuntz–Hodge lower quadrant (its flat's
      // edge travelling on a round arc about a C that stays put) no longer describes the ring:
      // C has moved and B′ is a hinge, so the ring stays in E–C–B (one-way switch).
      case kL: return reinforced_[i] && !ecb_started_[i];
      default: return reinforced_[i] && in_.ring_under == Level3RingUnder::LeastLoad;
    }
  }

  // --- equations ---------------------------------------------------------------------
  void rhs(double, const double* y, double* f) override {
    std::fill(f, f + size(), 0.0);
    const double v = y[1], F = y[2];
    f[0] = v;
    f[1] = -F / in_.impactor_mass_kg;
    f[3] = F * v;
    if (soft_ >= 0) {
      f[state(soft_)] = v;
      f[2] = slope(y, soft_) * v;
      return;
    }
    double inv = 0.0;
    for (int j = 0; j < m_; ++j)
      if (active_[j]) inv += 1.0 / std::max(slope(y, j), 1e-12 * p0_ / d_);
    if (inv <= 0.0) return;
    const double Fdot = v / inv;
    f[2] = Fdot;
    for (int j = 0; j < m_; ++j)
      if (active_[j]) f[state(j)] = Fdot / std::max(slope(y, j), 1e-12 * p0_ / d_);
  }
  void residual(double t, const double* y, const double* yp, double* r) override {
    rhs(t, y, r);
    for (std::size_t k = 0; k < size(); ++k) r[k] = yp[k] - r[k];
  }

  void event_roots(double, const double* y, double* g) override {
    for (int j = 0; j < m_; ++j) {
      if (active_[j]) g[j] = margin(y, j) / d_;
      else if (available(j)) g[j] = std::max((y[2] * (1.0 - switch_margin(j)) - load(y, j)) / p0_, -1e3);  // E–C–B may be +∞
      else g[j] = 1.0;
    }
    // A softening mechanism turns hardening, or a hardening one starts to soften (E–C–B's
    // load peaks before its limit; the wrap softens from its onset, the others never do).
    if (soft_ >= 0) {
      g[m_] = slope(y, soft_) * d_ / p0_;
    } else {
      g[m_] = 1.0;
      for (int j = 0; j < m_; ++j)
        if (active_[j]) g[m_] = std::min(g[m_], slope(y, j) * d_ / p0_);
    }
    g[m_ + 1] = y[1] / in_.impactor_velocity_m_s;
  }

  int root_departure(std::size_t i, int fired) const override {
    if (static_cast<int>(i) < m_ && fired > 0) return -1;  // activated: now a margin (falls)
    return fired;
  }

  EventAction on_event(double t, std::vector<double>& y, const std::vector<int>& fired) override {
    if (fired[m_ + 1] < 0 || y[1] <= 0.0) {
      events_.push_back({t, "impactor_arrested", -1, fmt::format("F = {:.1f} N", y[2])});
      arrested_ = true;
      return EventAction::Stop;
    }
    for (int j = 0; j < m_; ++j)
      if (active_[j] && fired[j] != 0 && margin(y.data(), j) <= 1e-9 * d_) {
        locked_[j] = true;
        events_.push_back({t, "ring_locked", j / kM,
                           fmt::format("{} mechanism at its limit", to_string(static_cast<Level3Mode>(j % kM)))});
      }
    return select(t, y) ? EventAction::Continue : EventAction::Stop;
  }

  // Mode selection: the admissible mechanisms of least load flow (THEORY §4.5).
  // Returns false when every mechanism is exhausted (the chain is locked).
  bool select(double t, std::vector<double>& y) {
    for (int pass = 0; pass < 4; ++pass) {
      std::fill(active_.begin(), active_.end(), false);
      soft_ = -1;
      double pmin = std::numeric_limits<double>::infinity();
      for (int j = 0; j < m_; ++j) {
        if (available(j) && margin(y.data(), j) <= 1e-9 * d_) locked_[j] = true;
        if (available(j)) pmin = std::min(pmin, load(y.data(), j));
      }
      if (!std::isfinite(pmin)) {
        lock_loss_ += 0.5 * in_.impactor_mass_kg * y[1] * y[1];
        events_.push_back({t, "chain_locked", -1, "every mechanism at its limit: impactor stopped"});
        y[1] = 0.0;
        return false;
      }
      // The massless chain carries no more than its least load: F rises to it, or drops to it
      // when a mechanism made available by this event is cheaper (E–C–B of a ring just
      // reinforced); the drop is instantaneous and costs no work (∫ F dδ is continuous).
      if (y[2] < pmin || y[2] > pmin * (1.0 + 1e-6)) y[2] = pmin;
      const double F = y[2];
      for (int j = 0; j < m_; ++j)
        if (available(j) && load(y.data(), j) <= F * (1.0 + 1e-7)) active_[j] = true;
      for (int i = 0; i < n_; ++i) {  // one mechanism per ring underneath: the cheaper
        const int b = kM * i + kL, e = kM * i + kE;
        if (active_[b] && active_[e])
          active_[load(y.data(), e) < load(y.data(), b) * (1.0 - 0.5 * kEcbSwitchMargin) ? b : e] = false;
      }
      for (int j = 0; j < m_ && soft_ < 0; ++j)  // softening: the one nearest the impactor
        if (active_[j] && slope(y.data(), j) < 0.0) soft_ = j;
      if (soft_ >= 0) {
        std::fill(active_.begin(), active_.end(), false);
        active_[soft_] = true;
      }
      for (int i = 0; i < n_; ++i)
        if (active_[kM * i + kE] && !ecb_started_[i]) switch_to_ecb(t, y, i);
      bool changed = false;
      for (int j = 0; j < m_; ++j) {
        if (!active_[j] || first_[j] >= 0) continue;
        first_[j] = t;
        const int i = j / kM;
        events_.push_back({t, "hinge_formed", i,
                           fmt::format("{} mechanism at F = {:.1f} N", to_string(static_cast<Level3Mode>(j % kM)), F)});
        if (j % kM == kW && !wrap_started_[i]) {
          wrap_started_[i] = true;
          reinforced_[i + 1] = true;
          psi0_[i + 1] = uniform_phi(y.data(), i + 1);  // the bottom half's current angle
          if (in_.hinge_e == Level3HingeE::ShearFree) theta_e_[i + 1] = shear_free_e(y.data(), i);
          double pu = load(y.data(), kM * i + kU);
          events_.push_back({t, "mode_selected", i,
                             fmt::format("wrap over ring {} (wrap load {:.1f} N <= uniform {:.1f} N)", i + 2,
                                         load(y.data(), j), pu)});
          changed = true;
        }
      }
      if (!changed) break;
    }
    return true;
  }

  // Ring i turns E: its E–C–B traced from the current bottom state (hinge/level3_ecb.hpp).
  void switch_to_ecb(double t, const std::vector<double>& y, int i) {
    const double psi = bottom_psi(y.data(), i), pb = load(y.data(), kM * i + kL);
    const double pe = load(y.data(), kM * i + kE);
    ecb_[static_cast<std::size_t>(i)] = level3_ecb_mechanism(r_, psi0_[i], psi, ecb_theta_e(i));
    bottom_frozen_[i] = y[static_cast<std::size_t>(state(kM * i + kL))];
    ecb_started_[i] = true;
    events_.push_back({t, "mode_selected", i,
                       fmt::format("E-C-B under ring {} (E at {:.1f} deg, load {:.3f} N < bottom {:.3f} N, psi = {:.3f} deg)", i,
                                   ecb_theta_e(i) * 180.0 / pi, pe, pb, psi * 180.0 / pi)});
  }

  // The shear-free E of ring i + 1 just reinforced by ring i's wrap: the least-load E–C–B
  // hinge beyond the cap held by ring i (level3_travelling_e.hpp), on the drawn shapes.
  double shear_free_e(const double* y, int i) const {
    const double t = r_.wall_thickness_m;
    const auto up = level3_ring_shape(r_, w_, ring_state(y, i), 0.0, 48);
    const auto lo = level3_ring_shape(r_, w_, ring_state(y, i + 1), up.bottom_y - t, 48);
    const double cap = level3_held_cap(up, lo, 1.1 * t);
    const double hard = 1.0 + r_.hardening_k * bottom_psi(y, i + 1);
    return level3_shear_free_e(lo, r_.plastic_moment_nm, cap, hard).theta_e;
  }

  bool finished(double, const double* y) override { return y[1] <= 0.0; }

  // --- results -----------------------------------------------------------------------
  void record(double t, const std::vector<double>& y, Level3History& h) const {
    h.time_s.push_back(t);
    h.impactor_displacement_m.push_back(y[0]);
    h.impactor_velocity_m_s.push_back(y[1]);
    h.force_n.push_back(y[2]);
    h.ring_crush_m.resize(n_);
    for (int i = 0; i < n_; ++i) h.ring_crush_m[i].push_back(ring_crush(y.data(), i));
    h.kinetic_j.push_back(0.5 * in_.impactor_mass_kg * y[1] * y[1]);
    h.plastic_j.push_back(y[3]);
    std::vector<Level3RingResult> states;
    states.reserve(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) states.push_back(ring_state(y.data(), i));
    h.ring_state.push_back(std::move(states));
  }

  // The geometric state of ring i (what level3_ring_shape draws).
  Level3RingResult ring_state(const double* s, int i) const {
    Level3RingResult rr;
    rr.uniform_crush_m = crush_of(s, kM * i + kU);
    rr.wrap_crush_m = crush_of(s, kM * i + kW);
    rr.bottom_crush_m = crush_of(s, kM * i + kL);
    rr.ecb_crush_m = crush_of(s, kM * i + kE);
    rr.ecb_started = ecb_started_[i];
    if (ecb_started_[i]) {
      const auto& m = ecb(i);
      rr.ecb_theta_e = m.theta_e;
      rr.ecb_psi = m.psi;
      rr.ecb_rotation_cb = m.q_at(rr.ecb_crush_m);
      rr.ecb_rotation_e = m.beta_at(rr.ecb_crush_m);
    }
    rr.crush_m = ring_crush(s, i);
    rr.uniform_angle = uniform_phi(s, i);
    rr.bottom_angle = reinforced_[i] ? bottom_psi(s, i) : 0.0;
    rr.wrap_started = wrap_started_[i];
    rr.wrap_theta_f = wrap_started_[i] ? w_.theta_f_at(rr.wrap_crush_m) : 0.0;
    rr.reinforced = reinforced_[i];
    rr.mode = wrap_started_[i]  ? Level3Mode::Wrap
              : ecb_started_[i] ? Level3Mode::Ecb
              : reinforced_[i]  ? Level3Mode::Bottom
                                : Level3Mode::Uniform;
    if (wrap_started_[i]) {  // κ between the table's nodes, linear in the wrap crush
      const std::size_t j = segment(w_.crush, rr.wrap_crush_m);
      const std::size_t k = std::min(j + 1, w_.crush.size() - 1);
      const double span = w_.crush[k] - w_.crush[j];
      const double f = span > 0 ? std::clamp((rr.wrap_crush_m - w_.crush[j]) / span, 0.0, 1.0) : 0.0;
      rr.wrap_curvature = w_.curvature[j] + f * (w_.curvature[k] - w_.curvature[j]);
    }
    return rr;
  }

  void finish(const std::vector<double>& y, Level3Result& res) const {
    const double* s = y.data();
    double total = 0.0;
    for (int i = 0; i < n_; ++i) {
      Level3RingResult rr = ring_state(s, i);
      const double eu = energy(s, kM * i + kU), ew = energy(s, kM * i + kW), el = reinforced_[i] ? energy(s, kM * i + kL) : 0.0;
      const double ee = energy(s, kM * i + kE);
      rr.plastic_work_j = eu + ew + el + ee;
      total += rr.plastic_work_j;
      // Hinge map (material angles from the top apex).
      const double fu = first_[kM * i + kU], fw = first_[kM * i + kW], fl = first_[kM * i + kL];
      const double phi = rr.uniform_angle;
      if (fu >= 0) {
        rr.hinges.push_back({"A", 0.0, fu, 2.0 * phi});
        rr.hinges.push_back({"C", 90.0, fu, 2.0 * phi});
        rr.hinges.push_back({"B", 180.0, fu, 2.0 * phi});
      }
      if (fw >= 0 && w_.travelling()) {  // travelling F: rotations accumulated along the trace
        const std::size_t j = segment(w_.crush, crush_of(s, kM * i + kW));
        const double arc = w_.dissipation[j] / (2.0 * r_.plastic_moment_nm) - std::abs(w_.rotation_c[j]) - w_.rotation_f[j];
        rr.hinges.push_back({"C", 90.0, fw, std::abs(w_.rotation_c[j])});
        rr.hinges.push_back({"F", rr.wrap_theta_f * 180.0 / pi, fw, w_.rotation_f[j]});
        rr.hinges.push_back({"B", 180.0, fw, arc});
      } else if (fw >= 0) {
        const double q = crush_of(s, kM * i + kW);
        const std::size_t j = segment(w_.crush, q);
        const double kappa = w_.curvature[j], alpha = w_.chord_angle[j];
        const double S = R_ * (pi - w_.theta_f);
        rr.hinges.push_back({"C", 90.0, fw, std::abs(alpha - w_.chord_angle.front())});
        rr.hinges.push_back({"F", w_.theta_f * 180.0 / pi, fw,
                             std::abs((kappa - w_.curvature.front()) * S - (alpha - w_.chord_angle.front()))});
        rr.hinges.push_back({"B", 180.0, fw, S * std::abs(kappa - w_.curvature.front())});
      }
      const double fe = first_[kM * i + kE];
      if (fl >= 0 && fe < 0) {  // E reported (not turned): its angle from the statics check
        rr.hinges.push_back({"E", in_.theta_e * 180.0 / pi, -1.0, 0.0});
        rr.hinges.push_back({"C", 90.0, fl, rr.bottom_angle - psi0_[i]});
        rr.hinges.push_back({"B", 180.0, fl, rr.bottom_angle - psi0_[i]});
      }
      if (fe >= 0) {  // E–C–B flowed: E turned by β, C by β + q, B′ (the flat's edge) by q
        if (fl >= 0) {
          rr.hinges.push_back({"C", 90.0, fl, rr.bottom_angle - psi0_[i]});
          rr.hinges.push_back({"B", 180.0, fl, rr.bottom_angle - psi0_[i]});
        }
        rr.hinges.push_back({"E", rr.ecb_theta_e * 180.0 / pi, fe, rr.ecb_rotation_e});
        rr.hinges.push_back({"C", 90.0, fe, rr.ecb_rotation_e + rr.ecb_rotation_cb});
        rr.hinges.push_back({"B'", 180.0 - rr.ecb_psi * 180.0 / pi, fe, rr.ecb_rotation_cb});
      }
      res.rings.push_back(rr);
    }
    res.plastic_work_closed_form_j = total;
    res.lock_loss_j = lock_loss_;
    res.events = events_;
  }

  double psi0(int i) const { return psi0_[i]; }

 private:
  Level3Input in_;
  Level3Ring r_;
  WrapMechanism w_;
  int n_, m_;
  double p0_ = 0, d_ = 0, R_ = 0;
  std::vector<bool> active_, locked_, wrap_started_, reinforced_;
  std::vector<double> first_, psi0_, theta_e_;  // theta_e_: E of the ring's E–C–B (rad)
  std::vector<EcbMechanism> ecb_;                // traced when the ring turns E
  std::vector<bool> ecb_started_;
  std::vector<double> bottom_frozen_;  // the bottom crush when E turned (the shared state's base)
  int soft_ = -1;
  double lock_loss_ = 0.0;
  bool arrested_ = false;
  std::vector<Level3Event> events_;
};

}  // namespace

double Level3Result::energy_balance_error() const {
  double e = 0.0;
  for (std::size_t k = 0; k < history.time_s.size(); ++k) {
    const double lock = k + 1 == history.time_s.size() ? lock_loss_j : 0.0;
    e = std::max(e, std::abs(history.kinetic_j[k] + history.plastic_j[k] + lock - initial_kinetic_energy_j) /
                        initial_kinetic_energy_j);
  }
  return e;
}

Level3Result simulate_level3(const Level3Input& in, const HybridOptions& options, bool record_history) {
  in.validate();
  Level3Result res;
  if (in.theta_f >= 0) res.wrap = level3_wrap_mechanism(in.ring, in.theta_f);
  else if (in.hinge_f == Level3HingeF::ShearFree) res.wrap = level3_travelling_wrap_mechanism(in.ring);
  else res.wrap = level3_wrap_mechanism(in.ring, level3_optimal_theta_f(in.ring));
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
  // Statics check and E on the output states (first and last only without a history): at
  // most ~200 evenly spread, plus every state where a ring changes mechanism (the events,
  // where the loads jump), plus the last — a check costs ≈ 0.2 ms, the runs keep thousands.
  const auto& h = res.history;
  const std::size_t ns = h.time_s.size(), stride = std::max<std::size_t>(1, ns / 200);
  auto changed = [&](std::size_t k) {
    if (k == 0) return true;
    for (std::size_t i = 0; i < h.ring_state[k].size(); ++i) {
      const auto &a = h.ring_state[k][i], &b = h.ring_state[k - 1][i];
      if (a.wrap_started != b.wrap_started || a.reinforced != b.reinforced || a.ecb_started != b.ecb_started) return true;
    }
    return false;
  };
  for (std::size_t k = 0; k < ns; ++k)
    if (k % stride == 0 || k + 1 == ns || changed(k))
      level3_check_states(in, res.wrap, h.ring_state[k], h.force_n[k], h.time_s[k], res.rings);
  for (auto& rr : res.rings)
    for (auto& hg : rr.hinges)
      if (hg.name == "E" && !rr.ecb_started) hg.angle_deg = rr.theta_e * 180.0 / pi;
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
