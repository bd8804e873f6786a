// The explicit step's serial tail in one pass (README "FE dynamics", session 13):
//  - the chain's final force sum in one pass (chain_force_sum.hpp) is bitwise the separate
//    sums (the helper's half on its range, the contact contributions in their order, the
//    bulk-viscous halves, f += q), and hands every dof to the step end once, with its final
//    f and q;
//  - the step end (explicit_step_end.hpp) over ranges in any order gives bitwise the plain
//    pass's a and v, and the energy sums of the dot products to round-off;
//  - an explicit run of a small chain with contact and bulk viscosity, the step end inside
//    ChainModel's force sum (one thread and two), is bitwise the run with the unfused default
//    (DynamicSystem::evaluate_explicit, commit): displacement, velocity, acceleration, force
//    and viscous force at every step; the energies agree to 1e-12 of the reference energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "fe/chain/chain_force_sum.hpp"
#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/explicit_driver.hpp"
#include "fe/dynamics/explicit_step_end.hpp"

using namespace ringcrush::fe;

namespace {

bool bitwise_equal(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

// A sum of `terms` random values of mixed magnitude that starts at +0.0, as the element sums do.
double random_sum(std::mt19937& rng, int terms) {
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-6, 6);
  double s = 0.0;
  for (int t = 0; t < terms; ++t) s += std::ldexp(mantissa(rng), exponent(rng));
  return s;
}

// Records what the one pass hands to the step end.
struct RecordingEnd {
  std::vector<int> seen;
  Eigen::VectorXd f, q;
  explicit RecordingEnd(Eigen::Index n) : seen(static_cast<std::size_t>(n), 0), f(Eigen::VectorXd::Zero(n)), q(f) {}
  void range(Eigen::Index b, Eigen::Index e, const double* force, const double* viscous) {
    for (Eigen::Index i = b; i < e; ++i) {
      ++seen[static_cast<std::size_t>(i)];
      f(i) = force[i];
      q(i) = viscous ? viscous[i] : std::numeric_limits<double>::quiet_NaN();
    }
  }
};

}  // namespace

