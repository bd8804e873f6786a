#include "fe/chain/chain_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <thread>

#include "fe/chain/chain_force_sum.hpp"
#include "fe/chain/chain_mesh.hpp"
#include "fe/chain/geometry_update.hpp"
#include "fe/contact/self_contact_taper.hpp"
#include "fe/element/bulk_viscosity.hpp"
#include "fe/contact/ring_pair_contact.hpp"
#include "fe/dynamics/fork_join.hpp"
#include "fe/dynamics/spin_wait.hpp"
#include "fe/dynamics/work_dealer.hpp"
#include "fe/element/cps8_force_lanes.hpp"
#include "fe/contact/penalty_step_cap.hpp"
#include "fe/dynamics/assembled_eigenvalue.hpp"
#include "fe/dof_pair.hpp"
#include "fe/dynamics/explicit_step_end.hpp"
#include "fe/dynamics/element_eigenvalue.hpp"
#include "fe/dynamics/lumped_mass.hpp"
#include "fe/material/j2_plane_stress.hpp"

namespace ringcrush::fe {

namespace {

// A rigid flat face (impactor, target, plate face) against the outer nodes of some rings.
// Gap g = dir · (y_s − y_face): dir = +1 for a face looking up (rings above it: target,
// plate top), −1 for a face looking down (rings below: impactor, plate bottom).
struct RigidFace {
  enum class Kind { Impactor, Target, Plate } kind;
  int body_node = -1;   // −1: fixed in space
  double y_ref = 0;     // reference face position
  double dir = 1;
  std::vector<int> rings;
};

// Shape measure of the element eigenvalue: λ_max ∝ (E/ρ_current)/h² with h the element's
// smallest height, h = A / (longest side), and ρ_current ∝ 1/A at constant mass, so
// λ_max ∝ L_max²/A (sides through their mid-side nodes; A of the 8-node polygon).
double shape_measure(const std::array<int, 8>& conn, const std::vector<Eigen::Vector2d>& x) {
  static constexpr int side[4][3] = {{0, 4, 1}, {1, 5, 2}, {2, 6, 3}, {3, 7, 0}};
  static constexpr int ring[8] = {0, 4, 1, 5, 2, 6, 3, 7};
  double l = 0, area = 0;
  for (const auto& s : side)
    l = std::max(l, (x[conn[s[0]]] - x[conn[s[1]]]).norm() + (x[conn[s[1]]] - x[conn[s[2]]]).norm());
  for (int i = 0; i < 8; ++i) {
    const auto &p = x[conn[ring[i]]], &q = x[conn[ring[(i + 1) % 8]]];
    area += 0.5 * (p.x() * q.y() - q.x() * p.y());
  }
  return area > 0 ? l * l / area : std::numeric_limits<double>::infinity();
}

// Largest out-of-plane stretch λ3 of an element's points (its stiffness scales with it).
double thickness_measure(const PointState* states, int points) {
  double l3 = 0;
  for (int i = 0; i < points; ++i) l3 = std::max(l3, states[i].thickness_stretch);
  return l3;
}

// Elements per lane group and per dealt chunk on two threads (work_dealer.hpp): eight where
// the AVX-512 kernel runs (cps8_force_lanes.hpp), else four. One group per chunk: ≈ 3–5 µs
// of work, long against the shared counter's cost, short against a step.
int lane_group_width() {
  static const int width = cps8_force_wide_lanes_available() ? kCps8WideLanes : kCps8Lanes;
  return width;
}

}  // namespace

struct ChainModel::Impl {
  ChainTopology topo;
  J2PlaneStress material;
  int points_per_element;
  std::vector<Cps8Geometry> geometry;
  std::vector<PointState> committed, trial;
  std::unique_ptr<SparseSystem> system;
  Eigen::VectorXd mass, u_n, u_last;
  bool trial_fresh = false;
  std::vector<Eigen::Vector2d> x;
  // x_n = X + u_n per node: the x of the evaluation that was committed (commit_trial() swaps
  // the two), the same sums as X + u_n formed element by element, so the explicit step's
  // element pass reads one pair per node for the coordinates instead of X and u_n.
  std::vector<Eigen::Vector2d> x_n;
  std::vector<ContactContribution> contributions;
  std::unique_ptr<SurfaceContact> surface;
  std::vector<RigidFace> faces;
  std::vector<double> outer_k, outer_area;  // per local outer node (all rings alike)
  // Element eigenvalue bound: the exact λ_max of each element at its last exact evaluation
  // and the shape measure there; in between λ is scaled with the shape measure.
  std::vector<std::array<double, 8>> element_mass;
  std::vector<double> omega2_exact, shape_exact, thickness_exact;
  // bulk_scale / √omega2_exact per element (the bulk-viscous coefficient b1 ρ c_d L_e), set
  // wherever omega2_exact is: the same quotient as formed at each evaluation before, without
  // a square root and a division per element and step.
  std::vector<double> bulk_coefficient;
  void set_omega2(std::size_t e, double omega2) {
    omega2_exact[e] = omega2;
    bulk_coefficient[e] = bulk_scale / std::sqrt(omega2);
  }
  MassScalingReport scaling;  // element_mass and omega2_exact are the scaled ones
  std::vector<Eigen::Vector2d> x_bound;  // current coordinates (stable_step)
  // The element part of the last stable_step() (ω² and what set it), reused by
  // contact_stable_step().
  double element_omega2 = 0;
  std::string element_limited_by;
  // StepBound::Assembled: K_e at the last exact evaluation, its scale since, the estimator.
  std::vector<ElementMatrix> stiffness_exact;
  std::vector<double> stiffness_scale;
  std::unique_ptr<AssembledEigenvalue> assembled;
  long assembled_calls = 0, assembled_iterations = 0, assembled_fallbacks = 0;
  std::unique_ptr<AssembledEigenvalue> elements_only;  // elements_only_assembled_omega2()
  std::vector<std::array<int, 16>> element_dofs;
  Eigen::VectorXd inv_sqrt_mass;
  StepParts parts;
  ChainContactForces forces;
  std::vector<std::pair<int, double>> pressure;
  double penalty_scale = 1;  // contact.penalty_scale, lowered by contact_penalty_step_fraction
  double face_near_omega2 = 0, surface_near_omega2 = 0;
  int face_near_node = -1, surface_near_node = -1;
  std::vector<std::array<double, 4>> ring_box;  // per ring: outer node box (lo x, hi x, lo y, hi y)
  SystemEvaluation scratch;
  // Bulk viscosity: the step the next increment is taken over (0: off) and 2 b1 E/(1 − ν²),
  // which over ω_e is the element's coefficient b1 ρ c_d L_e with L_e = 2 c_d / ω_e.
  double increment_time = 0, bulk_scale = 0;
  Cps8GeometryUpdater updater;
  double width;
  // Two threads: the caller does the contact, both do elements; the element sums are formed
  // in two fixed halves, [0, split) into the caller's buffers and [split, ne) into the
  // helper's (fixed order: the sums, hence the results, do not depend on timing).
  std::unique_ptr<ForkJoin> fork;
  int split = 0;
  Eigen::VectorXd helper_force, helper_viscous;
  // The dofs [helper_lo, helper_lo + helper_len) of the nodes of elements [split, ne): the
  // only ones their sums touch, so the only ones zeroed and added (elsewhere helper_force and
  // helper_viscous stay +0.0, and adding +0.0 to a sum that started at +0.0 changes no bit).
  // With two threads these vectors are written by the helper and read by the caller: on a VM
  // whose cores exchange cache lines slowly, every line not moved counts (README session 12).
  Eigen::Index helper_lo = 0, helper_len = 0;
  void zero_helper_sums(bool viscous) {
    helper_force.segment(helper_lo, helper_len).setZero();
    if (viscous) helper_viscous.segment(helper_lo, helper_len).setZero();
  }
  // commit() moved x_n (++xn_epoch): an element's stored geometry is on x_n when its epoch
  // equals xn_epoch; otherwise it is re-derived in the next element pass that reads it — or,
  // in the force-only lane pass, formed inside the kernel and not stored at all
  // (cps8_force_lanes_on_coords(); the epoch then stays behind).
  std::vector<unsigned> geometry_epoch;
  unsigned xn_epoch = 0;
  std::vector<ElementMatrix> tangents;  // want_tangent with two threads: scattered after the join
  // Force-only pass with two threads: the elements dealt in chunks, each into its slot.
  WorkDealer dealer;
  // ... and the contact passes' searches (deal_contact), once the caller has begun the
  // contact (contact_ready).
  WorkDealer contact_dealer;
  std::atomic<bool> contact_ready{false};
  std::vector<ElementVector> slot_force, slot_viscous;
  std::vector<std::array<double, 2>> slot_energy;  // elastic energy, plastic work

