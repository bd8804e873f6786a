// run_dynamic (dynamic_run.hpp): the ChainModel stepped by the chosen driver until arrest or
// the end time, with the whole-chain history, frames, statistics and the energy balance.
//
// Arrest (issue 4 item 7): the impactor has stopped or moves away from the chain (its
// velocity toward the chain ≤ 0) AND the kinetic energy of everything else — the rings and
// plates — is below rest_kinetic_fraction × KE0. The impactor's own rebound energy is
// excluded: an elastic bounce would otherwise keep a stopped chain "moving" until the end
// time. A chain with a free far end keeps translating and so runs to the end time.
#include "fe/dynamics/dynamic_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "fe/dynamics/explicit_driver.hpp"
#include "fe/dynamics/hht_driver.hpp"
#include "fe/time/static_driver.hpp"  // SolveFailure

namespace ringcrush::fe {

namespace {

using Clock = std::chrono::steady_clock;

void validate(const DynamicSolverInput& s) {
  const auto bad = [](const char* name, double value, const char* rule) {
    throw std::invalid_argument(fmt::format("dynamic solver: {} = {} {}", name, value, rule));
  };
  if (!(s.end_time_s > 0) || !std::isfinite(s.end_time_s)) bad("end_time_s", s.end_time_s, "must be > 0 and finite");
  if (!(s.rest_kinetic_fraction > 0 && s.rest_kinetic_fraction < 1))
    bad("rest_kinetic_fraction", s.rest_kinetic_fraction, "must be in (0, 1)");
  if (!(s.energy_error_limit >= 0)) bad("energy_error_limit", s.energy_error_limit, "must be ≥ 0 (0: no limit)");
  if (!(s.output_interval_s > 0)) bad("output_interval_s", s.output_interval_s, "must be > 0");
  if (s.frames < 0) bad("frames", s.frames, "must be ≥ 0");
  // The drivers check their own options (safety, α, steps, tolerances) and name them.
}

// Mass scaling aims at the step the explicit driver takes: the element's own step includes
// the driver's safety (mass_scaling.hpp), which lives in the solver input.
ChainInput with_solver_safety(ChainInput chain, const DynamicSolverInput& solver) {
  if (chain.mass_scaling.active()) chain.mass_scaling.safety = solver.safety;
  return chain;
}

class DynamicRun {
 public:
  DynamicRun(const ChainInput& chain, const DynamicSolverInput& solver, const DynamicCallbacks& cb)
      : solver_(solver), cb_(cb), model_(with_solver_safety(chain, solver)), sym_(model_.symmetry_factor()) {
    const auto& mesh = model_.mesh();
    node_ring_.assign(mesh.nodes.size(), -1);
    for (std::size_t e = 0; e < mesh.elements.size(); ++e)
      for (int n : mesh.elements[e]) node_ring_[static_cast<std::size_t>(n)] = mesh.element_ring[e];
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model_.dofs());
    for (int i = 0; i < static_cast<int>(mesh.ring_centre_y.size()); ++i) h0_.push_back(model_.ring_extent(i, zero));
  }

