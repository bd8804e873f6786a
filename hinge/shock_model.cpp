#include "shock_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ringcrush::hinge {

void ShockInput::validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(what);
  };
  require(impactor_mass_kg > 0, "shock model: impactor mass must be positive");
  require(impactor_velocity_m_s > 0, "shock model: impact velocity must be positive");
  require(plateau_force_n > 0, "shock model: plateau force must be positive");
  require(locking_strain > 0 && locking_strain < 1, "shock model: locking strain must lie in (0, 1)");
  require(mass_per_length_kg_m > 0, "shock model: mass per length must be positive");
  require(pitch_m > 0, "shock model: pitch must be positive");
  require(rings >= 1, "shock model: at least one ring");
}

ShockInput ShockInput::from_ring(const RingLaw& ring, int rings, double impactor_mass_kg,
                                 double impactor_velocity_m_s, ChainFarEnd far_end) {
  ShockInput in;
  in.impactor_mass_kg = impactor_mass_kg;
  in.impactor_velocity_m_s = impactor_velocity_m_s;
  in.plateau_force_n = ring.mean_force_to_lock();
  in.pitch_m = ring.outer_diameter_m;
  in.locking_strain = ring.lock_deflection() / in.pitch_m;
  in.mass_per_length_kg_m = ring.mass_kg / in.pitch_m;
  in.rings = rings;
  in.far_end = far_end;
  return in;
}

double ShockClosedForm::velocity_at(double x) const {
  const double a = eps * Pc / mu;
  const double w = (M * M * V * V + a * M * M) / ((M + mu * x) * (M + mu * x)) - a;
  return std::sqrt(std::max(w, 0.0));
}

ShockClosedForm shock_closed_form(const ShockInput& in) {
  in.validate();
  if (in.far_end != ChainFarEnd::Fixed)
    throw std::invalid_argument("shock closed form: fixed far end only (integrate the free end)");
  const double M = in.impactor_mass_kg, V = in.impactor_velocity_m_s, Pc = in.plateau_force_n,
               eps = in.locking_strain, mu = in.mass_per_length_kg_m;
  ShockClosedForm c{};
  c.M = M, c.V = V, c.Pc = Pc, c.eps = eps, c.mu = mu;
  c.arrest_position_m = M / mu * (std::sqrt(1.0 + mu * V * V / (eps * Pc)) - 1.0);
  c.locked_rings = c.arrest_position_m / in.pitch_m;
  c.arrest_time_s = M * V / Pc;
  c.initial_load_n = Pc + mu * V * V / eps;
  c.characteristic_velocity_m_s = std::sqrt(Pc * eps / mu);
  c.reaches_far_end = c.arrest_position_m > in.rings * in.pitch_m;
  return c;
}

namespace {

// y = [X, v, v_f, u, E_shock]:
//   Ẋ = (v − v_f)/ε_L,  (M + μX) v̇ = −P_c − μ(v − v_f)²/ε_L,
//   μ(N D − X) v̇_f = P_c (free end; v_f ≡ 0 fixed),  u̇ = v,  Ė_shock = ½ μ (v − v_f)² Ẋ.
class ShockOde final : public HybridSystem {
 public:
  explicit ShockOde(const ShockInput& in) : in_(in) {
    length_ = in.rings * in.pitch_m;
    free_ = in.far_end == ChainFarEnd::Free;
  }
  std::size_t size() const override { return 5; }
  std::size_t root_count() const override { return 2; }

  void rhs(double, const double* y, double* f) override {
    const double mu = in_.mass_per_length_kg_m, eps = in_.locking_strain;
    const double rel = y[1] - y[2];
    f[0] = rel / eps;
    f[1] = -(in_.plateau_force_n + mu * rel * rel / eps) / (in_.impactor_mass_kg + mu * y[0]);
    f[2] = free_ ? in_.plateau_force_n / (mu * std::max(length_ - y[0], 1e-12 * length_)) : 0.0;
    f[3] = y[1];
    f[4] = 0.5 * mu * rel * rel * f[0];
  }
  void residual(double t, const double* y, const double* yp, double* r) override {
    rhs(t, y, r);
    for (int i = 0; i < 5; ++i) r[i] = yp[i] - r[i];
  }
  void event_roots(double, const double* y, double* g) override {
    g[0] = (y[1] - y[2]) / in_.impactor_velocity_m_s;  // arrest (falls through 0)
    g[1] = (length_ - y[0]) / in_.pitch_m;             // front at the far end (falls)
  }
  int root_departure(std::size_t, int) const override { return 1; }
  EventAction on_event(double t, std::vector<double>&, const std::vector<int>& fired) override {
    if (fired[0] < 0) {
      arrest = t;
      return EventAction::Stop;
    }
    if (fired[1] < 0) {
      front_at_end = true;
      return EventAction::Stop;
    }
    return EventAction::Continue;
  }
  double arrest = -1.0;
  bool front_at_end = false;

