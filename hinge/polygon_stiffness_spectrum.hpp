// The highest natural frequency of the polygon chain's undamped stiffness, against which the
// central-difference step bound (PolygonChain::stable_step, a Gershgorin bound) is judged
// (README "Level 2 central-difference step", issue 7).
//
// λ_max of K v = λ M v over the free position unknowns — node x, y (the axis nodes' x are held
// on the symmetry plane) and the free bodies' y —, K = −∂φ/∂x from the analytic Jacobian
// (PolygonChain::stiffness_triplets: membrane incl. its geometric term, hinges, ties, and the
// touching contacts with the Hunt–Crossley slope k(1 + χṗ) the Gershgorin rows use; the
// Kelvin–Voigt dampers left out, as the implicit-damper step leaves them out), M the node and
// body masses. Estimated by power iteration on A = M^{-1/2} K M^{-1/2}, as the FE's
// fe/dynamics/assembled_eigenvalue.hpp does: |A x| of the unit iterate x is ≤ the largest |λ|
// (A symmetric: the analytic contact, hinge and bar blocks are), so the estimate approaches
// from BELOW — it is an estimate, not a bound. The iterate is kept between calls (warm start).
#pragma once

#include <cstddef>
#include <vector>

#include "polygon_chain.hpp"

namespace ringcrush::hinge {

class PolygonStiffnessSpectrum {
 public:
  explicit PolygonStiffnessSpectrum(PolygonChain& chain);

  struct Estimate {
    double lambda = 0.0;  // θ = |A x| ≤ λ_max (1/s²)
    int iterations = 0;
    bool converged = false;  // |θ_k − θ_{k−1}| ≤ tolerance · θ_k
  };
  // Assembles A at (t, y) and iterates from the last iterate, at least min_iterations and at
  // most max_iterations. Throws std::invalid_argument on bad limits or tolerance.
  Estimate estimate(double t, const double* y, int min_iterations, int max_iterations, double tolerance);

  // The free position unknowns (state rows) and A of the last estimate as (i, j, a_ij) entries
  // over them, duplicates to be summed: for tests against a dense eigen-solve.
  const std::vector<std::size_t>& position_rows() const { return position_; }
  struct Entry {
    int i, j;
    double a;
  };
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  PolygonChain& chain_;
  std::vector<std::size_t> position_;        // dof → state row of its position
  std::vector<double> inv_sqrt_mass_;        // dof → M^{-1/2}
  // State row → dof where the row is that dof's force (velocity) row, resp. its position row;
  // −1 elsewhere: the filter of the Jacobian's triplets is two look-ups (h63).
  std::vector<int> force_dof_, position_dof_;
  std::vector<PolygonChain::Triplet> triplets_;
  std::vector<Entry> entries_;
  std::vector<double> x_, ax_;
};

// The central-difference step with each stiffness term of the Gershgorin bound left out, and
// the step 2/√λ of the power-iteration estimate, at one state (the chain's last evaluation for
// the Gershgorin rows): which term sets the bound, and how pessimistic the bound is.
struct StableStepBreakdown {
  double gershgorin = 0.0;  // PolygonChain::stable_step(): all terms
  double without_membrane = 0.0, without_hinges = 0.0, without_ties = 0.0, without_contacts = 0.0;
  double membrane_only = 0.0, hinges_only = 0.0, ties_only = 0.0, contacts_only = 0.0;
  double power_iteration = 0.0;  // 2/√θ, θ the estimate (≥ the true 2/ω_max)
  int iterations = 0;
  bool converged = false;
};
StableStepBreakdown stable_step_breakdown(PolygonChain& chain, PolygonStiffnessSpectrum& spectrum, double t,
                                          const double* y);

}  // namespace ringcrush::hinge