  explicit Impl(const ChainInput& in)
      : topo(make_chain_topology(in)),
        material(in.material),
        points_per_element(in.integration == Integration::Reduced ? 4 : 9),
        bulk_scale(2 * in.bulk_viscosity * in.material.youngs_modulus_pa /
                   (1 - in.material.poisson_ratio * in.material.poisson_ratio)),
        updater(in.integration),
        width(in.ring.width_m) {}

  // Elements [e0, e1): force into `force` (all dofs), energies returned; the tangent goes
  // straight into the system (serial) or into `tangents` (threads). Two things ride along in
  // the same pass over the elements, so that they are split over the threads too and each
  // element is touched once per evaluation (performance, DESIGN.md):
  //  - the geometry on x_n when a commit has moved it (geometry_epoch; commit() only marks
  //    it: the element is re-referenced just before its first evaluation of the increment);
  //  - the bulk-viscous force of the increment (bulk_viscosity.hpp) into `viscous` (all
  //    dofs; null when off): b1 ρ c_d L_e with L_e = 2 c_d / ω_e, ω_e the element eigenvalue.
  void elements(int e0, int e1, const Eigen::VectorXd& u, bool want_tangent, bool store_tangent, double* force,
                double* viscous, double& elastic, double& plastic) {
    Cps8Output eo;
    ElementVector fv;
    elastic = plastic = 0;
    int e = e0;
    if (!want_tangent) {
      // Force only: eight or four elements at a time on vector lanes (cps8_force_lanes.hpp),
      // summed in element order as below; then a group of four, the remainder element by
      // element (bitwise the same kernel at every width).
      const auto sum = [&](int b, const auto& g) {
        for (int l = 0; l < static_cast<int>(g.out.size()); ++l) {
          scatter(b + l, g.out[l].force, g.viscous[l], force, viscous);
          elastic += g.out[l].elastic_energy;
          plastic += g.out[l].plastic_work;
        }
      };
      lane_groups(e, e1, viscous != nullptr, u, sum);
    }
    for (; e < e1; ++e) {
      evaluate_element(e, u, want_tangent, viscous != nullptr, eo, fv);
      scatter(e, eo.force, fv, force, viscous);
      elastic += eo.elastic_energy;
      plastic += eo.plastic_work;
      if (want_tangent) {
        if (store_tangent) tangents[e] = eo.tangent;
        else system->add_element(e, eo.tangent.data());
      }
    }
  }

  // Element e alone: force, energies (and tangent) into eo, its bulk-viscous force into fv
  // (viscous), after re-deriving its geometry on x_n when a commit has moved it.
  void evaluate_element(int e, const Eigen::VectorXd& u, bool want_tangent, bool viscous, Cps8Output& eo,
                        ElementVector& fv) {
    if (geometry_epoch[e] != xn_epoch) regeometry(e, e + 1, u_n);
    const auto& conn = topo.mesh.elements[e];
    double ue[16];
    for (int a = 0; a < 8; ++a) {
      ue[2 * a] = u(2 * conn[a]) - u_n(2 * conn[a]);
      ue[2 * a + 1] = u(2 * conn[a] + 1) - u_n(2 * conn[a] + 1);
    }
    const std::size_t p0 = static_cast<std::size_t>(e) * points_per_element;
    if (viscous) {
      fv.setZero();
      const double coefficient = bulk_coefficient[e];
      if (want_tangent) {
        cps8_evaluate(geometry[e], ue, &committed[p0], &trial[p0], material, true, eo);
        add_bulk_viscous_force(geometry[e], ue, increment_time, coefficient, fv);
      } else {
        const BulkViscousLoad load{coefficient, increment_time, &fv};
        cps8_force(geometry[e], ue, &committed[p0], &trial[p0], material, eo, &load);
      }
    } else {
      cps8_evaluate(geometry[e], ue, &committed[p0], &trial[p0], material, want_tangent, eo);
    }
  }

  // Elements [e, e + W) force only on vector lanes (cps8_force_lanes.hpp), W = 8 or 4:
  // bitwise evaluate_element() on each. A geometry not on x_n is formed inside the kernel from
  // the coordinates and not stored (the explicit step: once per step, README session 9); where
  // the kernel cannot (no AVX2, an inverted element), it is updated and stored first as before.
  template <int W>
  struct LaneResults {
    std::array<Cps8Output, W> out;
    std::array<ElementVector, W> viscous;
  };
  template <int W>
  void evaluate_lanes(int e, const Eigen::VectorXd& u, bool viscous, LaneResults<W>& r) {
    bool stale = false;
    for (int l = 0; l < W; ++l) stale = stale || geometry_epoch[e + l] != xn_epoch;
    double ue[W][16];
    std::array<ElementCoords, W> xe;
    std::array<BulkViscousLoad, W> load;
    Cps8LaneGroupOf<W> group;
    for (int l = 0; l < W; ++l) {
      if (stale) gather_increment(e + l, u, ue[l], &xe[l]);
      else gather_increment(e + l, u, ue[l], nullptr);
      const std::size_t p0 = static_cast<std::size_t>(e + l) * points_per_element;
      group[l] = Cps8Lane{&geometry[e + l], ue[l], &committed[p0], &trial[p0], &r.out[l], nullptr};
      if (viscous) {
        r.viscous[l].setZero();
        load[l] = BulkViscousLoad{bulk_coefficient[e + l], increment_time, &r.viscous[l]};
        group[l].viscous = &load[l];
      }
    }
    if (stale) {
      std::array<const ElementCoords*, W> x_lanes;
      for (int l = 0; l < W; ++l) x_lanes[l] = &xe[l];
      if (cps8_force_lanes_on_coords(group, updater.tables(), x_lanes, width, material)) return;
      for (int h = 0; h < W; h += kCps8Lanes) regeometry_lanes(e + h, u_n);
    }
    cps8_force_lanes(group, material);
  }
  // Force only on [e, e1): groups of lane_group_width(), then of four, on vector lanes, each
  // group's results handed to use(first element, LaneResults) in element order; e is left at
  // the first element of the remainder (fewer than four), for the caller to do one by one.
  template <class Use>
  void lane_groups(int& e, int e1, bool viscous, const Eigen::VectorXd& u, const Use& use) {
    if (lane_group_width() == kCps8WideLanes) {
      LaneResults<kCps8WideLanes> g;
      for (; e + kCps8WideLanes <= e1; e += kCps8WideLanes) {
        evaluate_lanes(e, u, viscous, g);
        use(e, g);
      }
    }
    LaneResults<kCps8Lanes> g;
    for (; e + kCps8Lanes <= e1; e += kCps8Lanes) {
      evaluate_lanes(e, u, viscous, g);
      use(e, g);
    }
  }