 private:
  ShockInput in_;
  double length_ = 0.0;
  bool free_ = false;
};

}  // namespace

ShockRun integrate_shock(const ShockInput& in, const HybridOptions& options) {
  in.validate();
  ShockOde ode(in);
  ShockRun run;
  const double M = in.impactor_mass_kg, V = in.impactor_velocity_m_s, mu = in.mass_per_length_kg_m;
  const double length = in.rings * in.pitch_m;
  run.initial_kinetic_energy_j = 0.5 * M * V * V;
  std::vector<double> y{0.0, V, 0.0, 0.0, 0.0};
  std::vector<double> f(5);
  run.outcome = run_hybrid(ode, 0.0, y, options, [&](double t, const std::vector<double>& s) {
    ode.rhs(t, s.data(), f.data());
    run.time_s.push_back(t);
    run.front_position_m.push_back(s[0]);
    run.velocity_m_s.push_back(s[1]);
    run.far_velocity_m_s.push_back(s[2]);
    run.impactor_displacement_m.push_back(s[3]);
    run.impactor_force_n.push_back(-M * f[1]);
    run.kinetic_j.push_back(0.5 * (M + mu * s[0]) * s[1] * s[1] +
                            0.5 * mu * std::max(length - s[0], 0.0) * s[2] * s[2]);
    run.plastic_j.push_back(in.plateau_force_n * in.locking_strain * s[0]);
    run.shock_loss_j.push_back(s[4]);
  });
  run.arrest_time_s = ode.arrest;
  run.front_reached_far_end = ode.front_at_end;
  if (ode.front_at_end && in.far_end == ChainFarEnd::Fixed) run.far_end_loss_j = run.kinetic_j.back();
  const double x = y[0];
  for (int i = 0; i < in.rings; ++i) {
    const double compacted = std::clamp(x - i * in.pitch_m, 0.0, in.pitch_m);
    run.final_crush_m.push_back(in.locking_strain * compacted);
  }
  return run;
}

double ShockRun::energy_balance_error() const {
  double worst = 0.0;
  for (std::size_t i = 0; i < time_s.size(); ++i)
    worst = std::max(worst, std::abs(kinetic_j[i] + plastic_j[i] + shock_loss_j[i] - initial_kinetic_energy_j));
  return worst / initial_kinetic_energy_j;
}

DiscreteShock discrete_shock(int rings, double pc, double lock_deflection, double ring_mass,
                             double m0, double v0) {
  if (!(rings >= 1 && pc > 0 && lock_deflection > 0 && ring_mass > 0 && m0 > 0 && v0 > 0))
    throw std::invalid_argument("discrete shock: every input must be positive");
  DiscreteShock r;
  r.crush_m.assign(rings, 0.0);
  r.time_locked_s.assign(rings, -1.0);
  double m = m0, v = v0, t = 0.0;
  for (int k = 0; k < rings && v > 0.0; ++k) {
    const double needed = 2.0 * pc * lock_deflection / m;  // v² lost crushing ring k to lock
    if (v * v > needed) {
      const double v_after = std::sqrt(v * v - needed);
      t += m * (v - v_after) / pc;
      r.crush_m[k] = lock_deflection;
      r.time_locked_s[k] = t;
      r.plastic_j += pc * lock_deflection;
      v = v_after;
      if (k + 1 < rings) {
        // perfectly plastic impact with the next contact mass (half of ring k, half of k+1)
        const double v_new = m * v / (m + ring_mass);
        r.impact_loss_j += 0.5 * m * v * v - 0.5 * (m + ring_mass) * v_new * v_new;
        m += ring_mass;
        v = v_new;
      }
    } else {
      r.crush_m[k] = 0.5 * m * v * v / pc;
      r.plastic_j += pc * r.crush_m[k];
      t += m * v / pc;
      v = 0.0;
    }
  }
  r.arrest_time_s = t;
  r.final_kinetic_j = 0.5 * m * v * v;  // > 0: the locked column reaches the target
  return r;
}

}  // namespace ringcrush::hinge
