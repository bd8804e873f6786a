// Small closed-form DynamicSystems for verifying the dynamic drivers (issue 4, STYLE.md
// practice 10): point masses on a line joined by linear springs (to each other or to the
// ground) and by penalty contact springs that push two masses apart only while they overlap
// (potential ½ k g² for gap g < 0, so the force is the gradient of the energy and the
// tangent its Hessian, as in the ring contact).
//
// Node i carries mass i: its x dof (2i) is free, its y dof (2i + 1) fixed.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fe/dynamics/dynamic_system.hpp"

namespace ringcrush::fe::testing {

class SpringMassSystem final : public DynamicSystem {
 public:
  SpringMassSystem(std::vector<double> masses, std::vector<double> positions)
      : x0_(std::move(positions)), n_(static_cast<int>(masses.size())), system_(n_, fixed_of(n_), {}) {
    mass_ = Eigen::VectorXd::Ones(2 * n_);
    for (int i = 0; i < n_; ++i) mass_(2 * i) = masses[static_cast<std::size_t>(i)];
    for (int i = 0; i < n_; ++i) fixed_.push_back(2 * i + 1);
    velocity_ = Eigen::VectorXd::Zero(2 * n_);
  }

  // b = −1: a spring from mass a to the ground.
  void add_spring(int a, int b, double k) {
    springs_.push_back({a, b, k});
    couple(a, b);
  }
  // Contact: mass a lies left of mass b; they repel with stiffness k while x_b − x_a < 0.
  void add_contact(int a, int b, double k) {
    contacts_.push_back({a, b, k});
    couple(a, b);
  }
  void set_velocity(int i, double v) { velocity_(2 * i) = v; }
  int active_contacts() const { return active_; }
  int evaluations() const { return evaluations_; }

  int dofs() const override { return 2 * n_; }
  const std::vector<int>& fixed_dofs() const override { return fixed_; }
  const Eigen::VectorXd& lumped_mass() const override { return mass_; }
  Eigen::VectorXd initial_velocity() const override { return velocity_; }
  SparseSystem& tangent_system() override { return system_; }
  void commit(const Eigen::VectorXd&) override {}

  void evaluate(const Eigen::VectorXd& u, bool want_tangent, SystemEvaluation& out) override {
    ++evaluations_;
    out = SystemEvaluation{};
    out.force = Eigen::VectorXd::Zero(2 * n_);
    if (want_tangent) system_.zero();
    for (const auto& s : springs_) {
      const double stretch = u(2 * s.a) - (s.b >= 0 ? u(2 * s.b) : 0.0);
      out.elastic_energy += 0.5 * s.k * stretch * stretch;
      add_pair(s.a, s.b, s.k * stretch, s.k, want_tangent, out);
    }
    active_ = 0;
    for (const auto& c : contacts_) {
      const double gap = (x0_[static_cast<std::size_t>(c.b)] + u(2 * c.b)) - (x0_[static_cast<std::size_t>(c.a)] + u(2 * c.a));
      if (gap >= 0) continue;
      ++active_;
      out.contact_energy += 0.5 * c.k * gap * gap;
      // E = ½ k g², g = x_b − x_a: ∂E/∂u_a = −k g (> 0 pushes a back), ∂E/∂u_b = k g.
      add_pair(c.a, c.b, -c.k * gap, c.k, want_tangent, out);
    }
  }

  // Gershgorin bound on ω_max² = max_i Σ_j |K_ij| / m_i over the active springs.
  StableStep stable_step(const Eigen::VectorXd& u) const override {
    std::vector<double> row(static_cast<std::size_t>(n_), 0.0);
    auto add = [&](int a, int b, double k) {
      row[static_cast<std::size_t>(a)] += k * (b >= 0 ? 2 : 1);
      if (b >= 0) row[static_cast<std::size_t>(b)] += 2 * k;
    };
    for (const auto& s : springs_) add(s.a, s.b, s.k);
    int contacts = 0;
    for (const auto& c : contacts_)
      if ((x0_[static_cast<std::size_t>(c.b)] + u(2 * c.b)) - (x0_[static_cast<std::size_t>(c.a)] + u(2 * c.a)) < 0) {
        add(c.a, c.b, c.k);
        ++contacts;
      }
    double w2 = 0;
    int at = 0;
    for (int i = 0; i < n_; ++i)
      if (row[static_cast<std::size_t>(i)] / mass_(2 * i) > w2) {
        w2 = row[static_cast<std::size_t>(i)] / mass_(2 * i);
        at = i;
      }
    StableStep s;
    s.step_s = w2 > 0 ? 2.0 / std::sqrt(w2) : 1e30;
    s.limited_by = "mass " + std::to_string(at) + (contacts ? " (with contact)" : "");
    return s;
  }

 private:
  struct Link {
    int a, b;
    double k;
  };
  static std::vector<int> fixed_of(int n) {
    std::vector<int> f;
    for (int i = 0; i < n; ++i) f.push_back(2 * i + 1);
    return f;
  }
  void couple(int a, int b) {
    if (b < 0) return;
    const int nodes[2] = {a, b};
    system_.ensure_coupled(nodes, 2);
  }
  // Force +p on a, −p on b (b = −1: ground); stiffness k between them.
  void add_pair(int a, int b, double p, double k, bool want_tangent, SystemEvaluation& out) {
    out.force(2 * a) += p;
    if (b >= 0) out.force(2 * b) -= p;
    if (!want_tangent) return;
    auto& m = system_.matrix();
    const int ia = system_.free_index(2 * a);
    m.coeffRef(ia, ia) += k;
    if (b >= 0) {
      const int ib = system_.free_index(2 * b);
      m.coeffRef(ib, ib) += k;
      m.coeffRef(ia, ib) -= k;
      m.coeffRef(ib, ia) -= k;
    }
  }

  std::vector<double> x0_;
  int n_;
  Eigen::VectorXd mass_, velocity_;
  std::vector<int> fixed_;
  std::vector<Link> springs_, contacts_;
  SparseSystem system_;
  int active_ = 0, evaluations_ = 0;
};

// Total momentum along x.
inline double momentum(const DynamicSystem& s, const Eigen::VectorXd& v) {
  double p = 0;
  for (int d = 0; d < s.dofs(); d += 2) p += s.lumped_mass()(d) * v(d);
  return p;
}

}  // namespace ringcrush::fe::testing