  // Element e's increments u − u_n (16, dof order) and, when xe is given, its node
  // coordinates x_n (from x_n, = X + u_n as regeometry() forms them): one pass over its nodes.
  void gather_increment(int e, const Eigen::VectorXd& u, double* du, ElementCoords* xe) const {
    const auto& conn = topo.mesh.elements[e];
    const double *pu = u.data(), *pn = u_n.data();
    for (int a = 0; a < 8; ++a) {
      const std::size_t d = 2 * static_cast<std::size_t>(conn[a]);
      store_dof_pair(du + 2 * a, load_dof_pair(pu + d) - load_dof_pair(pn + d));
      if (xe) {
        const Eigen::Vector2d& p = x_n[static_cast<std::size_t>(conn[a])];
        (*xe)(a, 0) = p.x();
        (*xe)(a, 1) = p.y();
      }
    }
  }

  // Element e's force (and bulk-viscous force, viscous non-null) added into the global
  // vectors, node by node: per dof the one addition of the element to the sum.
  void scatter(int e, const ElementVector& fe, const ElementVector& qe, double* force, double* viscous) const {
    const auto& conn = topo.mesh.elements[e];
    for (int a = 0; a < 8; ++a) {
      const std::size_t d = 2 * static_cast<std::size_t>(conn[a]);
      store_dof_pair(force + d, load_dof_pair(force + d) + load_dof_pair(fe.data() + 2 * a));
      if (viscous) store_dof_pair(viscous + d, load_dof_pair(viscous + d) + load_dof_pair(qe.data() + 2 * a));
    }
  }

  // Force-only pass on two threads (work_dealer.hpp): both threads take chunks of elements
  // into their slots — the caller from the front, the helper from the back (`from_back`),
  // so that each computes nearly the same elements every step and mostly those of the half
  // it sums — then each sums one of the two fixed halves in element order — the
  // caller [0, split) into force, the helper [split, ne) into helper_force — exactly the sums
  // elements() forms on one thread, so the result is bitwise the one-thread result whichever
  // thread computed which element.
  void deal(const Eigen::VectorXd& u, bool viscous, bool from_back) {
    Cps8Output eo;
    ElementVector fv;
    int b = 0, end = 0;
    try {
      const auto store = [&](int first, const auto& g) {
        for (int l = 0; l < static_cast<int>(g.out.size()); ++l) {
          slot_force[first + l] = g.out[l].force;
          if (viscous) slot_viscous[first + l] = g.viscous[l];
          slot_energy[first + l] = {g.out[l].elastic_energy, g.out[l].plastic_work};
        }
      };
      while (from_back ? dealer.next_back(b, end) : dealer.next(b, end)) {
        int e = b;
        lane_groups(e, end, viscous, u, store);
        for (; e < end; ++e) {
          evaluate_element(e, u, false, viscous, eo, fv);
          slot_force[e] = eo.force;
          if (viscous) slot_viscous[e] = fv;
          slot_energy[e] = {eo.elastic_energy, eo.plastic_work};
        }
        dealer.done(end - b);
      }
    } catch (...) {
      dealer.fail();
      throw;
    }
  }
  // The searches of the contact passes with candidates (SurfaceContact::search), dealt one
  // pass at a time to whichever thread asks: each pass writes only its own results, which
  // SurfaceContact::finish sums in pass order, so the dealing does not change a bit.
  void deal_contact() {
    const auto& busy = surface->busy_passes();
    int b = 0, end = 0;
    try {
      while (contact_dealer.next(b, end)) {
        for (int i = b; i < end; ++i) surface->search(static_cast<std::size_t>(busy[i]), x);
        contact_dealer.done(end - b);
      }
    } catch (...) {
      contact_dealer.fail();
      throw;
    }
  }
  // Sums the slots of [e0, e1) once every element is done; false if the other thread failed
  // (ForkJoin then rethrows its exception).
  bool sum_slots(int e0, int e1, double* force, double* viscous, double& elastic, double& plastic) const {
    if (!dealer.wait_all()) return false;
    elastic = plastic = 0;
    for (int e = e0; e < e1; ++e) {
      scatter(e, slot_force[e], slot_viscous[e], force, viscous);
      elastic += slot_energy[e][0];
      plastic += slot_energy[e][1];
    }
    return true;
  }

  // Geometry of elements [e0, e1) on the configuration X + u (kinematics.hpp).
  void regeometry(int e0, int e1, const Eigen::VectorXd& u) {
    const auto& mesh = topo.mesh;
    for (int e = e0; e < e1; ++e) {
      ElementCoords xe;
      for (int a = 0; a < 8; ++a) {
        const int n = mesh.elements[e][a];
        xe(a, 0) = mesh.nodes[n].x() + u(2 * n);
        xe(a, 1) = mesh.nodes[n].y() + u(2 * n + 1);
      }
      try {
        updater.update(xe, width, geometry[e]);
      } catch (const std::invalid_argument& err) {
        throw std::runtime_error(fmt::format("element {} (ring {}): {}", e + 1, mesh.element_ring[e] + 1, err.what()));
      }
      geometry_epoch[e] = xn_epoch;
    }
  }

  // Node coordinates X + u of elements [e, e + W), as regeometry() forms them.
  template <std::size_t W>
  void coordinates_lanes(int e, const Eigen::VectorXd& u, std::array<ElementCoords, W>& xe) const {
    const auto& mesh = topo.mesh;
    for (int l = 0; l < static_cast<int>(W); ++l)
      for (int a = 0; a < 8; ++a) {
        const int n = mesh.elements[e + l][a];
        xe[l](a, 0) = mesh.nodes[n].x() + u(2 * n);
        xe[l](a, 1) = mesh.nodes[n].y() + u(2 * n + 1);
      }
  }