  DynamicResult run() {
    const auto t0 = Clock::now();
    DynamicResult res;
    if (solver_.scheme == DynamicScheme::Explicit) {
      ExplicitOptions o;
      o.safety = solver_.safety;
      o.stable_step_every = solver_.stable_step_every;
      o.energy_error_limit = solver_.energy_error_limit;
      o.mass_scaling_target_s = model_.input().mass_scaling.target_step_s;
      ExplicitDriver d(model_, o);
      loop(d, res);
      res.statistics.step_limited_by = d.limited_by();
      res.statistics.full_bounds = d.full_bounds();
      res.statistics.contact_bounds = d.contact_bounds();
      res.statistics.bound_iterations = model_.step_bound_statistics().iterations;
      res.statistics.bound_fallbacks = model_.step_bound_statistics().fallbacks;
      res.statistics.steps_below_mass_scaling_target = d.steps_below_target();
    } else {
      HhtOptions o;
      o.alpha = solver_.alpha;
      o.initial_step_s = solver_.initial_step_s;
      o.min_step_s = solver_.min_step_s;
      o.max_step_s = solver_.max_step_s;
      o.haftol_n = solver_.haftol_n;
      o.ptol_n = solver_.ptol_n;
      o.max_iterations = solver_.max_iterations;
      o.energy_error_limit = solver_.energy_error_limit;
      HhtDriver d(model_, o);
      d.keep_attempts = false;
      loop(d, res);
      res.statistics.rejected_steps = d.rejected_steps();
      res.statistics.newton_iterations = d.newton_iterations();
      res.statistics.factorizations = d.factorizations();
      res.statistics.step_limited_by = "half-step residual control (HAFTOL)";
    }
    arrival_statistics(res.statistics);
    res.statistics.contact_penalty_scale = model_.contact_penalty_scale();
    res.mass_scaling = model_.mass_scaling();
    res.mass_scaling.element_mass_kg *= sym_;
    res.mass_scaling.added_mass_kg *= sym_;
    res.mesh = model_.mesh();
    res.max_peeq_per_ring = model_.max_peeq_per_ring();
    res.statistics.wall_time_s = std::chrono::duration<double>(Clock::now() - t0).count();
    return res;
  }

 private:
  std::string describe(int dof) const {
    const auto& mesh = model_.mesh();
    const int node = dof / 2;
    const char axis = dof % 2 == 0 ? 'x' : 'y';
    if (node == mesh.impactor_node) return fmt::format("the impactor (u{})", axis);
    for (std::size_t k = 0; k < mesh.plate_nodes.size(); ++k)
      if (mesh.plate_nodes[k] == node) return fmt::format("plate {} (u{})", k + 1, axis);
    const auto& x = mesh.nodes[static_cast<std::size_t>(node)];
    return fmt::format("node {} of ring {} (X = {:.3f} mm, Y = {:.3f} mm), u{}", node + 1,
                       node_ring_[static_cast<std::size_t>(node)] + 1, x.x() * 1e3, x.y() * 1e3, axis);
  }

  // Where a contact pair was refused (the deepest, for the summary and a failure's diagnosis).
  std::string refused_at(const RefusedArrival& r) const {
    const std::string node = describe(2 * r.node + 1);
    return fmt::format("{} into {}", node.substr(0, node.rfind(", u")),
                       r.self ? std::string("its own inner wall") : fmt::format("ring {}'s outer surface", r.master_ring + 1));
  }
  void arrival_statistics(DynamicStatistics& st) const {
    const ContactArrival& a = model_.contact_arrival();
    const double depth = model_.contact_depth();
    st.refused_contact_arrivals = a.refused();
    st.deepest_refused_arrival = a.deepest_refused().depth / depth;
    st.deepest_refused_arrival_at = a.refused() > 0 ? refused_at(a.deepest_refused()) : std::string();
    st.admitted_contact_arrivals = a.admitted();
    st.deepest_admitted_arrival = a.deepest_admitted() / depth;
  }

  // What the contact was doing when a step failed: the deepest penetration against the
  // penalty's reach (one element through the wall) and the energy absorbed so far. The
  // lock-up failures of the stability matrix (README) sit at a node of a flattened ring that
  // is a large fraction of the reach inside its neighbour (40 % at 50 m/s, ×4 mass, t/D 0.03)
  // — and a ×10 penalty leaves it 29 % inside and fails at the same time, so it is where the
  // closest surface changes, not a soft penalty.
  template <class Driver>
  std::string contact_context(const Driver& d) const {
    const ChainContactForces& c = model_.contact_forces();
    if (c.deepest_node < 0) return "; no contact penetrating at the last evaluation";
    const double depth = model_.contact_depth();
    using S = ChainContactForces::Surface;
    const std::string into = c.deepest_into == S::RingOuter      ? fmt::format("ring {}'s outer surface", c.deepest_ring + 1)
                             : c.deepest_into == S::OwnInnerWall ? std::string("its own inner wall")
                             : c.deepest_into == S::Impactor     ? std::string("the impactor face")
                             : c.deepest_into == S::Target       ? std::string("the target face")
                                                                 : std::string("a plate");
    const std::string node = describe(2 * c.deepest_node + 1);
    std::string s = fmt::format(
        "; deepest contact penetration {:.3g} mm ({:.0f} % of the {:.3g} mm through-wall element depth, the "
        "penalty contact's reach) at {} into {}; plastic dissipation so far {:.4g} J of the impact's {:.4g} J",
        c.max_penetration_m * 1e3, 100 * c.max_penetration_m / depth, depth * 1e3,
        node.substr(0, node.rfind(", u")), into,
        sym_ * d.energy().plastic, sym_ * d.energy().initial_kinetic);
    // The arrival rule (contact_arrival.hpp): deep first sights it kept out so far.
    const ContactArrival& a = model_.contact_arrival();
    if (a.refused() > 0)
      s += fmt::format("; {} contact pair(s) refused at a deep first sight so far, the deepest {:.0f} % of the depth at {}",
                       a.refused(), 100 * a.deepest_refused().depth / depth, refused_at(a.deepest_refused()));
    return s;
  }

