#include "owens_symonds.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ringcrush::hinge {
namespace {

constexpr double pi = std::numbers::pi;

// Mechanism mode of the right half ring for unit α̇ with A fixed (y up, θ from A at the top):
// arc A–E turns about A at ω₁ = 1, arc E–B at ω₂ = −(1 − cos θ_E)/(1 + cos θ_E) about E, so
// that B stays on the symmetry axis.
struct Mode {
  double te, w2;
  explicit Mode(double theta_e) : te(theta_e), w2(-(1 - std::cos(theta_e)) / (1 + std::cos(theta_e))) {}
  // velocity of the material point at θ (unit α̇), radius R
  void w(double theta, double r, double& wx, double& wy) const {
    // ẑ × (p − p_A) with p = R(sin θ, cos θ), p_A = (0, R)
    if (theta <= te) {
      wx = -(r * std::cos(theta) - r);
      wy = r * std::sin(theta);
      return;
    }
    const double ex = -(r * std::cos(te) - r), ey = r * std::sin(te);
    wx = ex - w2 * (r * std::cos(theta) - r * std::cos(te));
    wy = ey + w2 * (r * std::sin(theta) - r * std::sin(te));
  }
  double dissipation_per_rate(double m0) const {  // whole ring: A, E and E′, B
    return 2.0 * m0 * (1.0 + std::abs(w2 - 1.0) + std::abs(w2));
  }
};

template <typename F>
double simpson(F f, double lo, double hi, int n = 400) {
  const double h = (hi - lo) / n;
  double s = f(lo) + f(hi);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(lo + i * h);
  return s * h / 3.0;
}

struct MassTerms {
  double yy, ya, aa;  // whole ring
};

MassTerms mass_terms(const FreeRing& ring, const Mode& mode) {
  const double r = ring.mean_radius_m, mu = ring.mass_kg / (2 * pi * r);
  auto wy = [&](double th) { double a, b; mode.w(th, r, a, b); return b; };
  auto w2 = [&](double th) { double a, b; mode.w(th, r, a, b); return a * a + b * b; };
  const double iy = simpson(wy, 0, mode.te) + simpson(wy, mode.te, pi);
  const double ia = simpson(w2, 0, mode.te) + simpson(w2, mode.te, pi);
  return {ring.mass_kg, 2 * mu * r * iy, 2 * mu * r * ia};
}

// Accelerations (Ÿ, α̈) with Y along F (downward) and the mechanism opening (α̇ > 0).
void accelerations(const FreeRing& ring, const Mode& mode, double force, double& ay, double& aa) {
  const auto m = mass_terms(ring, mode);
  // y up in the mode; with Y downward the coupling changes sign.
  const double myy = m.yy, mya = -m.ya, maa = m.aa;
  const double qy = force, qa = -mode.dissipation_per_rate(ring.plastic_moment_nm);
  const double det = myy * maa - mya * mya;
  ay = (maa * qy - mya * qa) / det;
  aa = (myy * qa - mya * qy) / det;
}

// Shear at θ_E⁻ of arc A–E from its equilibrium with the d'Alembert loads of the
// accelerating mechanism: M(θ) = M_A + (p_A − p_θ) × (H, −F/2) + ∫₀^θ (p(ψ) − p(θ)) × f(ψ) R dψ,
// f = −μ a(ψ); H from M(θ_E) = +M0 with M_A = −M0. Returns dM/dθ at θ_E.
double shear_at_hinge(const FreeRing& ring, double theta_e, double force) {
  const Mode mode(theta_e);
  double ay, aa;
  accelerations(ring, mode, force, ay, aa);
  const double r = ring.mean_radius_m, mu = ring.mass_kg / (2 * pi * r), m0 = ring.plastic_moment_nm;
  // acceleration (y up) of the point at ψ: −Ÿ ŷ + α̈ w(ψ)
  auto load = [&](double psi, double& fx, double& fy) {
    double wx, wy;
    mode.w(psi, r, wx, wy);
    fx = -mu * (aa * wx);
    fy = -mu * (-ay + aa * wy);
  };
  auto moment_without_h = [&](double th) {
    const double px = r * std::sin(th), py = r * std::cos(th);
    // (p_A − p_θ) × (0, −F/2)
    double m = (0.0 - px) * (-0.5 * force);
    m += simpson([&](double psi) {
      double fx, fy;
      load(psi, fx, fy);
      const double dx = r * std::sin(psi) - px, dy = r * std::cos(psi) - py;
      return (dx * fy - dy * fx) * r;
    }, 0.0, th, 200);
    return -m0 + m;
  };
  // H term: (p_A − p_θ) × (H, 0) = −(R − R cos θ) H
  const double lever_e = -(r - r * std::cos(theta_e));
  const double h = (m0 - moment_without_h(theta_e)) / lever_e;
  auto moment = [&](double th) { return moment_without_h(th) - (r - r * std::cos(th)) * h; };
  const double d = 1e-5;
  return (moment(theta_e + d) - moment(theta_e - d)) / (2 * d);
}

}  // namespace

