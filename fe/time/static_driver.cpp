#include "fe/time/static_driver.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "fe/assembly/ring_model.hpp"
#include "fe/solve/linear_solver.hpp"

namespace ringcrush::fe {

namespace {

using Clock = std::chrono::steady_clock;

struct NewtonOutcome {
  bool converged = false;
  int iterations = 0;
  std::string reason;
  double residual = 0;
  int residual_dof = -1;
};

class StaticSolver {
 public:
  // Friction makes the tangent non-symmetric: LU instead of LDLᵀ (linear_solver.hpp).
  StaticSolver(const FeInput& in, const StaticCallbacks& cb)
      : in_(in), cb_(cb), model_(in), solver_(!model_.frictional()) {}

  StaticResult run();

 private:
  // Largest free residual component and its dof.
  double max_residual(const Eigen::VectorXd& r, int& where) const {
    double m = 0;
    where = -1;
    for (int d : model_.system().free_to_dof())
      if (std::abs(r(d)) > m || !std::isfinite(r(d))) {
        m = std::isfinite(r(d)) ? std::abs(r(d)) : INFINITY;
        where = d;
        if (!std::isfinite(m)) break;
      }
    return m;
  }
  void evaluate(const Eigen::VectorXd& u, double y_top, bool tangent, ModelEvaluation& ev) {
    model_.evaluate(u, y_top, tangent, false, ev);
    ++stats_.residual_evaluations;
  }
  NewtonOutcome newton(Eigen::VectorXd& u, const Eigen::VectorXd& u_n, double y_top, ModelEvaluation& ev);
  std::string where(int dof) const;
  void record(double lambda, double dlambda, const NewtonOutcome& o, const ModelEvaluation& ev);
  void frame(const Eigen::VectorXd& u, double deflection, double y_top);