TEST(ExplicitStepEnd, ChainForceSumInOnePassIsTheSeparateSums) {
  std::mt19937 rng(46);
  constexpr Eigen::Index kNodes = 350, n = 2 * kNodes;  // 700 dofs: blocks of 256 and a short one
  const Eigen::Index lo = 250, len = 300;               // the helper's range crosses two blocks
  int reordered_differs = 0;
  for (int round = 0; round < 20; ++round) {
    const bool viscous = round % 2 == 0;
    Eigen::VectorXd f0(n), fh(n), q0(n), qh(n);
    std::uniform_int_distribution<int> terms(0, 4);
    for (Eigen::Index i = 0; i < n; ++i) {
      f0(i) = i < lo + len / 2 ? random_sum(rng, terms(rng)) : 0.0;  // the caller's half ends mid-range
      q0(i) = i < lo + len / 2 ? random_sum(rng, terms(rng)) : 0.0;
      const bool helper = i >= lo && i < lo + len;
      fh(i) = helper ? random_sum(rng, terms(rng)) : 0.0;
      qh(i) = helper ? random_sum(rng, terms(rng)) : 0.0;
    }
    // Contacts on nodes in and out of the helper's range, several on the same node (the
    // impactor's node takes one from every ring node it presses), with ±0.0 components.
    std::vector<ContactContribution> contributions(40);
    std::uniform_int_distribution<int> node(0, kNodes - 1), count(1, 3);
    for (std::size_t k = 0; k < contributions.size(); ++k) {
      ContactContribution& c = contributions[k];
      c.count = count(rng);
      for (int a = 0; a < c.count; ++a) {
        c.nodes[static_cast<std::size_t>(a)] = k % 4 == 0 ? 200 : node(rng);
        c.force(2 * a) = a == 0 && k % 3 == 0 ? -0.0 : random_sum(rng, 1);
        c.force(2 * a + 1) = random_sum(rng, 1);
      }
    }
    // Unfused: the four sums of ChainModel::evaluate before session 13.
    Eigen::VectorXd f_ref = f0, q_ref = q0;
    f_ref.segment(lo, len) += fh.segment(lo, len);
    for (const auto& c : contributions)
      for (int a = 0; a < c.count; ++a) {
        f_ref(2 * c.nodes[static_cast<std::size_t>(a)]) += c.force(2 * a);
        f_ref(2 * c.nodes[static_cast<std::size_t>(a)] + 1) += c.force(2 * a + 1);
      }
    if (viscous) {
      q_ref.segment(lo, len) += qh.segment(lo, len);
      f_ref += q_ref;
    }
    // The same sums in another order (the contributions before the helper's half) differ:
    // the comparison below can see an order change.
    Eigen::VectorXd f_other = f0;
    for (const auto& c : contributions)
      for (int a = 0; a < c.count; ++a) {
        f_other(2 * c.nodes[static_cast<std::size_t>(a)]) += c.force(2 * a);
        f_other(2 * c.nodes[static_cast<std::size_t>(a)] + 1) += c.force(2 * a + 1);
      }
    f_other.segment(lo, len) += fh.segment(lo, len);
    if (viscous) f_other += q_ref;
    if (!bitwise_equal(f_other, f_ref)) ++reordered_differs;

    Eigen::VectorXd f = f0, q = q0, fh_buffer = fh;
    const ChainForceParts parts{f.data(), fh_buffer.data(), viscous ? q.data() : nullptr, viscous ? qh.data() : nullptr,
                                n, lo, len};
    RecordingEnd end(n);
    finish_chain_force(parts, contributions, end);
    EXPECT_TRUE(bitwise_equal(f, f_ref)) << "round " << round;
    if (viscous) {
      EXPECT_TRUE(bitwise_equal(q, q_ref)) << "round " << round;
    }
    EXPECT_TRUE(std::all_of(end.seen.begin(), end.seen.end(), [](int s) { return s == 1; })) << "round " << round;
    EXPECT_TRUE(bitwise_equal(end.f, f_ref)) << "round " << round;
    if (viscous) {
      EXPECT_TRUE(bitwise_equal(end.q, q_ref)) << "round " << round;
    } else {
      EXPECT_TRUE(end.q.array().isNaN().all()) << "round " << round;  // no q handed on
    }
    // The helper's buffer is +0.0 only where a contribution touched its range.
    for (Eigen::Index i = 0; i < n; ++i)
      if (fh_buffer(i) != fh(i)) {
        EXPECT_TRUE(fh_buffer(i) == 0.0 && !std::signbit(fh_buffer(i))) << i;
      }
  }
  EXPECT_GT(reordered_differs, 10);
}

