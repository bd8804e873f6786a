#include "polygon_simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "odeint_integrator.hpp"
#include "polygon_central_difference.hpp"

namespace ringcrush::hinge {

namespace {

class Recorder {
 public:
  Recorder(PolygonChain& chain, const PolygonRunOptions& options, PolygonRunOutput& out)
      : chain_(chain), options_(options), out_(out) {
    const auto s0 = chain.shape(chain.initial_state().data());
    out_.first_yield_time_s.assign(s0.nodes.size(), std::vector<double>(s0.nodes[0].size(), -1.0));
  }

  // Records one sample; returns false once the run should end.
  bool sample(double t, const double* y) {
    auto& h = out_.history;
    const double f = chain_.structure_factor();
    const auto e = chain_.energies(t, y);
    out_.max_penetration_m = std::max(out_.max_penetration_m, chain_.max_penetration_last());
    out_.max_membrane_strain = std::max(out_.max_membrane_strain, chain_.max_membrane_strain_last());
    h.time_s.push_back(t);
    h.impactor_displacement_m.push_back(chain_.impactor_position(t, y));
    const double v = chain_.impactor_velocity(t, y);
    h.impactor_velocity_m_s.push_back(v);
    // energies() evaluated the chain at (t, y): its forces, not two more evaluations (at
    // 1/16 stiff terms the samples' evaluations were ≈ 20 % of the steps' count).
    h.impactor_force_n.push_back(chain_.impactor_force_last());
    h.target_force_n.push_back(chain_.target_force_last());
    h.kinetic_j.push_back(f * e.kinetic);
    h.elastic_j.push_back(f * e.elastic);
    h.contact_j.push_back(f * e.contact);
    h.plastic_j.push_back(f * e.plastic);
    h.contact_damping_j.push_back(f * e.contact_damping);
    h.damping_j.push_back(f * e.damping);
    h.external_j.push_back(f * e.external);
    h.shapes.push_back(chain_.shape(y));
    if (h.time_s.size() == 1) out_.initial_energy_j = h.kinetic_j[0];
    balance_.push_back(h.kinetic_j.back() + h.elastic_j.back() + h.contact_j.back() +
                       h.plastic_j.back() + h.contact_damping_j.back() + h.damping_j.back() -
                       h.external_j.back() - out_.initial_energy_j);
    const auto& shape = h.shapes.back();
    for (std::size_t r = 0; r < shape.plastic_rotation.size(); ++r)
      for (std::size_t k = 0; k < shape.plastic_rotation[r].size(); ++k)
        if (out_.first_yield_time_s[r][k] < 0 &&
            shape.plastic_rotation[r][k] > options_.yield_threshold_rad)
          out_.first_yield_time_s[r][k] = t;
    for (double value : std::vector<double>(y, y + chain_.size()))
      if (!std::isfinite(value))
        throw std::runtime_error("polygon chain: non-finite state at t = " + std::to_string(t));
    if (options_.energy_error_limit > 0 && out_.initial_energy_j > 0) {
      const double error = std::abs(balance_.back()) / out_.initial_energy_j;
      if (!(error <= options_.energy_error_limit)) {
        // The buckets and the previous sample's balance tell a jump within one sample (a step
        // past the stable bound, a contact landing deep) from a steady drift (a term the
        // integrator does not conserve): what to change differs, so the message does not guess.
        const double previous =
            balance_.size() > 1 ? std::abs(balance_[balance_.size() - 2]) / out_.initial_energy_j : 0.0;
        const auto j = [](double value) { return fmt::format("{:.4g}", value); };
        throw PolygonEnergyLimitError(
            fmt::format("polygon chain: energy limit at t = {:.6g} s: |balance| = {:.4g} of the initial "
                        "kinetic energy exceeds energy_error_limit {:.4g} (previous sample, t = {:.6g} s: "
                        "{:.4g}); energies (J): initial kinetic {}, kinetic {}, elastic {}, contact {}, "
                        "plastic {}, contact damping {}, damping {}, external {}",
                        t, error, options_.energy_error_limit,
                        h.time_s.size() > 1 ? h.time_s[h.time_s.size() - 2] : t, previous,
                        j(out_.initial_energy_j), j(h.kinetic_j.back()), j(h.elastic_j.back()),
                        j(h.contact_j.back()), j(h.plastic_j.back()), j(h.contact_damping_j.back()),
                        j(h.damping_j.back()), j(h.external_j.back())),
            t, error);
      }
    }
    if (out_.arrest_time_s < 0 && t > 0 && v <= 0.0) out_.arrest_time_s = t;
    if (options_.stop_at_arrest && out_.arrest_time_s >= 0 &&
        t >= out_.arrest_time_s + options_.settle_time_s)
      return false;
    return t < options_.end_time_s;
  }

  // Largest |KE + elastic + contact + dissipated − external − KE0| over the run, relative to
  // the larger of KE0 and the final external work (driven runs start with KE0 = 0).
  void finish() {
    const double scale =
        std::max({out_.initial_energy_j, std::abs(out_.history.external_j.back()), 1e-300});
    out_.energy_balance_error = 0.0;
    for (double b : balance_) out_.energy_balance_error = std::max(out_.energy_balance_error, std::abs(b) / scale);
  }

