// The chain model as the dynamic drivers see it (issue 4 items 1–5): internal force zero for
// rigid motions (objectivity of the incremental element, zero stress), ring↔ring contact
// with action = reaction (momentum conservation) and no master/slave bias (mirror-symmetric
// forces), force = gradient of the stored energy, the assembled tangent equal to finite
// differences of the force, commit taking the states of the committed u, and the stable
// step bounding the highest frequency of the assembled system from above, within 2×.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>

#include "fe/chain/chain_model.hpp"
#include "chain_omega_max.hpp"
#include "fe/chain/geometry_update.hpp"

using namespace ringcrush::fe;

namespace {
constexpr double kR = 25.4e-3, kDepth = 1.6e-3;

ChainInput chain(int rings, JointKind joints, bool half = true, int around = 8) {
  ChainInput in;
  in.rings = rings;
  in.mesh.elements_around = around;
  in.mesh.half_ring = half;
  in.joints = joints;
  in.pitch_m = 2 * kR;
  in.fixed_target = false;
  return in;
}
// Force of a 0.1 % strain over the wall section: the scale of "zero" internal force.
double force_scale(const ChainInput& in) { return in.material.youngs_modulus_pa * in.ring.width_m * kDepth * 1e-3; }

void move_ring(const ChainModel& m, int ring, double dx, double dy, Eigen::VectorXd& u) {
  const auto& mesh = m.mesh();
  for (std::size_t e = 0; e < mesh.elements.size(); ++e)
    if (mesh.element_ring[e] == ring)
      for (int n : mesh.elements[e]) {
        u(2 * n) = dx;
        u(2 * n + 1) = dy;
      }
}
}  // namespace

TEST(ChainModel, RigidTranslationGivesZeroForceAndStress) {
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    ChainInput in = chain(3, JointKind::Welded);
    in.integration = rule;
    ChainModel model(in);
    Eigen::VectorXd u(model.dofs());
    for (int n = 0; n < model.dofs() / 2; ++n) {
      u(2 * n) = 0.7e-3;
      u(2 * n + 1) = 2.1e-3;
    }
    SystemEvaluation ev;
    model.evaluate(u, false, ev);
    EXPECT_LT(ev.force.lpNorm<Eigen::Infinity>(), 1e-10 * force_scale(in));
    EXPECT_EQ(model.contact_forces().active, 0);
    model.commit(u);
    for (const auto& f : model.element_fields()) EXPECT_LT(f.mises, 1e-10 * 1e-3 * in.material.youngs_modulus_pa);
  }
}

TEST(ChainModel, RigidRotationOfAFullRingGivesZeroForce) {
  ChainInput in = chain(1, JointKind::Free, false);
  in.integration = Integration::Selective;
  ChainModel model(in);
  const auto& mesh = model.mesh();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
  const double a = 0.4;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (static_cast<int>(n) == mesh.impactor_node) continue;
    const auto& p = mesh.nodes[n];
    u(2 * n) = std::cos(a) * p.x() - std::sin(a) * p.y() - p.x();
    u(2 * n + 1) = std::sin(a) * p.x() + std::cos(a) * p.y() - p.y();
  }
  u(model.impactor_dof()) = 1e-3;  // clear of the ring
  SystemEvaluation ev;
  model.evaluate(u, false, ev);
  EXPECT_LT(ev.force.lpNorm<Eigen::Infinity>(), 1e-10 * force_scale(in));
  EXPECT_LT(std::abs(ev.elastic_energy), 1e-20);
  model.commit(u);
  for (const auto& f : model.element_fields()) EXPECT_LT(f.mises, 1e-10 * 1e-3 * in.material.youngs_modulus_pa);
}

TEST(ChainModel, RingContactIsActionEqualsReaction) {
  for (bool half : {true, false}) {
    ChainModel model(chain(2, JointKind::Free, half));
    Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
    move_ring(model, 1, half ? 0.0 : 0.3e-3, 0.25 * kDepth, u);  // ring 2 pushed into ring 1
    u(model.impactor_dof()) = 1e-3;
    SystemEvaluation ev;
    model.evaluate(u, false, ev);
    const auto& cf = model.contact_forces();
    ASSERT_GT(cf.ring_ring_n, 0.0);
    EXPECT_GT(cf.active, 1);
    EXPECT_EQ(cf.impactor_n, 0.0);
    EXPECT_EQ(cf.pairs_checked, 1);
    double fx = 0, fy = 0, ring2_y = 0;
    for (int n = 0; n < model.dofs() / 2; ++n) {
      fx += ev.force(2 * n);
      fy += ev.force(2 * n + 1);
    }
    for (int n : model.mesh().ring_outer_nodes[1]) ring2_y += ev.force(2 * n + 1);
    // Momentum: the contact forces on both rings add up to zero.
    EXPECT_LT(std::abs(fx), 1e-12 * cf.ring_ring_n) << (half ? "half" : "full");
    EXPECT_LT(std::abs(fy), 1e-12 * cf.ring_ring_n);
    // Ring 2 is pushed down (the residual force is +y: f = ∂E/∂u grows with overlap).
    EXPECT_GT(ring2_y, 0.3 * cf.ring_ring_n);
    EXPECT_GT(ev.contact_energy, 0.0);
  }
}