TEST(ExplicitStepEnd, RangesInAnyOrderAreThePlainPass) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1, 1);
  constexpr Eigen::Index n = 1001;  // not a multiple of the four partial sums
  Eigen::VectorXd mass(n), inv_mass(n), v0(n), f(n), q(n), f_old(n), q_old(n), du(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    mass(i) = 1e-4 * (1.5 + d(rng));
    inv_mass(i) = i % 97 == 0 ? 0.0 : 1.0 / mass(i);  // a few fixed dofs
    v0(i) = 30 * d(rng);
    f(i) = 1e3 * d(rng);
    q(i) = 10 * d(rng);
    f_old(i) = 1e3 * d(rng);
    q_old(i) = 10 * d(rng);
    du(i) = 1e-6 * d(rng);
  }
  const double half = 2.5e-8;
  const Eigen::VectorXd zeros = Eigen::VectorXd::Zero(n);
  // A step end over these dofs writing v and a (old viscous force: null for none).
  auto step_end = [&](Eigen::VectorXd& v, Eigen::VectorXd& a, const double* old_viscous) {
    ExplicitStepEnd end;
    end.inv_mass = inv_mass.data();
    end.mass = mass.data();
    end.velocity = v.data();
    end.acceleration = a.data();
    end.old_force = f_old.data();
    end.old_viscous = old_viscous;
    end.zeros = zeros.data();
    end.increment = du.data();
    end.half_step = half;
    return end;
  };
  for (int viscous = 0; viscous < 3; ++viscous) {  // none; q_n and q_{n+1}; q_{n+1} only (first step)
    // The plain pass of the driver before session 13, and the energy sums of EnergyBalance.
    Eigen::VectorXd v_ref = v0, a_ref(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      a_ref(i) = -(inv_mass(i) * f(i));
      v_ref(i) += half * a_ref(i);
    }
    EnergyBalance ref;
    ref.add_step(f_old, f, viscous == 1 ? q_old : Eigen::VectorXd(), viscous > 0 ? q : Eigen::VectorXd(), du);
    const double ke_ref = EnergyBalance::kinetic_energy(mass, v_ref);

    // Ranges of random length in a random order.
    std::vector<Eigen::Index> cuts{0, n};
    for (int k = 0; k < 12; ++k) cuts.push_back(std::uniform_int_distribution<Eigen::Index>(1, n - 1)(rng));
    std::sort(cuts.begin(), cuts.end());
    std::vector<std::size_t> order(cuts.size() - 1);
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    Eigen::VectorXd v = v0, a = Eigen::VectorXd::Constant(n, 7.0);
    ExplicitStepEnd end = step_end(v, a, viscous == 1 ? q_old.data() : nullptr);
    for (std::size_t k : order) end.range(cuts[k], cuts[k + 1], f.data(), viscous > 0 ? q.data() : nullptr);
    EXPECT_TRUE(bitwise_equal(a, a_ref)) << viscous;
    EXPECT_TRUE(bitwise_equal(v, v_ref)) << viscous;
    EXPECT_EQ(end.not_finite, 0.0);
    EnergyBalance fused;
    fused.add_step_sums(end.force_du, end.viscous_du);
    // Round-off of sums of ~1000 terms: against the sum of the terms' magnitudes.
    const double scale_work = 0.5 * ((f_old.cwiseAbs() + f.cwiseAbs()).dot(du.cwiseAbs()));
    const double scale_viscous = 0.5 * ((q_old.cwiseAbs() + q.cwiseAbs()).dot(du.cwiseAbs()));
    EXPECT_NEAR(0.5 * end.mass_v2, ke_ref, 1e-13 * ke_ref) << viscous;
    EXPECT_NEAR(fused.force_work, ref.force_work, 1e-13 * (scale_work + scale_viscous)) << viscous;
    EXPECT_NEAR(fused.viscous_work, ref.viscous_work, 1e-13 * scale_viscous) << viscous;
    if (viscous == 0) {
      EXPECT_EQ(fused.viscous_work, 0.0);
    } else {
      EXPECT_GT(std::abs(fused.viscous_work), 1e-6 * scale_viscous);
    }
  }
  // A non-finite force is seen, wherever it lies.
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    Eigen::VectorXd f_bad = f, v = v0, a(n);
    f_bad(n - 2) = bad;
    ExplicitStepEnd end = step_end(v, a, nullptr);
    end.range(500, n, f_bad.data(), nullptr);
    end.range(0, 500, f_bad.data(), nullptr);
    EXPECT_FALSE(end.not_finite == 0);
  }
}

