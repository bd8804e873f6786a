#include "fe/dynamics/assembled_eigenvalue.hpp"

#include <fmt/format.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace ringcrush::fe {

AssembledEigenvalue::AssembledEigenvalue(std::vector<std::array<int, 16>> element_dofs, Eigen::VectorXd inv_sqrt_mass)
    : dofs_(std::move(element_dofs)), inv_sqrt_mass_(std::move(inv_sqrt_mass)) {
  const Eigen::Index n = inv_sqrt_mass_.size();
  for (const auto& d : dofs_)
    for (int i : d)
      if (i < 0 || i >= n) throw std::invalid_argument(fmt::format("AssembledEigenvalue: dof {} outside [0, {})", i, n));
  // Start: a fixed pseudo-random vector (every mode present, the run reproducible).
  std::mt19937 gen(12345);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  x_.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) x_(i) = inv_sqrt_mass_(i) != 0 ? dist(gen) : 0.0;
  if (!(x_.norm() > 0)) throw std::invalid_argument("AssembledEigenvalue: no free dof with mass");
  x_.normalize();
  y_.resize(n);
}

void AssembledEigenvalue::use_threads(ForkJoin* fork) {
  fork_ = fork;
  if (fork_) products_.resize(dofs_.size());
}

void AssembledEigenvalue::element_products(int e0, int e1, const std::vector<ElementMatrix>& k,
                                           const std::vector<double>& scale, const Eigen::VectorXd& x) {
  ElementVector xe, ye;
  for (int e = e0; e < e1; ++e) {
    const auto& d = dofs_[e];
    for (int i = 0; i < 16; ++i) xe(i) = x(d[i]) * inv_sqrt_mass_(d[i]);
    ye.noalias() = k[e] * xe;
    for (int i = 0; i < 16; ++i) products_[e](i) = scale[e] * ye(i) * inv_sqrt_mass_(d[i]);
  }
}

// y = M^{-1/2} (Σ_e s_e K_e) M^{-1/2} x. Each element's term is the same product on either
// path and y sums the terms in element order, so one and two threads give the same bits.
void AssembledEigenvalue::apply(const std::vector<ElementMatrix>& k, const std::vector<double>& scale,
                                const std::vector<ContactContribution>& springs, const Eigen::VectorXd& x,
                                Eigen::VectorXd& y) {
  y.setZero();
  const int ne = static_cast<int>(dofs_.size());
  if (fork_) {
    struct Half {
      AssembledEigenvalue* self;
      const std::vector<ElementMatrix>* k;
      const std::vector<double>* scale;
      const Eigen::VectorXd* x;
      int e0, e1;
      static void run(void* p) {
        auto& h = *static_cast<Half*>(p);
        h.self->element_products(h.e0, h.e1, *h.k, *h.scale, *h.x);
      }
    } helper{this, &k, &scale, &x, ne / 2, ne};
    fork_->run(&Half::run, &helper, [&] { element_products(0, ne / 2, k, scale, x); });
    for (int e = 0; e < ne; ++e) {
      const auto& d = dofs_[e];
      for (int i = 0; i < 16; ++i) y(d[i]) += products_[e](i);
    }
  } else {
    ElementVector xe, ye;
    for (int e = 0; e < ne; ++e) {
      const auto& d = dofs_[e];
      for (int i = 0; i < 16; ++i) xe(i) = x(d[i]) * inv_sqrt_mass_(d[i]);
      ye.noalias() = k[e] * xe;
      for (int i = 0; i < 16; ++i) y(d[i]) += scale[e] * ye(i) * inv_sqrt_mass_(d[i]);
    }
  }
  // Penalty springs k G Gᵀ (the part of the contact tangent without the curvature terms).
  for (const auto& c : springs) {
    if (!(c.stiffness > 0) || !(c.gap < 0)) continue;
    const double inv = 1.0 / (c.stiffness * c.gap);
    double s = 0;
    for (int a = 0; a < c.count; ++a)
      for (int j = 0; j < 2; ++j) {
        const int dof = 2 * c.nodes[a] + j;
        s += c.force(2 * a + j) * inv * inv_sqrt_mass_(dof) * x(dof);
      }
    s *= c.stiffness;
    for (int a = 0; a < c.count; ++a)
      for (int j = 0; j < 2; ++j) {
        const int dof = 2 * c.nodes[a] + j;
        y(dof) += s * c.force(2 * a + j) * inv * inv_sqrt_mass_(dof);
      }
  }
}

AssembledEstimate AssembledEigenvalue::estimate(const std::vector<ElementMatrix>& stiffness,
                                                const std::vector<double>& scale, int min_iterations,
                                                int max_iterations, double tolerance,
                                                const std::vector<ContactContribution>& springs) {
  if (stiffness.size() != dofs_.size() || scale.size() != dofs_.size())
    throw std::invalid_argument(fmt::format("AssembledEigenvalue: {} matrices and {} scales for {} elements",
                                            stiffness.size(), scale.size(), dofs_.size()));
  if (min_iterations < 1 || max_iterations < min_iterations)
    throw std::invalid_argument(
        fmt::format("AssembledEigenvalue: iterations {}..{} (need 1 ≤ min ≤ max)", min_iterations, max_iterations));
  if (!(tolerance > 0)) throw std::invalid_argument(fmt::format("AssembledEigenvalue: tolerance {} must be > 0", tolerance));
  for (const auto& c : springs)
    for (int a = 0; a < c.count; ++a)
      if (c.nodes[a] < 0 || 2 * c.nodes[a] + 1 >= inv_sqrt_mass_.size())
        throw std::invalid_argument(fmt::format("AssembledEigenvalue: contact node {} outside the model", c.nodes[a]));
  AssembledEstimate out;
  double previous = 0;
  for (int it = 1; it <= max_iterations; ++it) {
    apply(stiffness, scale, springs, x_, y_);
    // |x| = 1 and A ⪰ 0 (elastic element matrices, positive scales): the Rayleigh quotient
    // xᵀAx ≤ |Ax| ≤ λ_max, so |Ax| is the closer of the two lower estimates.
    const double norm = y_.norm();
    if (!(norm > 0) || !std::isfinite(norm)) return out;  // not converged: the caller falls back
    const double theta = norm;
    x_ = y_ / norm;
    out.lambda = theta;
    out.iterations = it;
    if (it >= min_iterations && it > 1 && std::abs(theta - previous) <= tolerance * theta) {
      out.converged = true;
      break;
    }
    previous = theta;
  }
  return out;
}

}  // namespace ringcrush::fe