TEST(ChainModel, TwoPassRingContactIsMirrorSymmetric) {
  // Ring 2 pushed into ring 1: the pair is symmetric about the plane half-way between the
  // centres, so the force on a node of ring 1 mirrors the force on its image in ring 2. One
  // pass (one ring as master) would not give this.
  ChainModel model(chain(2, JointKind::Free));
  const auto& mesh = model.mesh();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
  const double dy = 0.3 * kDepth;
  move_ring(model, 1, 0.0, dy, u);
  u(model.impactor_dof()) = 1e-3;
  SystemEvaluation ev;
  model.evaluate(u, false, ev);
  const double plane = 0.5 * (0.0 + (-2 * kR + dy));
  const double fmax = ev.force.lpNorm<Eigen::Infinity>();
  ASSERT_GT(fmax, 0.0);
  int pairs = 0;
  for (int n = 0; n < model.dofs() / 2; ++n) {
    if (n == mesh.impactor_node) continue;
    const Eigen::Vector2d p = mesh.nodes[n] + Eigen::Vector2d(u(2 * n), u(2 * n + 1));
    if (p.y() < plane) continue;
    const Eigen::Vector2d image(p.x(), 2 * plane - p.y());
    for (int m = 0; m < model.dofs() / 2; ++m) {
      const Eigen::Vector2d q = mesh.nodes[m] + Eigen::Vector2d(u(2 * m), u(2 * m + 1));
      if ((q - image).norm() > 1e-12) continue;
      ++pairs;
      EXPECT_NEAR(ev.force(2 * n), ev.force(2 * m), 1e-9 * fmax) << n << " ↔ " << m;
      EXPECT_NEAR(ev.force(2 * n + 1), -ev.force(2 * m + 1), 1e-9 * fmax) << n << " ↔ " << m;
    }
  }
  EXPECT_EQ(pairs, static_cast<int>(mesh.nodes.size() - 1) / 2);
}

namespace {
// A contact-rich elastic state: the impactor pressed into ring 1, ring 2 pushed up into
// ring 1 and a small random strain everywhere.
Eigen::VectorXd busy_state(const ChainModel& model, unsigned seed) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
  move_ring(model, 1, 0.0, 0.15 * kDepth, u);
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-1e-6 * kR, 1e-6 * kR);
  for (int i = 0; i < model.dofs(); ++i) u(i) += d(gen);
  for (int dof : model.fixed_dofs()) u(dof) = 0;
  u(model.impactor_dof()) = -0.2 * kDepth;
  return u;
}
}  // namespace

TEST(ChainModel, ForceIsTheGradientOfTheStoredEnergy) {
  ChainInput in = chain(2, JointKind::Free);
  in.fixed_target = true;
  ChainModel model(in);
  const Eigen::VectorXd u = busy_state(model, 3);
  SystemEvaluation ev, ep, em;
  model.evaluate(u, false, ev);
  ASSERT_GT(model.contact_forces().impactor_n, 0.0);
  ASSERT_GT(model.contact_forces().ring_ring_n, 0.0);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> r(-1, 1);
  Eigen::VectorXd dir(model.dofs());
  for (int i = 0; i < model.dofs(); ++i) dir(i) = r(gen);
  for (int dof : model.fixed_dofs()) dir(dof) = 0;
  const double h = 1e-9;
  model.evaluate(u + h * dir, false, ep);
  model.evaluate(u - h * dir, false, em);
  const double de = (ep.elastic_energy + ep.contact_energy - em.elastic_energy - em.contact_energy) / (2 * h);
  const double fd = ev.force.dot(dir);
  EXPECT_NEAR(de, fd, 1e-6 * std::abs(fd));
}