  template <class Driver>
  DynamicRow row(const Driver& d) const {
    DynamicRow r;
    const auto& u = d.displacement();
    const int imp = model_.impactor_dof();
    r.time_s = d.time();
    // The impactor comes down from +y: travel and velocity toward the chain are −u_y, −v_y.
    r.impactor_displacement_m = -u(imp);
    r.impactor_velocity_m_s = -d.velocity()(imp);
    r.impactor_force_n = sym_ * model_.contact_forces().impactor_n;
    for (std::size_t i = 0; i < h0_.size(); ++i) r.ring_crush_m.push_back(h0_[i] - model_.ring_extent(static_cast<int>(i), u));
    const EnergyBalance& e = d.energy();
    r.kinetic_j = sym_ * e.kinetic;
    r.elastic_j = sym_ * e.elastic;
    r.plastic_j = sym_ * e.plastic;
    r.contact_j = sym_ * e.contact;
    r.numerical_j = sym_ * e.numerical();
    r.external_work_j = sym_ * e.external_work;
    r.bulk_viscous_j = sym_ * e.viscous_work;
    r.step_s = d.step_size();
    return r;
  }

  DynamicFrame frame(double t, const Eigen::VectorXd& u) const {
    DynamicFrame f;
    f.time_s = t;
    f.displacement = u;
    for (const auto& c : model_.element_fields()) {
      f.mises_pa.push_back(c.mises);
      f.peeq.push_back(c.peeq);
      f.stress_pa.insert(f.stress_pa.end(), {c.sxx, c.syy, c.sxy});
    }
    f.contact_pressure_pa = model_.contact_pressure();
    return f;
  }