  // regeometry(e, e + 4, u) on vector lanes (Cps8GeometryUpdater::update_lanes, bitwise); an
  // inverted element is reported by regeometry(), with its number.
  void regeometry_lanes(int e, const Eigen::VectorXd& u) {
    std::array<ElementCoords, kCps8Lanes> xe;
    coordinates_lanes(e, u, xe);
    try {
      updater.update_lanes({&xe[0], &xe[1], &xe[2], &xe[3]}, width,
                           {&geometry[e], &geometry[e + 1], &geometry[e + 2], &geometry[e + 3]});
    } catch (const std::invalid_argument&) {
      regeometry(e, e + kCps8Lanes, u);
    }
    for (int l = 0; l < kCps8Lanes; ++l) geometry_epoch[e + l] = xn_epoch;
  }

  struct ElementJob {
    Impl* model;
    const Eigen::VectorXd* u;
    bool want_tangent;
    bool viscous;
    double elastic = 0, plastic = 0;
    static void run(void* p) {
      auto& j = *static_cast<ElementJob*>(p);
      auto& m = *j.model;
      m.zero_helper_sums(j.viscous);
      const int ne = static_cast<int>(m.topo.mesh.elements.size());
      if (!j.want_tangent) {
        m.deal(*j.u, j.viscous, true);
        // The contact passes the caller has not taken yet (once it has begun the contact).
        for (unsigned turn = 0; !m.contact_ready.load(std::memory_order_acquire);) spin_wait_turn(turn);
        m.deal_contact();
        m.sum_slots(m.split, ne, m.helper_force.data(), j.viscous ? m.helper_viscous.data() : nullptr, j.elastic,
                    j.plastic);
        return;
      }
      m.elements(m.split, ne, *j.u, j.want_tangent, true,
                 m.helper_force.data(), j.viscous ? m.helper_viscous.data() : nullptr, j.elastic, j.plastic);
    }
  };
};



ChainModel::ChainModel(const ChainInput& input) : input_(input) {
  impl_ = std::make_unique<Impl>(input);
  Impl& m = *impl_;
  mesh_ = m.topo.mesh;
  const int nodes = static_cast<int>(mesh_.nodes.size());
  const int ne = static_cast<int>(mesh_.elements.size());
  m.u_n = Eigen::VectorXd::Zero(2 * nodes);
  m.u_last = m.u_n;
  m.x.resize(nodes);
  m.x_n.resize(nodes);
  for (int i = 0; i < nodes; ++i) m.x_n[i] = mesh_.nodes[i] + Eigen::Vector2d(m.u_n(2 * i), m.u_n(2 * i + 1));
  m.committed.assign(static_cast<std::size_t>(ne) * m.points_per_element, PointState{});
  m.trial = m.committed;
  m.system = std::make_unique<SparseSystem>(nodes, m.topo.fixed_dofs, mesh_.elements);
  m.ring_box.resize(input.rings);

  // Lumped mass: HRZ per element (a half ring's elements are the half ring); rigid bodies
  // carry the model's share of their mass (half in a half model), on both dofs.
  const double share = 1.0 / symmetry_factor();
  m.mass = Eigen::VectorXd::Zero(2 * nodes);
  m.geometry.resize(ne);
  m.geometry_epoch.assign(ne, m.xn_epoch);  // cps8_geometry() below: on x_0
  m.element_mass.resize(ne);
  m.omega2_exact.resize(ne);
  m.bulk_coefficient.resize(ne);
  m.shape_exact.resize(ne);
  m.thickness_exact.assign(ne, 1.0);
  // Mass scaling (explicit, opt-in, mass_scaling.hpp) needs the element's stiffness again.
  const bool scaling = input.mass_scaling.active();
  std::vector<ElementMatrix> k_scaling;
  for (int e = 0; e < ne; ++e) {
    ElementCoords xe;
    for (int a = 0; a < 8; ++a) xe.row(a) = mesh_.nodes[mesh_.elements[e][a]].transpose();
    m.element_mass[e] = hrz_lumped_mass(xe, input.density_kg_m3, input.ring.width_m);
    m.geometry[e] = cps8_geometry(xe, input.integration, input.ring.width_m);
    const ElementMatrix k = element_elastic_stiffness(xe, input.integration, input.ring.width_m, m.material);
    m.set_omega2(e, element_max_eigenvalue(k, m.element_mass[e]));
    if (input.step_bound == StepBound::Assembled) m.stiffness_exact.push_back(k);
    if (scaling) k_scaling.push_back(k);
    m.shape_exact[e] = shape_measure(mesh_.elements[e], mesh_.nodes);
  }
  // The element's own step as the driver takes it: safety and the bulk-viscosity reduction
  // of contact_stable_step() included (mass_scaling.hpp). Off: nothing is touched.
  const double xi = input.bulk_viscosity;
  m.scaling = scale_element_masses(input.mass_scaling, input.mass_scaling.safety * (std::sqrt(1 + xi * xi) - xi),
                                   m.element_mass, m.omega2_exact);
  // λ_max of a scaled element from its eigenproblem, as every later re-bound computes it.
  for (int e = 0; scaling && e < ne; ++e)
    if (m.scaling.element_scale[e] != 1.0) m.set_omega2(e, element_max_eigenvalue(k_scaling[e], m.element_mass[e]));
  // scale_element_masses() rescaled omega2_exact in place: the coefficients follow it.
  for (int e = 0; e < ne; ++e) m.set_omega2(e, m.omega2_exact[e]);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 8; ++a) {
      m.mass(2 * mesh_.elements[e][a]) += m.element_mass[e][a];
      m.mass(2 * mesh_.elements[e][a] + 1) += m.element_mass[e][a];
    }
  m.mass(2 * mesh_.impactor_node) = m.mass(2 * mesh_.impactor_node + 1) = share * input.impactor_mass_kg;
  for (int p : mesh_.plate_nodes) m.mass(2 * p) = m.mass(2 * p + 1) = share * input.plate_mass_kg;
  if (input.step_bound == StepBound::Assembled) {
    // M^{-1/2} on the free dofs.
    Eigen::VectorXd inv_sqrt = Eigen::VectorXd::Zero(2 * nodes);
    std::vector<std::array<int, 16>> dofs(ne);
    for (int e = 0; e < ne; ++e)
      for (int a = 0; a < 8; ++a) {
        const int n = mesh_.elements[e][a];
        dofs[e][2 * a] = 2 * n;
        dofs[e][2 * a + 1] = 2 * n + 1;
        inv_sqrt(2 * n) = 1 / std::sqrt(m.mass(2 * n));
        inv_sqrt(2 * n + 1) = 1 / std::sqrt(m.mass(2 * n + 1));
      }
    // The rigid bodies (impactor, plates) have no element stiffness but their contact
    // springs load them.
    inv_sqrt(2 * mesh_.impactor_node + 1) = 1 / std::sqrt(m.mass(2 * mesh_.impactor_node + 1));
    for (int p : mesh_.plate_nodes) inv_sqrt(2 * p + 1) = 1 / std::sqrt(m.mass(2 * p + 1));
    for (int d : m.topo.fixed_dofs) inv_sqrt(d) = 0;
    m.stiffness_scale.assign(ne, 1.0);
    m.element_dofs = dofs;
    m.inv_sqrt_mass = inv_sqrt;
    m.assembled = std::make_unique<AssembledEigenvalue>(std::move(dofs), std::move(inv_sqrt));
  }