TEST(ChainModel, TangentMatchesFiniteDifferencesOfTheForce) {
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    ChainInput in = chain(2, JointKind::Free);
    in.fixed_target = true;
    in.integration = rule;
    ChainModel model(in);
    const Eigen::VectorXd u = busy_state(model, 11);
    SystemEvaluation ev, ep, em;
    model.evaluate(u, true, ev);
    ASSERT_GT(model.contact_forces().ring_ring_n, 0.0);
    SparseSystem& sys = model.tangent_system();
    const Eigen::MatrixXd k = Eigen::MatrixXd(sys.matrix());
    const int nf = sys.free_dofs();
    Eigen::MatrixXd kfd(nf, nf);
    const double h = 1e-8 * kR;
    for (int j = 0; j < nf; ++j) {
      Eigen::VectorXd up = u, um = u;
      up(sys.free_to_dof()[j]) += h;
      um(sys.free_to_dof()[j]) -= h;
      model.evaluate(up, false, ep);
      model.evaluate(um, false, em);
      for (int i = 0; i < nf; ++i) kfd(i, j) = (ep.force(sys.free_to_dof()[i]) - em.force(sys.free_to_dof()[i])) / (2 * h);
    }
    const double scale = k.lpNorm<Eigen::Infinity>();
    EXPECT_LT((k - kfd).lpNorm<Eigen::Infinity>(), 1e-6 * scale);
    EXPECT_LT((k - k.transpose()).lpNorm<Eigen::Infinity>(), 1e-9 * scale);
  }
}

TEST(ChainModel, CommitTakesTheStatesOfTheCommittedDisplacement) {
  ChainInput in = chain(1, JointKind::Free);
  ChainModel a(in), b(in);
  Eigen::VectorXd u1 = Eigen::VectorXd::Zero(a.dofs()), u2 = u1;
  // A large radial squeeze of the ring's side: plastic.
  for (int n = 0; n < a.dofs() / 2; ++n) {
    u1(2 * n) = -0.02 * a.mesh().nodes[n].x();
    u2(2 * n) = -0.04 * a.mesh().nodes[n].x();
  }
  SystemEvaluation ev;
  a.evaluate(u1, false, ev);
  a.evaluate(u2, false, ev);  // e.g. a half-step residual, evaluated after the step
  a.commit(u1);
  b.evaluate(u1, false, ev);
  b.commit(u1);
  const auto fa = a.element_fields(), fb = b.element_fields();
  ASSERT_GT(fb[0].peeq, 0.0);
  for (std::size_t e = 0; e < fa.size(); ++e) {
    EXPECT_EQ(fa[e].mises, fb[e].mises);
    EXPECT_EQ(fa[e].peeq, fb[e].peeq);
  }
  EXPECT_GT(a.max_peeq_per_ring()[0], 0.0);
}

TEST(ChainModel, InitialVelocityExtentAndImpactorForce) {
  ChainInput in = chain(3, JointKind::Welded);
  in.impactor_velocity_m_s = 30;
  ChainModel model(in);
  const auto v = model.initial_velocity();
  EXPECT_EQ(v(model.impactor_dof()), -30.0);
  EXPECT_EQ(v.lpNorm<1>(), 30.0);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(model.ring_extent(i, u), 2 * kR, 1e-12);
  u(model.impactor_dof()) = -0.1 * kDepth;
  SystemEvaluation ev;
  model.evaluate(u, false, ev);
  // The force on the impactor's dof is the contact force pushing it back up (residual −).
  EXPECT_GT(model.contact_forces().impactor_n, 0.0);
  EXPECT_NEAR(-ev.force(model.impactor_dof()), model.contact_forces().impactor_n, 1e-9 * model.contact_forces().impactor_n);
  const auto p = model.contact_pressure();
  EXPECT_GT(p[model.mesh().ring_outer_nodes[0].front()], 0.0);
  EXPECT_THROW(model.ring_extent(3, u), std::invalid_argument);
}

namespace {
double omega_max(ChainModel& model) { return test::chain_omega_max(model); }
}  // namespace

TEST(ChainModel, StableStepBoundsTheHighestFrequency) {
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    for (double press : {0.0, 0.1}) {
      ChainInput in = chain(2, JointKind::Welded, true, 4);
      in.integration = rule;
      in.fixed_target = true;
      ChainModel model(in);
      Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
      u(model.impactor_dof()) = -press * kDepth;
      SystemEvaluation ev;
      model.evaluate(u, true, ev);
      const double truth = omega_max(model);
      const StableStep s = model.stable_step(u);
      const double bound = 2 / s.step_s;
      EXPECT_GE(bound, truth * (1 - 1e-9)) << s.limited_by;
      EXPECT_LE(bound, 2 * truth) << s.limited_by;
      EXPECT_FALSE(s.limited_by.empty());
    }
  }
}