namespace {

// The ChainModel behind the DynamicSystem defaults: evaluate(), then the step end over all
// dofs in order (evaluate_explicit), and the comparing commit() (commit_evaluated).
class UnfusedChain final : public DynamicSystem {
 public:
  explicit UnfusedChain(ChainModel& m) : m_(m) {}
  int dofs() const override { return m_.dofs(); }
  const std::vector<int>& fixed_dofs() const override { return m_.fixed_dofs(); }
  const Eigen::VectorXd& lumped_mass() const override { return m_.lumped_mass(); }
  Eigen::VectorXd initial_velocity() const override { return m_.initial_velocity(); }
  void evaluate(const Eigen::VectorXd& u, bool want_tangent, SystemEvaluation& out) override {
    m_.evaluate(u, want_tangent, out);
  }
  void commit(const Eigen::VectorXd& u) override { m_.commit(u); }
  SparseSystem& tangent_system() override { return m_.tangent_system(); }
  StableStep stable_step(const Eigen::VectorXd& u) const override { return m_.stable_step(u); }
  StableStep contact_stable_step(const Eigen::VectorXd& u) const override { return m_.contact_stable_step(u); }
  void set_increment_time(double dt) override { m_.set_increment_time(dt); }

 private:
  ChainModel& m_;
};

}  // namespace

TEST(ExplicitStepEnd, ChainRunIsBitwiseTheUnfusedRun) {
  // Two free rings struck at 30 m/s (impactor, ring↔ring and target contact), bulk viscosity on.
  ChainInput in;
  in.rings = 2;
  in.joints = JointKind::Free;
  in.mesh.elements_around = 12;
  in.pitch_m = 2 * in.ring.outer_radius_m;
  in.impactor_mass_kg = 0.256;
  in.impactor_velocity_m_s = 30;
  in.bulk_viscosity = 0.06;
  for (int threads : {1, 2}) {
    in.threads = threads;
    ChainModel fused_model(in), reference_model(in);
    UnfusedChain reference_system(reference_model);
    ExplicitOptions options;
    ExplicitDriver fused(fused_model, options), reference(reference_system, options);
    const double e_ref = reference.energy().reference();
    int with_contact = 0;
    std::uint64_t active_set = 0;
    for (int step = 0; step < 400; ++step) {
      fused.step();
      reference.step();
      const std::string where = "threads " + std::to_string(threads) + ", step " + std::to_string(step);
      ASSERT_TRUE(bitwise_equal(fused.displacement(), reference.displacement())) << where;
      ASSERT_TRUE(bitwise_equal(fused.velocity(), reference.velocity())) << where;
      ASSERT_TRUE(bitwise_equal(fused.acceleration(), reference.acceleration())) << where;
      ASSERT_TRUE(bitwise_equal(fused.evaluation().force, reference.evaluation().force)) << where;
      ASSERT_TRUE(bitwise_equal(fused.evaluation().viscous_force, reference.evaluation().viscous_force)) << where;
      ASSERT_EQ(fused.step_size(), reference.step_size()) << where;
      const EnergyBalance &a = fused.energy(), &b = reference.energy();
      EXPECT_NEAR(a.kinetic, b.kinetic, 1e-12 * e_ref) << where;
      EXPECT_NEAR(a.force_work, b.force_work, 1e-12 * e_ref) << where;
      EXPECT_NEAR(a.viscous_work, b.viscous_work, 1e-12 * e_ref) << where;
      EXPECT_EQ(a.elastic, b.elastic) << where;
      EXPECT_EQ(a.plastic, b.plastic) << where;
      if (fused_model.contact_forces().active > 0) ++with_contact;
      // The contact re-bound as run_dynamic asks for it, in both runs.
      if (fused_model.contact_forces().active_set != active_set) {
        active_set = fused_model.contact_forces().active_set;
        fused.request_contact_bound();
        reference.request_contact_bound();
      }
    }
    EXPECT_GT(with_contact, 300) << threads;
    EXPECT_GT(fused.energy().viscous_work, 0.0);
    EXPECT_GT(fused.energy().plastic, 0.0);
    EXPECT_LT(std::abs(fused.energy().balance_error()), 0.01 * e_ref);
  }
}
