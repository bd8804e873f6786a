#include "polygon_stiffness_spectrum.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace ringcrush::hinge {

// K = −∂φ/∂x of the force laws with the Kelvin–Voigt coefficients at zero: their entries in
// the position columns (the turn of a bar's or hinge's damper direction, ∝ c ṽ) are not
// stiffness, and the implicit dampers do not bound the step (polygon_central_difference.hpp).
// With the implicit membrane (set_implicit_membrane) k_m is at zero as well: the driver
// integrates the bars implicitly, so they do not bound the step either (their geometric term
// (N/ℓ)(I − e eᵀ), ≤ k_m |ε| ≈ 1e-3 k_m, goes with them).
void PolygonChain::stiffness_triplets(double t, const double* y, std::vector<Triplet>& out) {
  const double c_bar = c_bar_, c_hinge = c_hinge_, k_m = k_m_;
  c_bar_ = c_hinge_ = 0.0;
  if (implicit_membrane_) k_m_ = 0.0;
  try {
    analytic_jacobian(t, 0.0, y, out);
  } catch (...) {
    c_bar_ = c_bar;
    c_hinge_ = c_hinge;
    k_m_ = k_m;
    throw;
  }
  c_bar_ = c_bar;
  c_hinge_ = c_hinge;
  k_m_ = k_m;
}

PolygonStiffnessSpectrum::PolygonStiffnessSpectrum(PolygonChain& chain) : chain_(chain) {
  force_dof_.assign(chain.size(), -1);
  position_dof_.assign(chain.size(), -1);
  auto add = [&](std::size_t position_row, std::size_t velocity_row) {
    const int dof = static_cast<int>(position_.size());
    position_.push_back(position_row);
    inv_sqrt_mass_.push_back(1.0 / std::sqrt(chain.mass_row(velocity_row)));
    position_dof_[position_row] = force_dof_[velocity_row] = dof;
  };
  const bool half = chain.input().half_symmetry;
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < chain.independent_nodes(); ++j) {
      const auto o = chain.node_offset(r, j);
      const bool axis = half && (j == 0 || j == chain.independent_nodes() - 1);
      if (!axis) add(o, o + 2);  // the symmetry plane holds the axis nodes' x
      add(o + 1, o + 3);
    }
  for (int b = 0; b < chain.body_count(); ++b) {
    if (b == 0 && chain.input().driven_impactor) continue;  // prescribed motion
    add(chain.body_offset(b), chain.body_offset(b) + 1);
  }
  // Start: a fixed pseudo-random vector (every mode present, the run reproducible).
  std::mt19937 gen(12345);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  x_.resize(position_.size());
  double norm = 0.0;
  for (auto& v : x_) {
    v = dist(gen);
    norm += v * v;
  }
  for (auto& v : x_) v /= std::sqrt(norm);
  ax_.resize(x_.size());
}

PolygonStiffnessSpectrum::Estimate PolygonStiffnessSpectrum::estimate(double t, const double* y, int min_iterations,
                                                                     int max_iterations, double tolerance) {
  if (!(min_iterations >= 1 && max_iterations >= min_iterations))
    throw std::invalid_argument("PolygonStiffnessSpectrum: need 1 ≤ min_iterations ≤ max_iterations, got " +
                                std::to_string(min_iterations) + ", " + std::to_string(max_iterations));
  if (!(tolerance > 0.0))
    throw std::invalid_argument("PolygonStiffnessSpectrum: tolerance must be > 0, got " + std::to_string(tolerance));
  chain_.stiffness_triplets(t, y, triplets_);
  // Force rows (velocity rows) × position columns of free dofs; K_ij/√(m_i m_j).
  entries_.clear();
  for (const auto& e : triplets_) {
    const auto row = static_cast<std::size_t>(e.row), col = static_cast<std::size_t>(e.col);
    const int i = force_dof_[row], j = position_dof_[col];
    if (i < 0 || j < 0 || e.value == 0.0) continue;
    entries_.push_back({i, j, e.value * inv_sqrt_mass_[static_cast<std::size_t>(i)] *
                                  inv_sqrt_mass_[static_cast<std::size_t>(j)]});
  }
  Estimate out;
  double previous = 0.0;
  for (int it = 1; it <= max_iterations; ++it) {
    std::fill(ax_.begin(), ax_.end(), 0.0);
    for (const auto& e : entries_) ax_[static_cast<std::size_t>(e.i)] += e.a * x_[static_cast<std::size_t>(e.j)];
    double norm = 0.0;
    for (double v : ax_) norm += v * v;
    norm = std::sqrt(norm);
    out.lambda = norm;
    out.iterations = it;
    if (!(norm > 0.0)) break;  // no stiffness on the iterate (cannot happen with bars)
    for (std::size_t k = 0; k < x_.size(); ++k) x_[k] = ax_[k] / norm;
    out.converged = it > 1 && std::abs(norm - previous) <= tolerance * norm;
    if (out.converged && it >= min_iterations) break;
    previous = norm;
  }
  return out;
}

StableStepBreakdown stable_step_breakdown(PolygonChain& chain, PolygonStiffnessSpectrum& spectrum, double t,
                                          const double* y) {
  using T = PolygonChain::StepTerm;
  StableStepBreakdown b;
  const unsigned all = T::kAllStiffness;
  b.gershgorin = chain.stable_step(all);
  b.without_membrane = chain.stable_step(all & ~T::kMembrane);
  b.without_hinges = chain.stable_step(all & ~T::kHinges);
  b.without_ties = chain.stable_step(all & ~T::kTies);
  b.without_contacts = chain.stable_step(all & ~T::kContacts);
  b.membrane_only = chain.stable_step(T::kMembrane);
  b.hinges_only = chain.stable_step(T::kHinges);
  b.ties_only = chain.stable_step(T::kTies);
  b.contacts_only = chain.stable_step(T::kContacts);
  // After the Gershgorin steps: the estimate re-evaluates the chain at y.
  const auto e = spectrum.estimate(t, y, 20, 400, 1e-4);
  b.power_iteration = e.lambda > 0.0 ? 2.0 / std::sqrt(e.lambda) : 0.0;
  b.iterations = e.iterations;
  b.converged = e.converged;
  return b;
}

}  // namespace ringcrush::hinge