double onset_moment_ratio(const FreeRing& ring, double theta) {
  const auto on = owens_symonds_onset(ring);
  return -1.0 + on.force_n * ring.mean_radius_m / (2 * ring.plastic_moment_nm) * (1 - theta / pi) * std::sin(theta);
}

OnsetThreshold owens_symonds_onset(const FreeRing& ring) {
  if (!(ring.mean_radius_m > 0 && ring.plastic_moment_nm > 0 && ring.mass_kg > 0))
    throw std::invalid_argument("Owens-Symonds: radius, plastic moment and mass must be positive");
  // tan θ = π − θ  ⇔  g(θ) = sin θ − (π − θ) cos θ = 0 on (0, π/2): Newton from 1.
  double th = 1.0;
  for (int i = 0; i < 50; ++i) {
    const double g = std::sin(th) - (pi - th) * std::cos(th);
    const double dg = std::cos(th) + std::cos(th) + (pi - th) * std::sin(th);
    const double step = g / dg;
    th -= step;
    if (std::abs(step) < 1e-15) break;
  }
  OnsetThreshold o{};
  o.hinge_angle_rad = th;
  o.force_n = 4 * ring.plastic_moment_nm / (ring.mean_radius_m * (1 - th / pi) * std::sin(th));
  double worst = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = pi * i / 2000.0;
    worst = std::max(worst, std::abs(-1.0 + o.force_n * ring.mean_radius_m / (2 * ring.plastic_moment_nm) *
                                                (1 - t / pi) * std::sin(t)));
  }
  o.max_moment_ratio = worst;
  return o;
}

double mechanism_collapse_force(const FreeRing& ring, double theta) {
  const Mode mode(theta);
  const auto m = mass_terms(ring, mode);
  return mode.dissipation_per_rate(ring.plastic_moment_nm) * ring.mass_kg / std::abs(m.ya);
}

MechanismState owens_symonds_mechanism(const FreeRing& ring, double force) {
  const auto on = owens_symonds_onset(ring);
  if (!(force > on.force_n)) throw std::invalid_argument("Owens-Symonds: force below the onset threshold");
  // Bisection of the shear at the hinge over θ_E ∈ (0.2, 2.5), bracketing the static root.
  double lo = 0.2, hi = 2.5;
  double glo = shear_at_hinge(ring, lo, force);
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double gm = shear_at_hinge(ring, mid, force);
    if ((gm > 0) == (glo > 0)) {
      lo = mid;
      glo = gm;
    } else {
      hi = mid;
    }
  }
  MechanismState s{};
  s.hinge_angle_rad = 0.5 * (lo + hi);
  accelerations(ring, Mode(s.hinge_angle_rad), force, s.translation_acceleration, s.rotation_acceleration);
  return s;
}