TEST(ChainModel, TwoThreadsGiveTheSerialResult) {
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    ChainInput in = chain(2, JointKind::Free);
    in.fixed_target = true;
    in.integration = rule;
    in.threads = 1;
    ChainModel serial(in);
    in.threads = 2;
    ChainModel threaded(in);
    Eigen::VectorXd u = busy_state(serial, 5);
    for (int step = 0; step < 2; ++step) {
      SystemEvaluation a, b;
      serial.evaluate(u, true, a);
      threaded.evaluate(u, true, b);
      // Bitwise: the same partial sums in the same order.
      EXPECT_EQ(a.force, b.force);
      EXPECT_EQ(a.elastic_energy, b.elastic_energy);
      EXPECT_EQ(Eigen::MatrixXd(serial.tangent_system().matrix()), Eigen::MatrixXd(threaded.tangent_system().matrix()));
      serial.commit(u);
      threaded.commit(u);
      u *= 1.5;  // the next increment starts from the committed configuration
    }
  }
}

TEST(ChainModel, GeometryUpdateEqualsCps8Geometry) {
  ElementCoords x;
  const double c[8][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  for (int k = 0; k < 8; ++k) {
    x(k, 0) = 2e-3 * c[k][0] + 3e-4 * c[k][1] * c[k][1] + 1.0;
    x(k, 1) = 8e-4 * c[k][1] + 1e-4 * c[k][0] * c[k][1] - 0.5;
  }
  ElementCoords x0 = x;
  x0.col(0) *= 1.1;
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective}) {
    Cps8Geometry geo = cps8_geometry(x0, rule, 0.0125);
    Cps8GeometryUpdater(rule).update(x, 0.0125, geo);
    const Cps8Geometry ref = cps8_geometry(x, rule, 0.0125);
    for (int i = 0; i < ref.points; ++i) {
      EXPECT_LT((geo.dndx[i] - ref.dndx[i]).norm(), 1e-12 * ref.dndx[i].norm());
      EXPECT_NEAR(geo.weight[i], ref.weight[i], 1e-14 * ref.weight[i]);
    }
    if (rule == Integration::Selective) {
      for (int r = 0; r < 4; ++r) EXPECT_LT((geo.dndx_reduced[r] - ref.dndx_reduced[r]).norm(), 1e-12 * ref.dndx_reduced[r].norm());
    }
    ElementCoords inverted = x;
    inverted.col(0) *= -1;
    EXPECT_THROW(Cps8GeometryUpdater(rule).update(inverted, 0.0125, geo), std::invalid_argument);
  }
}

TEST(ChainModel, StableStepBoundsAShearedRing) {
  // A ring sheared by x += γ (y − y_c): its elements are skewed up to ~40°, where the
  // shortest edge alone would underestimate the element eigenvalue ~2×. Truth: the
  // assembled elastic stiffness of the unstressed elements on the sheared coordinates.
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    ChainInput in = chain(1, JointKind::Free, false, 4);
    in.integration = rule;
    ChainModel model(in);
    const auto& mesh = model.mesh();
    Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
    for (int n = 0; n < model.dofs() / 2; ++n)
      if (n != mesh.impactor_node) u(2 * n) = 0.8 * mesh.nodes[n].y();
    u(model.impactor_dof()) = 0.02;  // out of the way
    SystemEvaluation ev;
    model.evaluate(u, false, ev);
    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(model.dofs(), model.dofs());
    const J2PlaneStress material(in.material);
    for (const auto& conn : mesh.elements) {
      ElementCoords xe;
      for (int a = 0; a < 8; ++a) xe.row(a) = (mesh.nodes[conn[a]] + Eigen::Vector2d(u(2 * conn[a]), u(2 * conn[a] + 1))).transpose();
      const Cps8Geometry geo = cps8_geometry(xe, rule, in.ring.width_m);
      std::array<PointState, 9> c{}, t{};
      const double du[16] = {};
      Cps8Output out;
      cps8_evaluate(geo, du, c.data(), t.data(), material, true, out);
      for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) k(2 * conn[i / 2] + i % 2, 2 * conn[j / 2] + j % 2) += out.tangent(i, j);
    }
    std::vector<bool> fixed(model.dofs(), false);
    for (int d : model.fixed_dofs()) fixed[d] = true;
    std::vector<int> free;
    for (int d = 0; d < model.dofs(); ++d)
      if (!fixed[d]) free.push_back(d);
    Eigen::MatrixXd a(free.size(), free.size());
    for (std::size_t i = 0; i < free.size(); ++i)
      for (std::size_t j = 0; j < free.size(); ++j)
        a(i, j) = k(free[i], free[j]) / std::sqrt(model.lumped_mass()(free[i]) * model.lumped_mass()(free[j]));
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (a + a.transpose()), Eigen::EigenvaluesOnly);
    const double truth = std::sqrt(eig.eigenvalues().maxCoeff());
    const StableStep s = model.stable_step(u);
    const double bound = 2 / s.step_s;
    EXPECT_GE(bound, truth * (1 - 1e-9)) << s.limited_by;
    EXPECT_LE(bound, 2 * truth) << s.limited_by;
  }
}

