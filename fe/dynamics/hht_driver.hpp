// Implicit HHT-α integration of M ü + f(u) = 0 (Hilber, Hughes & Taylor; thesis §3.5,
// eqs. 3.5-2a/b) over the DynamicSystem interface, with the half-step residual step control
// of Hibbitt & Karlsson that ABAQUS used for the thesis runs (*DYNAMIC, HAFTOL).
//
// Sign convention (Hilber's): α ∈ [−1/3, 0]; α = 0 is the trapezoidal rule; α < 0 damps the
// high frequencies, spectral radius → (1 + α)/(1 − α) as ωΔt → ∞.
//
//   M a_{n+1} + (1 + α) f(u_{n+1}) − α f(u_n) = 0                                 (3.5-2a)
//   u_{n+1} = u_n + Δt v_n + Δt² ((½ − β) a_n + β a_{n+1})
//   v_{n+1} = v_n + Δt ((1 − γ) a_n + γ a_{n+1}),   β = (1 − α)²/4, γ = ½ − α       (3.5-2b)
//
// Newton on u_{n+1} with the full tangent K_eff = M/(βΔt²) + (1 + α) ∂f/∂u (the system's
// sparse tangent, pattern analysed once per pattern version and factorised per iteration;
// the pattern grows when contact couples new nodes). Convergence: largest residual force
// ≤ PTOL and largest correction ≤ correction_tolerance × largest displacement increment of
// the step (the correction test is waived when the residual is 1000× below PTOL).
//
// Step control (thesis §3.5, steps 1–6). After convergence, the accelerations are taken
// linear over the step, a(τ) = (1 − τ) a_n + τ a_{n+1}; at τ = ½ the Newmark formulas give
//   u_{n+½} = u_n + (Δt/2) v_n + (Δt/2)² ((½ − β) a_n + β a_{n+½}),
// and the equilibrium equation (3.5-2a) written at t + Δt/2, its α-term (which lags one
// step) interpolated linearly over the previous step like the accelerations (the form of
// Hibbitt & Karlsson used by ABAQUS),
//   R_{n+½} = M a_{n+½} + (1 + α) f(u_{n+½}) − (α/2) (f_{n−1} + f_n),
// is evaluated. When (3.5-2a) holds at t_n and t_{n+1} it reduces to
// (1 + α) [f(u_{n+½}) − ½ (f_n + f_{n+1})], the departure of the force at the mid-step state
// from the chord: it vanishes as Δt → 0 and measures how well Δt resolves the response. (With
// the plain α f_n instead, R would tend to −α (f_n − f_{n−1}) ≠ 0 as Δt → 0, and a halving
// could never end.) The half-step evaluation is a trial only: commit(u_{n+1}) re-evaluates the
// trial states at u_{n+1} (dynamic_system.hpp), so the committed path never sees it. With R = max |R_{n+½}|
// over the free dofs:
//   R > HAFTOL                 → reject the step, Δt ← Δt/2, restart from t;
//   HAFTOL/2 < R ≤ HAFTOL      → accept, keep Δt;
//   R ≤ HAFTOL/2 twice running → accept, Δt ← 1.25 Δt (the count restarts).
// A Newton failure (no convergence in max_iterations, a diverging residual, a tangent that
// cannot be factorised, a non-finite value) cuts Δt to Δt/4. Δt stays in [min, max]; a
// step that would go below the minimum throws SolveFailure naming the time, step, the
// residual and the dof where it is largest.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fe/dynamics/dynamic_system.hpp"
#include "fe/dynamics/energy_balance.hpp"

namespace ringcrush::fe {

struct HhtOptions {
  double alpha = -0.105;          // thesis deck: *DYNAMIC, ALPHA = −0.105
  double initial_step_s = 5e-7;
  double min_step_s = 1e-10;
  double max_step_s = 1e-4;
  double haftol_n = 1e4;          // half-step residual tolerance (model force units)
  bool half_step_control = true;  // false: constant Δt (operator verification only)
  double ptol_n = 3.0;            // Newton: largest residual force
  double correction_tolerance = 1e-2;
  int max_iterations = 10;
  double energy_error_limit = 0;  // |balance error| / reference energy (0: no limit)
};

// One attempted step (accepted or not), for diagnosis and the step-control tests.
struct HhtAttempt {
  double time_s = 0;                 // start of the step
  double step_s = 0;
  int iterations = 0;
  double half_step_residual_n = 0;   // R_{n+½} (0 when Newton failed)
  bool accepted = false;
  const char* outcome = "";          // "kept", "grown", "small", "halved", "newton cut-back"
};

class LinearSolver;

class HhtDriver {
 public:
  HhtDriver(DynamicSystem& system, const HhtOptions& options, const Eigen::VectorXd& u0 = {});
  ~HhtDriver();

  // One accepted step (after as many rejections as needed), not passing t_limit.
  void step(double t_limit = std::numeric_limits<double>::infinity());

  double time() const { return t_; }
  double step_size() const { return last_dt_; }   // last accepted step
  double next_step() const { return dt_; }        // nominal step for the next attempt
  long steps() const { return steps_; }
  long rejected_steps() const { return rejected_; }
  long newton_iterations() const { return iterations_; }
  long factorizations() const;
  double min_step() const { return min_dt_; }
  double max_step() const { return max_dt_; }
  double contact_time() const { return contact_time_; }
  const std::vector<HhtAttempt>& attempts() const { return attempts_; }
  bool keep_attempts = true;  // record every attempt in attempts()

  const Eigen::VectorXd& displacement() const { return u_; }
  const Eigen::VectorXd& velocity() const { return v_; }
  const Eigen::VectorXd& acceleration() const { return a_; }
  const SystemEvaluation& evaluation() const { return ev_; }
  const EnergyBalance& energy() const { return energy_; }

  std::function<void(const std::string&)> log;
  std::function<std::string(int)> describe_dof;

 private:
  struct Newton {
    bool converged = false;
    int iterations = 0;
    double residual = 0;
    int residual_dof = -1;
    std::string reason;
  };
  Newton newton(double dt, Eigen::VectorXd& u, Eigen::VectorXd& a);
  double max_free(const Eigen::VectorXd& r, int& at) const;
  void add_mass_to_tangent(double c0);
  std::string where(int dof) const;
  [[noreturn]] void fail(const std::string& what, double dt, double residual, int dof) const;

  DynamicSystem& sys_;
  HhtOptions opt_;
  double beta_ = 0.25, gamma_ = 0.5;
  std::unique_ptr<LinearSolver> solver_;
  std::vector<int> diag_pos_;       // value index of each free diagonal entry
  long diag_version_ = -1;
  Eigen::VectorXd mass_;            // lumped mass (fixed dofs: as given, not used)
  std::vector<int> free_;           // free dofs
  Eigen::VectorXd u_, v_, a_, f_prev_, u_new_, a_new_, v_new_, u_half_, a_half_, r_, du_, rhs_, dx_;
  SystemEvaluation ev_, ev_trial_, ev_half_;
  EnergyBalance energy_;
  double t_ = 0, dt_ = 0, last_dt_ = 0;
  int small_count_ = 0;             // consecutive steps with R ≤ HAFTOL/2
  long steps_ = 0, rejected_ = 0, iterations_ = 0;
  double min_dt_ = 0, max_dt_ = 0, contact_time_ = 0;
  std::vector<HhtAttempt> attempts_;
};

}  // namespace ringcrush::fe