  // Contact: penalty per outer node as RingContact (penalty_scale · E · w · L / h).
  const RingMesh& r = m.topo.ring;
  m.penalty_scale = input.contact.penalty_scale;
  std::vector<int> all_rings(input.rings);
  for (int i = 0; i < input.rings; ++i) all_rings[i] = i;
  m.faces.push_back({RigidFace::Kind::Impactor, mesh_.impactor_node, mesh_.nodes[mesh_.impactor_node].y(), -1.0, all_rings});
  if (input.fixed_target) m.faces.push_back({RigidFace::Kind::Target, -1, m.topo.target_y, 1.0, all_rings});
  for (std::size_t k = 0; k < mesh_.plate_nodes.size(); ++k) {
    const int node = mesh_.plate_nodes[k];
    const double yc = mesh_.nodes[node].y(), half = m.topo.plate_half_thickness;
    std::vector<int> above, below;
    for (int i = 0; i < input.rings; ++i) (i <= static_cast<int>(k) ? above : below).push_back(i);
    m.faces.push_back({RigidFace::Kind::Plate, node, yc + half, 1.0, above});
    m.faces.push_back({RigidFace::Kind::Plate, node, yc - half, -1.0, below});
  }
  std::vector<ContactPass> passes;
  auto penalties = [&] {  // every contact spring at m.penalty_scale
    const double k_scale = m.penalty_scale * input.material.youngs_modulus_pa * input.ring.width_m / r.element_depth;
    m.outer_k.clear();
    m.outer_area.clear();
    for (double w : r.outer_weight) {
      m.outer_k.push_back(k_scale * w);
      m.outer_area.push_back(w * input.ring.width_m);
    }
    passes.clear();
    for (int i = 0; i < input.rings; ++i)
      for (int j = 0; j < input.rings; ++j)
        if (i != j)
          passes.push_back(outer_pass(r, m.topo.ring_node[i], i, m.topo.ring_node[j], j, k_scale, input.ring.width_m,
                                      input.contact.smoothing));
    if (input.contact.self_contact)
      for (int i = 0; i < input.rings; ++i)
        for (auto& p : inner_wall_passes(r, m.topo.ring_node[i], i, k_scale, input.ring.width_m, input.contact.smoothing,
                                         input.contact.self_contact_min_separation_rad,
                                         kSelfContactTaperBandRad,
                                         input.contact.self_contact_two_pass))
          passes.push_back(std::move(p));
  };
  penalties();
  if (input.contact_penalty_step_fraction > 0) {
    // The penalty that costs at most the set fraction of the element step
    // (penalty_step_cap.hpp): the stiffest spring of the model as the bound counts it, on the
    // rigid faces and on the surfaces, against the largest element eigenvalue at t = 0.
    double spring = surface_spring_omega2(passes, m.mass);
    for (const RigidFace& face : m.faces) {
      const double inv_body = face.body_node >= 0 ? 1.0 / m.mass(2 * face.body_node + 1) : 0.0;
      for (int ring : face.rings)
        for (std::size_t i = 0; i < r.outer_nodes.size(); ++i) {
          const int node = m.topo.ring_node[ring][r.outer_nodes[i]];
          spring = std::max(spring, m.outer_k[i] * (1.0 / m.mass(2 * node + 1) + inv_body));
        }
    }
    const double element = *std::max_element(m.omega2_exact.begin(), m.omega2_exact.end());
    const double factor = penalty_step_factor(input.contact_penalty_step_fraction, element, spring);
    if (factor < 1) {
      m.penalty_scale *= factor;
      penalties();
    }
  }
  m.surface = std::make_unique<SurfaceContact>(std::move(passes), r.element_depth,
                                               input.contact.arrival_depth * r.element_depth);
  m.surface->set_mass(m.mass);
  // Threads: automatic = two when the machine has two cores that are not already busy (on
  // an oversubscribed machine the fork-join waits on the scheduler and runs slower than
  // one thread) and the chain is big enough to pay for the join (~1 µs).
  bool two = input.threads == 2;
  if (input.threads == 0 && std::thread::hardware_concurrency() >= 2 && ne >= 64) {
    double load[1] = {0};
    two = getloadavg(load, 1) == 1 && load[0] < std::thread::hardware_concurrency() - 0.5;
  }
  // The two partial sums [0, split), [split, ne) of the element pass (the same on one thread
  // or two). With the tangent the caller, which also does the contact, computes [0, split)
  // and the helper the rest; force only, the elements are dealt (work_dealer.hpp) and the
  // split only fixes the order of the sums.
  m.split = static_cast<int>(0.45 * ne);
  m.helper_force = Eigen::VectorXd::Zero(2 * nodes);
  m.helper_viscous = Eigen::VectorXd::Zero(2 * nodes);
  if (m.split < ne) {
    int lo = nodes, hi = -1;
    for (int e = m.split; e < ne; ++e)
      for (int n : mesh_.elements[e]) {
        lo = std::min(lo, n);
        hi = std::max(hi, n);
      }
    m.helper_lo = 2 * static_cast<Eigen::Index>(lo);
    m.helper_len = 2 * static_cast<Eigen::Index>(hi + 1 - lo);
  }
  if (two) {
    m.fork = std::make_unique<ForkJoin>();
    m.slot_force.resize(ne);
    m.slot_viscous.resize(ne);
    m.slot_energy.resize(ne);
    if (m.assembled) m.assembled->use_threads(m.fork.get());  // its power iteration on both threads
  }
  m.contributions.reserve(256);
  m.pressure.reserve(256);
}

ChainModel::~ChainModel() = default;

int ChainModel::dofs() const { return 2 * static_cast<int>(mesh_.nodes.size()); }
const std::vector<int>& ChainModel::fixed_dofs() const { return impl_->topo.fixed_dofs; }
const Eigen::VectorXd& ChainModel::lumped_mass() const { return impl_->mass; }
const MassScalingReport& ChainModel::mass_scaling() const { return impl_->scaling; }
const std::array<double, 8>& ChainModel::element_mass(int e) const {
  if (e < 0 || e >= static_cast<int>(impl_->element_mass.size()))
    throw std::invalid_argument(fmt::format("ChainModel::element_mass: element {} of {}", e, impl_->element_mass.size()));
  return impl_->element_mass[static_cast<std::size_t>(e)];
}
SparseSystem& ChainModel::tangent_system() { return *impl_->system; }
const ChainContactForces& ChainModel::contact_forces() const { return impl_->forces; }

const ContactArrival& ChainModel::contact_arrival() const { return impl_->surface->arrival(); }

double ChainModel::contact_depth() const { return impl_->topo.ring.element_depth; }

Eigen::VectorXd ChainModel::initial_velocity() const {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(dofs());
  v(impactor_dof()) = -input_.impactor_velocity_m_s;  // the chain lies below (−y)
  return v;
}

void ChainModel::evaluate(const Eigen::VectorXd& u, bool want_tangent, SystemEvaluation& out) {
  evaluate_ending(u, want_tangent, out, nullptr);
}

void ChainModel::evaluate_explicit(const Eigen::VectorXd& u, SystemEvaluation& out, ExplicitStepEnd& end) {
  evaluate_ending(u, false, out, &end);
}