  template <class Driver>
  void loop(Driver& d, DynamicResult& res) {
    constexpr bool kExplicit = std::is_same_v<Driver, ExplicitDriver>;
    d.describe_dof = [this](int dof) { return describe(dof); };
    if (cb_.log) d.log = cb_.log;
    const int imp = model_.impactor_dof();
    const double mass_imp = model_.lumped_mass()(imp);
    const double ke0 = d.energy().initial_kinetic;
    res.initial_kinetic_j = sym_ * ke0;
    if (!(ke0 > 0)) throw std::invalid_argument("dynamic run: the initial kinetic energy is zero (impactor velocity 0?)");
    res.history.push_back(row(d));
    const double end = solver_.end_time_s;
    // Frames start 16× denser than `frames` over the end time and thin out by halves (below),
    // so a run that arrests long before the end time still gets `frames`..2·`frames` of them.
    double frame_interval = solver_.frames > 0 ? end / (16.0 * solver_.frames) : INFINITY;
    double next_frame = frame_interval;
    if (solver_.frames > 0) res.frames.push_back(frame(0, d.displacement()));
    double next_output = solver_.output_interval_s;
    std::uint64_t active = model_.contact_forces().active_set;
    auto last_progress = Clock::now();
    res.end_reason = "end_time";
    while (d.time() < end * (1 - 1e-12)) {
      try {
        d.step(end);
      } catch (const SolveFailure& e) {
        // The driver knows only the model it integrates: in a half model its joules are half
        // the chain's, while the context below and every output are the whole chain's.
        const std::string half = sym_ != 1.0 ? fmt::format(" (the driver's energies are the half model's: × {} for the "
                                                           "whole chain, as below and in the outputs)", sym_)
                                             : std::string();
        throw SolveFailure(e.what() + half + contact_context(d));
      }
      if constexpr (kExplicit) {
        // The stable step drops when a contact closes (its penalty stiffness joins ω_max):
        // re-bound when the set of active contacts changed.
        if (model_.contact_forces().active_set != active) {
          active = model_.contact_forces().active_set;
          d.request_contact_bound();
        }
      }
      const auto& u = d.displacement();
      const auto& v = d.velocity();
      // The explicit driver has already refused a non-finite force or kinetic energy (so every
      // free velocity is finite, and u moved by Δt times it): two passes over the state per
      // step saved on its serial path. HHT is checked here.
      if constexpr (!kExplicit)
        if (!u.allFinite() || !v.allFinite())
          throw SolveFailure(fmt::format("dynamic run: non-finite state at t = {:.6g} s", d.time()));
      res.energy_balance_error = std::max(res.energy_balance_error, d.energy().relative_balance_error());
      res.statistics.max_penetration_m =
          std::max(res.statistics.max_penetration_m, model_.contact_forces().max_penetration_m);
      const double t = d.time();
      const double v_toward = -v(imp);
      const double ke_rest = d.energy().kinetic - 0.5 * mass_imp * v(imp) * v(imp);
      const bool arrested = solver_.stop_at_rest && v_toward <= 0 && ke_rest < solver_.rest_kinetic_fraction * ke0;
      if (arrested) res.end_reason = "arrest";
      const bool last = arrested || t >= end * (1 - 1e-12);
      if (t >= next_output || last) {
        res.history.push_back(row(d));
        next_output = t + solver_.output_interval_s;
      }
      if (solver_.frames > 0 && (t >= next_frame || last)) {
        res.frames.push_back(frame(t, u));
        next_frame += frame_interval;
        // Keep the frames spread over the run whatever its length: when twice too many have
        // been taken, drop every other one and double the interval.
        if (static_cast<int>(res.frames.size()) > 2 * solver_.frames) {
          std::vector<DynamicFrame> kept;
          for (std::size_t k = 0; k < res.frames.size(); k += 2) kept.push_back(std::move(res.frames[k]));
          res.frames = std::move(kept);
          frame_interval *= 2;
          next_frame = res.frames.back().time_s + frame_interval;
        }
      }
      if (cb_.progress && (last || Clock::now() - last_progress > std::chrono::milliseconds(100))) {
        last_progress = Clock::now();
        DynamicProgress p;
        p.time_s = t;
        p.end_time_s = end;
        p.step_s = d.step_size();
        p.impactor_velocity_m_s = v_toward;
        p.kinetic_fraction = d.energy().kinetic / ke0;
        p.step = d.steps();
        cb_.progress(p);
      }
      if (arrested) break;
    }
    res.final_displacement = d.displacement();
    res.numerical_dissipation = d.energy().numerical() / ke0;
    auto& st = res.statistics;
    st.steps = d.steps();
    st.contact_time_s = d.contact_time();
    st.min_step_s = d.min_step();
    st.max_step_s = d.max_step();
  }

  DynamicSolverInput solver_;
  DynamicCallbacks cb_;
  ChainModel model_;
  double sym_;
  std::vector<int> node_ring_;
  std::vector<double> h0_;
};

}  // namespace

DynamicResult run_dynamic(const ChainInput& chain, const DynamicSolverInput& solver, const DynamicCallbacks& callbacks) {
  validate(chain);
  validate(solver);
  if (solver.scheme != DynamicScheme::Explicit && chain.mass_scaling.active())
    throw std::invalid_argument(fmt::format(
        "dynamic solver: mass scaling (mass_scaling_dt = {} s, mass_scaling_factor = {}) is for the explicit solver "
        "only: the HHT step is set by its half-step residual control, not the stable step, so added mass would "
        "only change the physics",
        chain.mass_scaling.target_step_s, chain.mass_scaling.factor));
  DynamicRun run(chain, solver, callbacks);
  return run.run();
}

}  // namespace ringcrush::fe