 private:
  PolygonChain& chain_;
  const PolygonRunOptions& options_;
  PolygonRunOutput& out_;
  std::vector<double> balance_;
};

}  // namespace

PolygonRunOutput run_polygon_chain(const PolygonChainInput& input, const PolygonRunOptions& options) {
  if (!(options.output_interval_s > 0) || !(options.end_time_s > 0))
    throw std::invalid_argument("run_polygon_chain: output interval and end time must be positive");
  if (!(options.energy_error_limit >= 0))
    throw std::invalid_argument("run_polygon_chain: energy_error_limit must be ≥ 0 (0: none)");
  const auto start = std::chrono::steady_clock::now();
  PolygonChain chain(input);
  PolygonRunOutput out;
  Recorder recorder(chain, options, out);
  std::vector<double> y = chain.initial_state();
  const double dt = options.output_interval_s;
  bool go = recorder.sample(0.0, y.data());

  // IDA and the central difference both advance to each output time and are sampled there.
  std::optional<PolygonStiffnessSpectrum> spectrum;
  if (options.step_breakdown) spectrum.emplace(chain);
  const auto breakdown = [&](double t, const double* state) {
    if (spectrum) out.step_breakdown.emplace_back(t, stable_step_breakdown(chain, *spectrum, t, state));
  };
  breakdown(0.0, y.data());
  const auto march = [&](auto& stepper) {
    for (long k = 1; go; ++k) {
      const double t = stepper.advance(std::min(static_cast<double>(k) * dt, options.end_time_s));
      go = recorder.sample(t, stepper.y().data()) && t < options.end_time_s;
      breakdown(t, stepper.y().data());
    }
    y = stepper.y();
  };
  if (options.integrator == PolygonIntegrator::Ida) {
    PolygonIdaOptions io;
    io.relative_tolerance = options.relative_tolerance;
    io.absolute_scale = options.absolute_scale;
    io.max_step = options.max_step_s;
    io.max_order = options.ida_max_order;
    io.linear_solver = options.ida_linear_solver;
    io.jacobian = options.ida_jacobian;
    io.step_log = options.ida_step_log;
    io.velocity_tolerance_factor = options.velocity_tolerance_factor;
    io.plastic_tolerance_factor = options.plastic_tolerance_factor;
    io.jacobian_reuse_steps = options.ida_jacobian_reuse_steps;
    io.klu_ordering = options.ida_klu_ordering;
    io.pattern_slack = options.ida_pattern_slack;
    PolygonIdaSolver ida(chain, 0.0, y, io);
    march(ida);
    const auto s = ida.statistics();
    out.steps = s.steps;
    out.rejected_steps = s.error_test_failures + s.nonlinear_convergence_failures;
    out.nonlinear_iterations = s.nonlinear_iterations;
    out.rhs_evaluations = s.residual_evaluations;
    out.jacobian_setups = s.preconditioner_setups;
    out.linear_iterations = s.linear_iterations;
    out.symbolic_factorisations = s.symbolic_factorisations;
    out.jacobian_formations = s.jacobian_formations;
    out.pattern_rebuilds = s.pattern_rebuilds;
    out.pattern_remaps = s.pattern_remaps;
  } else if (options.integrator == PolygonIntegrator::CentralDifference) {
    CentralDifferenceOptions co;
    co.safety = options.central_difference_safety;
    co.max_step_s = options.max_step_s;
    co.implicit_ring_dampers = options.central_difference_implicit_dampers;
    co.power_iteration_bound = options.central_difference_power_bound;
    co.contact_landing_depth = options.central_difference_landing_depth_m;
    co.fixed_step_s = options.central_difference_fixed_step_s;
    co.implicit_membrane = options.central_difference_implicit_membrane;
    PolygonCentralDifference cd(chain, 0.0, y, co);
    march(cd);
    const auto& s = cd.statistics();
    out.steps = s.steps;
    out.rhs_evaluations = s.rhs_evaluations;
    out.min_step_s = s.min_step_s;
    out.max_step_s = s.max_step_s;
    out.min_flow_relaxation_s = s.min_flow_relaxation_s;
    out.power_refreshes = s.power_refreshes;
    out.landing_steps = s.landing_steps;
    out.membrane_correction_work_j = chain.structure_factor() * s.membrane_correction_work_j;
    out.hinge_damper_plastic_work_j = chain.structure_factor() * s.hinge_damper_plastic_work_j;
  } else {
    OdeintOptions oo;
    oo.relative_tolerance = options.relative_tolerance;
    oo.absolute_tolerance = options.absolute_scale * chain.mean_radius();
    oo.initial_step = 1e-8;
    oo.max_step = options.max_step_s;
    long next = 1;
    OdeintStatistics stats;
    std::vector<double> ys;
    integrate_dense(
        chain, y, 0.0, options.end_time_s, oo,
        [&](double, double t, const std::function<void(double, std::vector<double>&)>& at) {
          while (go && static_cast<double>(next) * dt <= t + 1e-15) {
            const double ts = static_cast<double>(next) * dt;
            at(ts, ys);
            go = recorder.sample(ts, ys.data());
            ++next;
          }
          return go;
        },
        &stats);
    out.steps = stats.steps;
    out.rhs_evaluations = stats.rhs_evaluations;
    if (go && out.history.time_s.back() < options.end_time_s)
      recorder.sample(options.end_time_s, y.data());
  }
  recorder.finish();
  out.end_time_s = out.history.time_s.back();
  out.final_state = y;
  out.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace ringcrush::hinge