void ChainModel::evaluate_ending(const Eigen::VectorXd& u, bool want_tangent, SystemEvaluation& out,
                                 ExplicitStepEnd* end) {
  Impl& m = *impl_;
  if (u.size() != dofs()) throw std::invalid_argument(fmt::format("ChainModel::evaluate: u has {} values, expected {}", u.size(), dofs()));
  // Until this evaluation is complete the trial states are those of no u (commit() re-evaluates).
  m.trial_fresh = false;
  double contact_energy = 0, contact_time = 0;
  // --- contact (the rigid faces and the list on the calling thread, while the helper runs
  // elements; the passes' searches dealt to both threads; the sums on the caller) ----------
  auto contact_begin = [&] {
    const auto t0 = std::chrono::steady_clock::now();
    // The evaluated u is kept for commit() (u_last) in the same pass over u as the coordinates
    // (here the helper is computing elements, not at the serial end of the step).
    const std::size_t nn = mesh_.nodes.size();
    for (std::size_t i = 0; i < nn; ++i) {
      const double ux = u(2 * i), uy = u(2 * i + 1);
      m.x[i] = mesh_.nodes[i] + Eigen::Vector2d(ux, uy);
      m.u_last(2 * i) = ux;
      m.u_last(2 * i + 1) = uy;
    }
    m.contributions.clear();
    m.pressure.clear();
    ChainContactForces& cf = m.forces;
    cf = ChainContactForces{};
    const double depth = m.topo.ring.element_depth;
    for (int i = 0; i < input_.rings; ++i) {
      auto& b = m.ring_box[i];
      b = {1e300, -1e300, 1e300, -1e300};
      for (int n : mesh_.ring_outer_nodes[i]) {
        b[0] = std::min(b[0], m.x[n].x()); b[1] = std::max(b[1], m.x[n].x());
        b[2] = std::min(b[2], m.x[n].y()); b[3] = std::max(b[3], m.x[n].y());
      }
    }
    for (int i = 0; i < input_.rings; ++i)
      for (int j = i + 1; j < input_.rings; ++j) {
        const auto &a = m.ring_box[i], &b = m.ring_box[j];
        if (a[0] - depth <= b[1] && b[0] - depth <= a[1] && a[2] - depth <= b[3] && b[2] - depth <= a[3]) ++cf.pairs_checked;
      }
    m.face_near_omega2 = 0;
    m.face_near_node = -1;
    const RingMesh& r = m.topo.ring;
    for (const RigidFace& face : m.faces) {
      const double y_face = face.y_ref + (face.body_node >= 0 ? u(2 * face.body_node + 1) : 0.0);
      const double inv_body = face.body_node >= 0 ? 1.0 / m.mass(2 * face.body_node + 1) : 0.0;
      for (int ring : face.rings) {
        const auto& b = m.ring_box[ring];
        // Broad phase: the ring's outer box against the face, one element depth of margin.
        if (face.dir > 0 ? b[2] > y_face + depth : b[3] < y_face - depth) continue;
        const auto& map = m.topo.ring_node[ring];
        for (std::size_t i = 0; i < r.outer_nodes.size(); ++i) {
          const int node = map[r.outer_nodes[i]];
          const double gap = face.dir * (m.x[node].y() - y_face);
          if (gap >= depth) continue;
          const double k = m.outer_k[i];
          const double w2 = k * (1.0 / m.mass(2 * node + 1) + inv_body);
          if (w2 > m.face_near_omega2) { m.face_near_omega2 = w2; m.face_near_node = node; }
          if (gap >= 0) continue;
          // Energy ½ k g²: ∂/∂y_s = k g dir, ∂/∂y_face = −k g dir.
          ContactContribution& c = m.contributions.emplace_back();
          c.nodes[0] = node;
          c.force(1) = k * gap * face.dir;
          c.stiffness = k;
          c.gap = gap;
          if (face.body_node >= 0) {
            c.count = 2;
            c.nodes[1] = face.body_node;
            c.force(3) = -k * gap * face.dir;
            if (want_tangent) {
              c.tangent(1, 1) = c.tangent(3, 3) = k;
              c.tangent(1, 3) = c.tangent(3, 1) = -k;
            }
          } else {
            c.count = 1;
            if (want_tangent) c.tangent(1, 1) = k;
          }
          const double fn = -k * gap;
          if (face.kind == RigidFace::Kind::Impactor) cf.impactor_n += fn;
          if (face.kind == RigidFace::Kind::Target) cf.target_n += fn;
          contact_energy += 0.5 * k * gap * gap;
          if (-gap > cf.max_penetration_m) {
            cf.max_penetration_m = -gap;
            cf.deepest_node = node;
            cf.deepest_into = face.kind == RigidFace::Kind::Impactor ? ChainContactForces::Surface::Impactor
                              : face.kind == RigidFace::Kind::Target ? ChainContactForces::Surface::Target
                                                                     : ChainContactForces::Surface::Plate;
          }
          ++cf.active;
          m.pressure.emplace_back(node, fn / m.outer_area[i]);
        }
      }
    }
    m.surface->begin(m.x);
    contact_time += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  auto contact_finish = [&] {
    const auto t0 = std::chrono::steady_clock::now();
    ChainContactForces& cf = m.forces;
    SurfaceContactState ss;
    m.surface->finish(m.x, want_tangent, m.contributions, &m.pressure, ss);
    cf.ring_ring_n = ss.ring_ring_force;
    cf.candidate_pairs = static_cast<long>(m.surface->candidates());
    cf.list_rebuilds = m.surface->rebuilds();
    cf.self_n = ss.self_force;
    cf.active += ss.active;
    if (ss.max_penetration > cf.max_penetration_m) {
      cf.max_penetration_m = ss.max_penetration;
      cf.deepest_node = ss.deepest_node;
      cf.deepest_into = ss.deepest_self ? ChainContactForces::Surface::OwnInnerWall : ChainContactForces::Surface::RingOuter;
      cf.deepest_ring = ss.deepest_master_ring;
    }
    contact_energy += ss.energy;
    for (const auto& c : m.contributions)  // FNV-1a over the slave nodes, in the (fixed) search order
      cf.active_set = (cf.active_set ^ static_cast<std::uint64_t>(c.nodes[0] + 1)) * 1099511628211ULL;
    m.surface_near_omega2 = ss.near_omega2;
    m.surface_near_node = ss.near_node;
    contact_time += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  auto contact = [&] {  // all of it on this thread
    contact_begin();
    const auto t0 = std::chrono::steady_clock::now();
    for (int pass : m.surface->busy_passes()) m.surface->search(static_cast<std::size_t>(pass), m.x);
    contact_time += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    contact_finish();
  };

  // --- elements ------------------------------------------------------------------------
  // New contact couplings grow the pattern before anything is written into it.
  auto prepare_tangent = [&] {
    for (const auto& c : m.contributions)
      if (c.count > 1) m.system->ensure_coupled(c.nodes.data(), c.count);
    m.system->zero();
  };
  if (out.force.size() != dofs()) out.force.resize(dofs());
  out.force.setZero();
  double elastic = 0, plastic = 0;
  const int ne = static_cast<int>(mesh_.elements.size());
  // Two partial sums, elements [0, split) and [split, ne), on one thread or two: the same
  // arithmetic either way, so the result does not depend on the threads.
  double helper_elastic = 0, helper_plastic = 0;
  // Bulk viscosity: elements [0, split) into out.viscous_force, [split, ne) into
  // helper_viscous, summed below (again the same order on one thread or two).
  const bool viscous = m.bulk_scale > 0 && m.increment_time > 0;
  if (viscous) out.viscous_force.setZero(dofs());
  else out.viscous_force.resize(0);
  double* const q_main = viscous ? out.viscous_force.data() : nullptr;
  if (m.fork) {
    if (want_tangent && m.tangents.size() != mesh_.elements.size()) m.tangents.resize(mesh_.elements.size());
    Impl::ElementJob job{&m, &u, want_tangent, viscous};
    if (!want_tangent) {
      m.dealer.reset(ne, lane_group_width());
      m.contact_ready.store(false, std::memory_order_relaxed);
    }
    m.fork->run(&Impl::ElementJob::run, &job, [&] {
      if (want_tangent) {
        contact();
        m.elements(0, m.split, u, want_tangent, true, out.force.data(), q_main, elastic, plastic);
        return;
      }
      // Force only: the caller begins the contact, then both threads deal its passes and the
      // elements — the caller passes first, the helper elements first — so that neither
      // waits for the other's share; the sums are formed afterwards in the fixed order.
      try {
        contact_begin();
        m.contact_dealer.reset(static_cast<int>(m.surface->busy_passes().size()), 1);
        m.contact_ready.store(true, std::memory_order_release);
        const auto t0 = std::chrono::steady_clock::now();
        m.deal_contact();
        contact_time += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        m.deal(u, viscous, false);
      } catch (...) {
        m.contact_dealer.fail();
        m.contact_ready.store(true, std::memory_order_release);
        m.dealer.fail();
        throw;
      }
      if (!m.contact_dealer.wait_all()) return;  // the helper failed: ForkJoin rethrows
      contact_finish();
      m.sum_slots(0, m.split, out.force.data(), q_main, elastic, plastic);
    });
    helper_elastic = job.elastic;
    helper_plastic = job.plastic;
    if (want_tangent) {
      prepare_tangent();
      for (int e = 0; e < ne; ++e) m.system->add_element(e, m.tangents[e].data());
    }
  } else {
    contact();
    if (want_tangent) prepare_tangent();
    m.elements(0, m.split, u, want_tangent, false, out.force.data(), q_main, elastic, plastic);
    m.zero_helper_sums(viscous);
    m.elements(m.split, ne, u, want_tangent, false, m.helper_force.data(), viscous ? m.helper_viscous.data() : nullptr,
               helper_elastic, helper_plastic);
  }
  elastic += helper_elastic;
  plastic += helper_plastic;
  if (want_tangent)
    for (const auto& c : m.contributions) m.system->add_nodes(c.nodes.data(), c.count, c.tangent.data(), 12);
  // The two halves, the contact and the bulk viscosity summed in one pass, bitwise the
  // separate sums (chain_force_sum.hpp), with the explicit step's end on each finished block.
  const ChainForceParts parts{out.force.data(), m.helper_force.data(), q_main,
                              viscous ? m.helper_viscous.data() : nullptr, out.force.size(), m.helper_lo,
                              m.helper_len};
  if (end) {
    finish_chain_force(parts, m.contributions, *end);
  } else {
    NoForceEnd none;
    finish_chain_force(parts, m.contributions, none);
  }
  out.elastic_energy = elastic;
  out.plastic_work = plastic;
  out.contact_energy = contact_energy;
  out.contact_time_s = contact_time;
  m.trial_fresh = true;
}

void ChainModel::commit(const Eigen::VectorXd& u) {
  Impl& m = *impl_;
  // The trial states must be those of u (a driver may have evaluated elsewhere since, e.g.
  // the half-step residual of thesis §3.5).
  if (!m.trial_fresh || m.u_last.size() != u.size() || m.u_last != u) evaluate(u, false, m.scratch);
  commit_trial();
}

void ChainModel::commit_evaluated(const Eigen::VectorXd& u) {
  // The caller evaluated at u and has not changed it since, so the comparison of commit() is
  // known to hold; an evaluation that did not complete is still re-done.
  if (!impl_->trial_fresh || impl_->u_last.size() != u.size()) evaluate(u, false, impl_->scratch);
  commit_trial();
}

void ChainModel::commit_trial() {
  Impl& m = *impl_;
  std::swap(m.committed, m.trial);
  m.surface->commit();
  m.trial_fresh = false;
  // u_last equals u here; it serves only the freshness test above, which the next
  // evaluate() re-arms by writing it, so it gives its buffer to u_n (no copy).
  std::swap(m.u_n, m.u_last);
  // x was formed from u_last in the same evaluation: it is X + u_n now (the next evaluation
  // writes the whole of x again before reading it).
  std::swap(m.x_n, m.x);
  // The next increment is described on this configuration (kinematics.hpp): the element
  // geometry is re-derived on x_n in the next element pass (Impl::elements).
  ++m.xn_epoch;
}

StableStep ChainModel::stable_step(const Eigen::VectorXd& u) const {
  Impl& m = *impl_;  // the exact element eigenvalues are cached
  // Elements (issue 4 item 5): ω_max² of the assembled system is at most the largest
  // element λ_max(K_e, M_e) (Rayleigh quotient, M = Σ M_e), with the elastic tangent, which
  // bounds the elastic-plastic one (element_eigenvalue.hpp). λ_max is computed exactly
  // (16×16 eigenproblem, with the committed thickness λ3 of the points) at the start and again for every
  // element whose shape measure (L_max²/A) or largest λ3 has changed by more than 5 % since
  // its last exact value; in between it is scaled with both. (The shortest edge alone
  // underestimates λ of a sheared element up to 3×; the reference thickness underestimates
  // it by λ3, up to 1.4× at a crushed hinge.)
  const std::size_t nn = mesh_.nodes.size();
  if (m.x_bound.size() != nn) m.x_bound.resize(nn);
  auto& x = m.x_bound;
  for (std::size_t i = 0; i < nn; ++i) x[i] = mesh_.nodes[i] + Eigen::Vector2d(u(2 * i), u(2 * i + 1));
  const bool assembled = input_.step_bound == StepBound::Assembled;
  double el = 0;
  int worst = -1;
  for (std::size_t e = 0; e < mesh_.elements.size(); ++e) {
    const double shape = shape_measure(mesh_.elements[e], x);
    if (!std::isfinite(shape)) throw std::runtime_error(fmt::format("stable step: element {} (ring {}) has collapsed", e + 1, mesh_.element_ring[e] + 1));
    const int ppe = m.points_per_element;
    const PointState* states = &m.committed[e * static_cast<std::size_t>(ppe)];
    const double thick = thickness_measure(states, ppe);
    if (std::abs(shape / m.shape_exact[e] - 1) > 0.05 || std::abs(thick / m.thickness_exact[e] - 1) > 0.05) {
      ElementCoords xe;
      for (int a = 0; a < 8; ++a) xe.row(a) = x[mesh_.elements[e][a]].transpose();
      try {
        const ElementMatrix k =
            element_elastic_stiffness(xe, input_.integration, input_.ring.width_m, m.material, states, ppe);
        m.set_omega2(e, element_max_eigenvalue(k, m.element_mass[e]));
        if (assembled) m.stiffness_exact[e] = k;
      } catch (const std::invalid_argument& err) {
        throw std::runtime_error(fmt::format("stable step: element {} (ring {}): {}", e + 1, mesh_.element_ring[e] + 1, err.what()));
      }
      m.shape_exact[e] = shape;
      m.thickness_exact[e] = thick;
    }
    const double scale = (shape / m.shape_exact[e]) * (thick / m.thickness_exact[e]);
    if (assembled) m.stiffness_scale[e] = scale;
    const double w2 = m.omega2_exact[e] * scale;
    if (w2 > el) { el = w2; worst = static_cast<int>(e); }
  }
  m.element_omega2 = el;
  m.element_limited_by = fmt::format("element {} (ring {})", worst + 1, mesh_.element_ring[worst] + 1);
  return contact_stable_step(u);
}

// The element part of the last stable_step() (at most the driver's re-bound interval old)
// with the contact springs of the last evaluate(): the re-bound after a change of the
// contact activity, which on the thesis chain happens every few steps.
StableStep ChainModel::contact_stable_step(const Eigen::VectorXd& /*u*/) const {
  Impl& m = *impl_;
  if (!(m.element_omega2 > 0)) throw std::logic_error("ChainModel::contact_stable_step before stable_step");
  const double el = m.element_omega2;
  // Contact springs of the last evaluation within one element depth (active or about to
  // be): they load the same nodal masses, so their frequency² adds to the elements'.
  const bool surface_wins = m.surface_near_omega2 > m.face_near_omega2;
  const double contact = std::max(m.surface_near_omega2, m.face_near_omega2);
  const int contact_node = surface_wins ? m.surface_near_node : m.face_near_node;
  double w2 = el + contact;
  std::string limited_by = contact > el ? fmt::format("contact penalty, node {}", contact_node + 1) : m.element_limited_by;
  m.parts = StepParts{el, contact, 0, 1};
  if (input_.step_bound == StepBound::Assembled) {
    // The assembled estimate (assembled_eigenvalue.hpp) of the scaled element matrices and
    // the ACTIVE penalty springs (k G Gᵀ) together, instead of the sum of the largest element
    // and the largest spring frequency²: θ·margin, never above that sum, and the sum itself
    // when the iteration has not settled. A spring that closes changes the active set, so
    // the driver re-bounds before the next step (run_dynamic). The first call starts from a
    // random vector and iterates long; later calls follow the highest mode from the last
    // iterate.
    const bool first = m.assembled_calls++ == 0;
    const AssembledEstimate est = m.assembled->estimate(m.stiffness_exact, m.stiffness_scale, first ? 200 : 3,
                                                        first ? 2000 : 200, 1e-4, m.contributions);
    m.assembled_iterations += est.iterations;
    if (est.converged && est.lambda > 0) {
      const double sharp = input_.step_bound_margin * est.lambda;
      m.parts.assembled_omega2 = sharp;
      if (sharp < w2) {
        limited_by = fmt::format("assembled power iteration ({} it., {:.3f} of the element + contact bound, {})",
                                 est.iterations, std::sqrt(sharp / w2), limited_by);
        w2 = sharp;
      }
    } else {
      ++m.assembled_fallbacks;
    }
  }
  StableStep s;
  s.step_s = 2.0 / std::sqrt(w2);
  // Bulk viscosity damps the highest mode at ξ = b1: the central-difference limit becomes
  // Δt ≤ (2/ω_max)(√(1 + ξ²) − ξ) (ABAQUS Analysis Guide, explicit stability limit).
  const double xi = input_.bulk_viscosity;
  if (xi > 0) s.step_s *= std::sqrt(1 + xi * xi) - xi;
  if (xi > 0) m.parts.bulk_factor = std::sqrt(1 + xi * xi) - xi;
  s.limited_by = limited_by;
  return s;
}

void ChainModel::set_increment_time(double dt) {
  if (!(dt >= 0) || !std::isfinite(dt))
    throw std::invalid_argument(fmt::format("ChainModel::set_increment_time: dt = {} must be >= 0 and finite", dt));
  impl_->increment_time = dt;
}

std::vector<double> ChainModel::contact_pressure() const {
  std::vector<double> p(mesh_.nodes.size(), 0.0);
  for (const auto& [node, value] : impl_->pressure) p[node] += value;
  return p;
}

double ChainModel::ring_extent(int ring, const Eigen::VectorXd& u) const {
  if (ring < 0 || ring >= input_.rings) throw std::invalid_argument(fmt::format("ring_extent: no ring {}", ring));
  double lo = 1e300, hi = -1e300;
  for (int n : mesh_.ring_outer_nodes[ring]) {
    const double y = mesh_.nodes[n].y() + u(2 * n + 1);
    lo = std::min(lo, y);
    hi = std::max(hi, y);
  }
  return hi - lo;
}

std::vector<Cps8Fields> ChainModel::element_fields() const {
  const Impl& m = *impl_;
  std::vector<Cps8Fields> out;
  out.reserve(mesh_.elements.size());
  for (std::size_t e = 0; e < mesh_.elements.size(); ++e)
    out.push_back(cps8_fields(&m.committed[e * m.points_per_element], m.points_per_element));
  return out;
}

double ChainModel::contact_penalty_scale() const { return impl_->penalty_scale; }

const ChainModel::StepParts& ChainModel::step_parts() const { return impl_->parts; }

double ChainModel::elements_only_assembled_omega2() const {
  Impl& m = *impl_;
  if (input_.step_bound != StepBound::Assembled)
    throw std::logic_error("ChainModel::elements_only_assembled_omega2 needs StepBound::Assembled");
  if (!(m.element_omega2 > 0)) throw std::logic_error("ChainModel::elements_only_assembled_omega2 before stable_step");
  const bool first = !m.elements_only;
  if (first) m.elements_only = std::make_unique<AssembledEigenvalue>(m.element_dofs, m.inv_sqrt_mass);
  const AssembledEstimate est =
      m.elements_only->estimate(m.stiffness_exact, m.stiffness_scale, first ? 200 : 3, first ? 2000 : 200, 1e-4);
  return est.converged ? input_.step_bound_margin * est.lambda : 0.0;
}

ChainModel::StepBoundStatistics ChainModel::step_bound_statistics() const {
  return {impl_->assembled_calls, impl_->assembled_iterations, impl_->assembled_fallbacks};
}

std::vector<double> ChainModel::max_peeq_per_ring() const {
  const Impl& m = *impl_;
  std::vector<double> out(input_.rings, 0.0);
  for (std::size_t e = 0; e < mesh_.elements.size(); ++e)
    for (int p = 0; p < m.points_per_element; ++p)
      out[mesh_.element_ring[e]] = std::max(out[mesh_.element_ring[e]], m.committed[e * m.points_per_element + p].peeq);
  return out;
}

}  // namespace ringcrush::fe
