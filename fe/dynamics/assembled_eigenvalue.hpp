// A sharper explicit stable step than the element eigenvalue inequality (issue 4
// performance; element_eigenvalue.hpp): the highest eigenvalue of the ASSEMBLED system
// K v = λ M v (M lumped, diagonal) estimated by power iteration on the symmetric form
// A = M^{-1/2} K M^{-1/2}, K = Σ_e K_e.
//
// Why: the element bound max_e λ_e(K_e, M_e) is a guaranteed upper bound of λ_max, but on
// the thesis chain it is ≈ 1.45 λ_max (2/ω from it is 0.83 of the true 2/ω_max, README), since
// neighbouring elements share the mass of their common nodes. |A x| of the unit power
// iterate x converges to λ_max from BELOW, so it is an estimate, not a bound: the caller
// multiplies it by a margin and never goes above the element bound. The iterate is kept
// between calls (warm start): along a run the deformation changes K slowly, so a few
// iterations per call follow the highest mode, and the iterations accumulate.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "fe/contact/contact_element.hpp"
#include "fe/dynamics/fork_join.hpp"
#include "fe/element/cps8_element.hpp"

namespace ringcrush::fe {

struct AssembledEstimate {
  double lambda = 0;      // θ = |A x| for the unit iterate x: θ ≤ λ_max (1/s²)
  int iterations = 0;
  bool converged = false;  // |θ_k − θ_{k−1}| ≤ tolerance · θ_k
};

class AssembledEigenvalue {
 public:
  // element_dofs: the 16 global dofs of each element; inv_sqrt_mass: M^{-1/2} per dof, 0 on
  // fixed dofs (and on dofs without element stiffness, e.g. the rigid bodies).
  AssembledEigenvalue(std::vector<std::array<int, 16>> element_dofs, Eigen::VectorXd inv_sqrt_mass);

  // λ_max of Σ_e scale_e K_e + Σ_c k_c G_c G_cᵀ by power iteration from the last iterate,
  // at least min_iterations and at most max_iterations; stops when θ changed by
  // ≤ tolerance · θ. springs: contact contributions with stiffness and gap set (others are
  // skipped), G_c = force / (k g) on their nodes' dofs. Throws std::invalid_argument on sizes
  // that do not match the element count or bad iteration limits.
  AssembledEstimate estimate(const std::vector<ElementMatrix>& stiffness, const std::vector<double>& scale,
                             int min_iterations, int max_iterations, double tolerance,
                             const std::vector<ContactContribution>& springs = {});

  // Two threads (null: one): the element products of every iteration are formed half on the
  // calling thread, half on fork's helper, each into its element's slot, and summed on the
  // caller in element order — the sums of one thread, so the estimate is bitwise the same
  // (tests). On the explicit chain the estimate runs between two steps, when nothing else
  // can (the step needs its Δt), and one thread doing it all left the helper idle (README,
  // session 9). The fork must outlive this object's estimates.
  void use_threads(ForkJoin* fork);

 private:
  void apply(const std::vector<ElementMatrix>& k, const std::vector<double>& scale,
             const std::vector<ContactContribution>& springs, const Eigen::VectorXd& x, Eigen::VectorXd& y);
  // M^{-1/2} s_e K_e M^{-1/2} x of elements [e0, e1) into their slots products_[e].
  void element_products(int e0, int e1, const std::vector<ElementMatrix>& k, const std::vector<double>& scale,
                        const Eigen::VectorXd& x);

  std::vector<std::array<int, 16>> dofs_;
  Eigen::VectorXd inv_sqrt_mass_, x_, y_;
  ForkJoin* fork_ = nullptr;
  std::vector<ElementVector> products_;
};

}  // namespace ringcrush::fe