  const FeInput& in_;
  const StaticCallbacks& cb_;
  RingModel model_;
  LinearSolver solver_;
  StaticStatistics stats_;
  StaticResult result_;
  double work_ = 0;  // external work of the driven plate, model
};

std::string StaticSolver::where(int dof) const {
  if (dof < 0) return "nowhere";
  const int node = dof / 2;
  const auto& x = model_.mesh().nodes[node];
  return fmt::format("node {} (X = {:.3f} mm, Y = {:.3f} mm), u{}", node + 1, x.x() * 1e3, x.y() * 1e3,
                     dof % 2 == 0 ? 'x' : 'y');
}

NewtonOutcome StaticSolver::newton(Eigen::VectorXd& u, const Eigen::VectorXd& u_n, double y_top,
                                   ModelEvaluation& ev) {
  const auto& sv = in_.solver;
  const auto& free = model_.system().free_to_dof();
  const int nf = model_.system().free_dofs();
  NewtonOutcome out;
  std::vector<double> hist;
  double last_correction = 0;
  bool have_eval = false;
  Eigen::VectorXd rhs(nf), du_free(nf), du(model_.dofs()), trial(model_.dofs());
  ModelEvaluation ls;
  for (int it = 0;; ++it) {
    if (!have_eval) evaluate(u, y_top, true, ev);
    have_eval = false;
    int at = -1;
    const double rmax = max_residual(ev.residual, at);
    out.residual = rmax;
    out.residual_dof = at;
    out.iterations = it;
    if (!std::isfinite(rmax)) {
      out.reason = "non-finite residual";
      return out;
    }
    const double incr = (u - u_n).cwiseAbs().maxCoeff();
    // The correction test is waived once the residual is 1000× below PTOL: the correction
    // is then at round-off level of the (penalty-stiffened) system, not a sign of drift.
    if (rmax <= sv.force_tolerance_n &&
        (last_correction <= sv.correction_tolerance * std::max(incr, 1e-300) || rmax <= 1e-3 * sv.force_tolerance_n)) {
      out.converged = true;
      return out;
    }
    hist.push_back(rmax);
    if (std::getenv("RINGCRUSH_FE_TRACE"))
      fmt::print(stderr, "    it {} |r| {:.3e} at {} corr {:.3e} incr {:.3e}\n", it, rmax, where(at), last_correction, incr);
    if (it >= sv.max_iterations) {
      out.reason = fmt::format("no convergence in {} iterations", sv.max_iterations);
      return out;
    }
    // Thesis §3.4: from the 4th iteration the residual ratio predicts convergence.
    if (it >= 3 && rmax > sv.force_tolerance_n) {
      const double ratio = rmax / hist[hist.size() - 2];
      if (ratio >= 1.0) {
        out.reason = fmt::format("residual not decreasing (ratio {:.3g})", ratio);
        return out;
      }
      const double predicted = it + std::log(sv.force_tolerance_n / rmax) / std::log(ratio);
      if (predicted > sv.max_iterations) {
        out.reason = fmt::format("convergence predicted at iteration {:.1f} > {}", predicted, sv.max_iterations);
        return out;
      }
    }
    const auto t0 = Clock::now();
    const bool ok = solver_.factorize(model_.system().matrix(), model_.system().pattern_version());
    if (!ok) {
      out.reason = "tangent could not be factorised";
      return out;
    }
    for (int i = 0; i < nf; ++i) rhs(i) = -ev.residual(free[i]);
    du_free = solver_.solve(rhs);
    stats_.solve_time_s += std::chrono::duration<double>(Clock::now() - t0).count();
    stats_.pattern_analyses = solver_.analyses();
    stats_.factorizations = solver_.factorizations();
    ++stats_.newton_iterations;
    if (!du_free.allFinite()) {
      out.reason = "non-finite Newton correction";
      return out;
    }
    du.setZero();
    for (int i = 0; i < nf; ++i) du(free[i]) = du_free(i);
    const double s0 = du.dot(ev.residual);

    // Line search on s(η) = du · r(u + η du): accept η = 1 unless the directional
    // derivative changed sign and grew (overshoot); then regula falsi on [0, 1].
    double eta = 1.0;
    trial = u + du;
    evaluate(trial, y_top, true, ev);
    const double s1 = du.dot(ev.residual);
    if (sv.line_search && s0 < 0 && s1 > 0.8 * std::abs(s0) && std::isfinite(s1)) {
      ++stats_.line_searches;
      double a = 0, sa = s0, b = 1, sb = s1;
      for (int k = 0; k < 6; ++k) {
        eta = a - sa * (b - a) / (sb - sa);
        eta = std::clamp(eta, a + 0.1 * (b - a), b - 0.1 * (b - a));
        trial = u + eta * du;
        evaluate(trial, y_top, false, ls);
        const double s = du.dot(ls.residual);
        if (std::abs(s) <= 0.8 * std::abs(s0)) break;
        if (s < 0) { a = eta; sa = s; } else { b = eta; sb = s; }
      }
      u = trial;
      have_eval = false;
    } else {
      u = trial;
      have_eval = true;
    }
    last_correction = eta * du.cwiseAbs().maxCoeff();
  }
}

void StaticSolver::record(double lambda, double dlambda, const NewtonOutcome& o, const ModelEvaluation& ev) {
  const double f = model_.symmetry_factor();
  StaticIncrement h;
  h.deflection_m = lambda * in_.solver.crush_m;
  h.force_n = f * ev.contact.top_force;
  h.fixed_force_n = f * ev.contact.bottom_force;
  h.self_contact_force_n = f * ev.contact.self_force;
  h.elastic_j = f * ev.elastic_energy;
  h.plastic_j = f * ev.plastic_work;
  h.contact_j = f * ev.contact.energy;
  h.friction_j = f * ev.contact.friction_dissipation;
  h.friction_force_n = f * ev.contact.top_friction_force;
  h.slipping_contacts = ev.contact.slipping_contacts;
  h.external_work_j = f * work_;
  h.increment = dlambda;
  h.iterations = o.iterations;
  h.residual_n = o.residual;
  h.max_plate_penetration_m = ev.contact.max_plate_penetration;
  h.max_self_penetration_m = ev.contact.max_self_penetration;
  h.self_contacts = ev.contact.self_contacts;
  if (h.force_n > 0)
    result_.max_equilibrium_error =
        std::max(result_.max_equilibrium_error, std::abs(h.force_n - h.fixed_force_n) / h.force_n);
  result_.history.push_back(h);
}

void StaticSolver::frame(const Eigen::VectorXd& u, double deflection, double y_top) {
  FieldFrame fr;
  fr.deflection_m = deflection;
  fr.displacement = u;
  for (const auto& f : model_.element_fields()) {
    fr.mises_pa.push_back(f.mises);
    fr.peeq.push_back(f.peeq);
  }
  ModelEvaluation ev;
  model_.evaluate(u, y_top, false, true, ev);
  fr.contact_pressure_pa = ev.contact.node_pressure;
  result_.frames.push_back(std::move(fr));
}

StaticResult StaticSolver::run() {
  const auto start = Clock::now();
  const auto& sv = in_.solver;
  result_.mesh = model_.mesh();
  const int n = model_.dofs();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n), u_n = u;
  ModelEvaluation ev;

  // Initial contact state: nodes touching or overlapping a surface before any load.
  model_.evaluate(u, model_.plate_top_initial(), false, false, ev);
  model_.commit(u);
  result_.initial_overlaps = ev.contact.plate_contacts + ev.contact.self_contacts;
  result_.max_initial_overlap_m = std::max(ev.contact.max_plate_penetration, ev.contact.max_self_penetration);
  if (cb_.log) {
    cb_.log(result_.initial_overlaps == 0
                ? std::string("initial contact check: no overlaps")
                : fmt::format("initial contact check: {} overlapping node(s), deepest {:.3g} m",
                              result_.initial_overlaps, result_.max_initial_overlap_m));
  }
  record(0.0, 0.0, NewtonOutcome{true, 0, "", 0.0, -1}, ev);
  if (sv.frames > 0) frame(u, 0.0, model_.plate_top_initial());