namespace {

// y = [Y, Ẏ, α, α̇, W_ext]: the mechanism with a fixed hinge while α̇ > 0.
class PulseOde final : public HybridSystem {
 public:
  PulseOde(const FreeRing& ring, double theta_e, double force, double duration)
      : ring_(ring), mode_(theta_e), force_(force), duration_(duration) {
    const auto m = mass_terms(ring, mode_);
    myy_ = m.yy, mya_ = -m.ya, maa_ = m.aa;
    d1_ = mode_.dissipation_per_rate(ring.plastic_moment_nm);
  }
  std::size_t size() const override { return 5; }
  std::size_t root_count() const override { return 2; }
  double force(double t) const { return t < duration_ ? force_ : 0.0; }
  void rhs(double t, const double* y, double* f) override {
    const double qy = force(t), qa = deforming_ ? -d1_ : 0.0;
    double ay, aa;
    if (deforming_) {
      const double det = myy_ * maa_ - mya_ * mya_;
      ay = (maa_ * qy - mya_ * qa) / det;
      aa = (myy_ * qa - mya_ * qy) / det;
    } else {
      ay = qy / myy_;
      aa = 0.0;
    }
    f[0] = y[1];
    f[1] = ay;
    f[2] = y[3];
    f[3] = aa;
    f[4] = qy * y[1];
  }
  void residual(double t, const double* y, const double* yp, double* r) override {
    rhs(t, y, r);
    for (int i = 0; i < 5; ++i) r[i] = yp[i] - r[i];
  }
  void event_roots(double t, const double* y, double* g) override {
    g[0] = deforming_ ? y[3] : 1.0;   // mechanism stops
    g[1] = (duration_ - t) / duration_;  // end of the pulse
  }
  int root_departure(std::size_t, int) const override { return 1; }
  EventAction on_event(double t, std::vector<double>& y, const std::vector<int>& fired) override {
    if (fired[0] < 0 && deforming_) {
      deforming_ = false;
      y[3] = 0.0;
      stop_time = t;
      return EventAction::Stop;  // rigid-body motion from here on
    }
    return EventAction::Continue;
  }
  double dissipation() const { return d1_; }
  double kinetic(const double* y) const {
    return 0.5 * (myy_ * y[1] * y[1] + 2 * mya_ * y[1] * y[3] + maa_ * y[3] * y[3]);
  }
  double stop_time = -1.0;

 private:
  FreeRing ring_;
  Mode mode_;
  double force_, duration_;
  double myy_ = 0, mya_ = 0, maa_ = 0, d1_ = 0;
  bool deforming_ = true;
};

}  // namespace

PulseResponse owens_symonds_pulse(const FreeRing& ring, double force, double duration,
                                  const HybridOptions& options) {
  if (!(duration > 0)) throw std::invalid_argument("Owens-Symonds: pulse duration must be positive");
  const auto mech = owens_symonds_mechanism(ring, force);
  PulseOde ode(ring, mech.hinge_angle_rad, force, duration);
  PulseResponse r;
  r.hinge_angle_rad = mech.hinge_angle_rad;
  std::vector<double> y{0, 0, 0, 0, 0};
  // Start a hair into the motion so that α̇ > 0 (the mechanism opens from rest).
  std::vector<double> f(5);
  auto o = options;
  r.outcome = run_hybrid(ode, 0.0, y, o, [&](double t, const std::vector<double>& s) {
    r.time_s.push_back(t);
    r.rotation_rad.push_back(s[2]);
    r.rotation_rate.push_back(s[3]);
  });
  r.deformation_end_s = ode.stop_time;
  r.final_rotation_rad = y[2];
  r.external_work_j = y[4];
  r.kinetic_j = ode.kinetic(y.data());
  r.plastic_j = ode.dissipation() * y[2];
  r.final_velocity_m_s = y[1];
  return r;
}

double PulseResponse::energy_balance_error() const {
  return std::abs(external_work_j - kinetic_j - plastic_j) / external_work_j;
}

}  // namespace ringcrush::hinge
