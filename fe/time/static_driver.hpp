// Static crush driver (thesis §3.4): displacement control of the driven plate, Newton with
// the consistent tangent and a line search, automatic increments.
//
//   - Each increment starts from the committed state; Newton writes trial states only.
//   - Convergence: largest residual force ≤ PTOL and largest correction ≤ correction
//     tolerance × largest displacement increment.
//   - From the 4th iteration on, the residual ratio λ = R(i)/R(i−1) predicts the iteration n
//     of convergence, n = i + ln(PTOL/R(i)) / ln λ; if λ ≥ 1 or n > M the increment is cut
//     to 1/4 (as it is when M iterations are used up or the tangent cannot be factorised).
//   - Two consecutive increments converging in fewer than M/2 iterations grow the next
//     increment by 25 %, up to the maximum.
//   - An increment below the minimum ends the run with a SolveFailure naming the
//     increment, the deflection, the residual norm and the node where it is largest.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fe/fe_input.hpp"
#include "fe/mesh/ring_mesh.hpp"

namespace ringcrush::fe {

class SolveFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One converged increment. Forces and energies are for the WHOLE ring (a half model's
// values doubled).
struct StaticIncrement {
  double deflection_m = 0;     // driven-plate travel
  double force_n = 0;          // force of the driven plate on the ring
  double fixed_force_n = 0;    // force of the fixed plate on the ring
  double self_contact_force_n = 0;
  double elastic_j = 0, plastic_j = 0, contact_j = 0, external_work_j = 0;
  // Plate friction: work dissipated since the start (W_ext = elastic + plastic + contact +
  // friction), Σ |tangential force| on the driven plate, slipping plate contacts (model).
  double friction_j = 0, friction_force_n = 0;
  int slipping_contacts = 0;
  double increment = 0;        // Δ (fraction of the travel)
  int iterations = 0;
  double residual_n = 0;       // largest residual at convergence (model)
  double max_plate_penetration_m = 0, max_self_penetration_m = 0;
  int self_contacts = 0;
};

struct FieldFrame {
  double deflection_m = 0;
  Eigen::VectorXd displacement;     // 2 per node
  std::vector<double> mises_pa;     // per element (Cauchy, point average)
  std::vector<double> peeq;         // per element (point average)
  std::vector<double> contact_pressure_pa;  // per node
};

struct StaticStatistics {
  long increments = 0, cutbacks = 0, newton_iterations = 0, line_searches = 0;
  long residual_evaluations = 0, pattern_analyses = 0, factorizations = 0;
  double wall_time_s = 0, solve_time_s = 0;
};

struct StaticResult {
  RingMesh mesh;
  std::vector<StaticIncrement> history;  // first entry: the unloaded state
  std::vector<FieldFrame> frames;
  StaticStatistics statistics;
  int initial_overlaps = 0;              // nodes penetrating a surface before loading
  double max_initial_overlap_m = 0;
  double max_equilibrium_error = 0;      // max |F_driven − F_fixed| / F_driven over increments
};

// Plate force (whole ring) at deflection `delta`, linear between the converged increments
// that bracket it; the last force beyond the end of the run. The load-curve comparisons
// (mesh convergence, friction, benchmarks) all read the curve through this.
double load_at(const StaticResult& r, double delta);

struct StaticProgress {
  double fraction = 0, deflection_m = 0, force_n = 0, increment = 0;
  long step = 0;
  int iterations = 0;
};

struct StaticCallbacks {
  std::function<void(const StaticProgress&)> progress;
  std::function<void(const std::string&)> log;  // one-off messages (e.g. initial overlaps)
};

StaticResult run_static(const FeInput& input, const StaticCallbacks& callbacks = {});

}  // namespace ringcrush::fe