  double lambda = 0, dlambda = sv.initial_increment, prev_force = 0, dlambda_prev = 0;
  Eigen::VectorXd u_prev = u;
  int quick = 0;
  int next_frame = 1;
  while (lambda < 1.0 - 1e-12) {
    if (stats_.increments >= sv.max_increments)
      throw SolveFailure(fmt::format("static crush: {} increments used before reaching the end (deflection {:.4g} mm)",
                                     sv.max_increments, lambda * sv.crush_m * 1e3));
    // Do not leave a sliver of travel for a last tiny increment.
    if (lambda + dlambda > 1.0 - 1e-3 * dlambda) dlambda = 1.0 - lambda;
    NewtonOutcome o;
    double y_top = 0;
    for (;;) {
      y_top = model_.plate_top_initial() - (lambda + dlambda) * sv.crush_m;
      // Predictor: linear extrapolation of the previous increment (ABAQUS's default).
      u = u_n;
      if (dlambda_prev > 0) u += (dlambda / dlambda_prev) * (u_n - u_prev);
      o = newton(u, u_n, y_top, ev);
      if (o.converged) break;
      ++stats_.cutbacks;
      if (std::getenv("RINGCRUSH_FE_TRACE"))
        fmt::print(stderr, "  cut-back at deflection {:.4f} mm (increment {:.3g}): {}\n",
                   (lambda + dlambda) * sv.crush_m * 1e3, dlambda, o.reason);
      const double cut = dlambda / 4.0;
      if (cut < sv.min_increment)
        throw SolveFailure(fmt::format(
            "static crush failed at increment {} (deflection {:.5g} mm, increment {:.3g} of the travel): {}; "
            "residual {:.4g} N largest at {}; the increment would fall below the minimum {:.3g}",
            stats_.increments + 1, (lambda + dlambda) * sv.crush_m * 1e3, dlambda, o.reason, o.residual,
            where(o.residual_dof), sv.min_increment));
      dlambda = cut;
    }
    try {
      model_.commit(u);
    } catch (const std::runtime_error& e) {
      throw SolveFailure(fmt::format("static crush: converged increment {} (deflection {:.5g} mm) leaves {}",
                                     stats_.increments + 1, (lambda + dlambda) * sv.crush_m * 1e3, e.what()));
    }
    u_prev = u_n;
    u_n = u;
    dlambda_prev = dlambda;
    lambda = (1.0 - lambda - dlambda < 1e-12) ? 1.0 : lambda + dlambda;
    ++stats_.increments;
    const double force = ev.contact.top_force;
    work_ += 0.5 * (prev_force + force) * dlambda * sv.crush_m;
    prev_force = force;
    record(lambda, dlambda, o, ev);
    if (sv.frames > 0 && (lambda >= static_cast<double>(next_frame) / sv.frames - 1e-12 || lambda >= 1.0)) {
      frame(u, lambda * sv.crush_m, y_top);
      while (next_frame <= sv.frames && lambda >= static_cast<double>(next_frame) / sv.frames - 1e-12) ++next_frame;
    }
    if (cb_.progress)
      cb_.progress({lambda, lambda * sv.crush_m, model_.symmetry_factor() * force, dlambda, stats_.increments, o.iterations});
    // Thesis §3.4: two quick convergences in a row grow the increment by 25 %.
    quick = (o.iterations <= sv.max_iterations / 2) ? quick + 1 : 0;
    if (quick >= 2) {
      dlambda = std::min(1.25 * dlambda, sv.max_increment);
      quick = 0;
    }
  }
  stats_.wall_time_s = std::chrono::duration<double>(Clock::now() - start).count();
  result_.statistics = stats_;
  return std::move(result_);
}

}  // namespace

StaticResult run_static(const FeInput& input, const StaticCallbacks& callbacks) {
  validate(input);
  StaticSolver solver(input, callbacks);
  return solver.run();
}

double load_at(const StaticResult& r, double delta) {
  const auto& h = r.history;
  if (h.empty()) throw std::invalid_argument("load_at: the run has no increments");
  for (std::size_t i = 1; i < h.size(); ++i)
    if (h[i].deflection_m >= delta) {
      const double t = (delta - h[i - 1].deflection_m) / (h[i].deflection_m - h[i - 1].deflection_m);
      return h[i - 1].force_n + t * (h[i].force_n - h[i - 1].force_n);
    }
  return h.back().force_n;
}

}  // namespace ringcrush::fe