TEST(ChainModel, StableStepBoundsACrushedRing) {
  // A ring crushed in one increment by a uniform in-plane compression to 0.75 (the shape
  // measure L²/A does not change): plastic flow thickens the plane-stress wall (λ3 ≈ 1.3),
  // which stiffens every element by λ3 at the same mass. Truth: the assembled tangent of the
  // committed state (elastic, or elastic-plastic at points on the yield surface).
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    ChainInput in = chain(1, JointKind::Free, true, 8);
    in.integration = rule;
    ChainModel model(in);
    const auto& mesh = model.mesh();
    Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
    const double step0 = model.stable_step(u).step_s;
    for (int n = 0; n < model.dofs() / 2; ++n)
      if (n != mesh.impactor_node) u.segment<2>(2 * n) = -0.25 * mesh.nodes[n];
    u(model.impactor_dof()) = 0.02;  // out of the way
    SystemEvaluation ev;
    model.evaluate(u, false, ev);
    model.commit(u);
    model.evaluate(u, true, ev);  // zero increment: the tangent of the committed state
    const double truth = omega_max(model);
    const StableStep s = model.stable_step(u);
    EXPECT_GE(2 / s.step_s, truth * (1 - 1e-9)) << s.limited_by;
    EXPECT_LE(2 / s.step_s, 2 * truth) << s.limited_by;
    // The thickening shortens the step by about √λ3 (the bound before this change did not).
    EXPECT_LT(s.step_s, step0 / 1.08);
  }
}

TEST(ChainModel, TangentWithInnerWallContactMatchesFiniteDifferences) {
  // A ring squeezed flat until its inner walls overlap at the centre (y → y (r − ri − δ)/r,
  // elastic material so that the force is smooth): the inner-wall contact's tangent.
  for (bool half : {true, false}) {
    ChainInput in = chain(1, JointKind::Free, half, 6);
    in.material.hardening = {{1e15, 0.0}};
    ChainModel model(in);
    const auto& mesh = model.mesh();
    Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
    const double ri = in.ring.inner_radius_m, delta = 0.1e-3;
    for (int n = 0; n < model.dofs() / 2; ++n) {
      if (n == mesh.impactor_node) continue;
      const Eigen::Vector2d& p = mesh.nodes[n];
      u(2 * n + 1) = p.y() * (p.norm() - ri - delta) / p.norm() - p.y();
    }
    u(model.impactor_dof()) = 0.02;
    SystemEvaluation ev, ep, em;
    model.evaluate(u, true, ev);
    ASSERT_GT(model.contact_forces().self_n, 0.0) << (half ? "half" : "full");
    SparseSystem& sys = model.tangent_system();
    const Eigen::MatrixXd k = Eigen::MatrixXd(sys.matrix());
    const int nf = sys.free_dofs();
    Eigen::MatrixXd kfd(nf, nf);
    const double h = 1e-8 * kR;
    for (int j = 0; j < nf; ++j) {
      Eigen::VectorXd up = u, um = u;
      up(sys.free_to_dof()[j]) += h;
      um(sys.free_to_dof()[j]) -= h;
      model.evaluate(up, false, ep);
      model.evaluate(um, false, em);
      for (int i = 0; i < nf; ++i) kfd(i, j) = (ep.force(sys.free_to_dof()[i]) - em.force(sys.free_to_dof()[i])) / (2 * h);
    }
    EXPECT_LT((k - kfd).lpNorm<Eigen::Infinity>(), 1e-6 * k.lpNorm<Eigen::Infinity>()) << (half ? "half" : "full");
  }
}
