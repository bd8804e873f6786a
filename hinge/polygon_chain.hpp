// Level 2 of the hinge model (THEORY §4.3–4.4): every ring a closed polygon of N rigid bars
// joined by elastic–viscoplastic rotational springs, with membrane springs in the bars,
// lumped node masses, penalty contact (ring–plate, ring–ring, inner wall–inner wall with the
// wall thickness as offset, plate–plate), welded ties as stiff springs, and rigid plates
// (impactor, interleaved plates, target). One model, two forms:
//   * DAE  F(t, y, y′) = μ ∘ y′ − φ(t, y) = 0 for IDA (DaeSystem), with a sparse Jacobian
//     by coloured finite differences (polygon_ida.hpp);
//   * ODE  y′ = φ(t, y) / μ for Boost.Odeint (OdeSystem).
// The mass "μ" is diagonal, so both forms are the same equations.
//
// Geometry: the polygon is the mean line. Ring r has centre (0, c_r); its full-ring node k
// sits at material angle a_k = 2πk/N measured clockwise from the top (node 0 = A, node N/2 =
// B), at (R sin a_k, c_r + R cos a_k). With the x = 0 symmetry plane (the thesis FE model),
// only nodes 0…N/2 are unknowns; the others are their mirror images, and the model's energy,
// masses and forces are those of the half (x ≥ 0) structure: nodes on the axis carry half a
// node mass, half a hinge and half a plate contact. y is upward; the impactor comes from
// above and moves toward −y.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "dae_system.hpp"
#include "ode_system.hpp"

namespace ringcrush::hinge {

enum class PolygonJoint { Welded, Free, Plates };

struct PolygonChainInput {
  // Rings (all alike). Effective E and σ0 carry the section state: plane strain passes
  // E/(1 − ν²) and 2σ0/√3 (THEORY §1.2).
  int rings = 1;
  double outer_diameter_m = 0.0508;
  double wall_thickness_m = 0.0016;
  double width_m = 0.0125;
  double pitch_m = 0.0;               // ring-centre spacing; 0 means D (touching rings)
  double youngs_modulus_pa = 202e9;
  double yield_stress_pa = 273e6;
  double hardening_modulus_pa = 0.0;  // E′ of the hinge hardening M_y = M0 + H_θ ā
  double yield_cap_ratio = 0.0;       // M_y ≤ cap·M0 (the flat end of the hardening table); 0: none
  double density_kg_m3 = 7850.0;
  int nodes_per_ring = 48;            // N of the full ring; even, and a multiple of 4 for the half model
  bool half_symmetry = true;

  // Hinge law (THEORY §4.3). Hinge length l_h = α t when α > 0, else the bar length ℓ0;
  // H_θ = E′ I / l_h. Viscoplastic Cowper–Symonds flow
  //   λ̇ = (2 l_h / t) D ⟨|M|/M_y − 1⟩^q.
  double redwood_alpha = 0.0;
  // true: the hardening uses the hinge length fitted so that one ring follows Redwood's
  // curve for redwood_alpha (redwood_hinge_length.hpp) instead of α t; the flow law keeps α t.
  bool redwood_fitted_hardening = false;
  double cowper_symonds_d_per_s = 40.4;  // mild steel, Jones (1989)
  double cowper_symonds_q = 5.0;

  // Joints between rings and their plates.
  PolygonJoint joint = PolygonJoint::Free;
  double plate_mass_kg = 0.0;        // interleaved plates (full mass)
  double plate_thickness_m = 0.0;
  double tie_stiffness_scale = 1.0;  // welded: k_tie = scale · E t L / ℓ0 (penalty tie)

  // Contact: k_n = scale · E t L / ℓ0 per node; Hunt–Crossley damping f = k p (1 + χ ṗ),
  // clipped at zero (no adhesion), χ in s/m.
  double contact_stiffness_scale = 1.0;
  double contact_damping_s_per_m = 0.05;

  // Membrane bars: k_m = scale · E t L / ℓ0 (the penalties above stay on the unscaled
  // E t L / ℓ0). 1 is the section's EA. Below 1 it is a numerical softening of the hoop
  // stretch, as the penalties are numerical: the bar mode 2c/ℓ0 bounds the central
  // difference's step, and a thin ring crushes by bending: EA → s EA multiplies the hoop-stretch
  // term π R/(4 EA) of the diametral compliance by 1/s, next to the bending term
  // (π/4 − 2/π) R³/EI (THEORY §1.1) — the Test 30 ring's elastic stiffness falls by 0.4 % at
  // s = 1/4, 2.5 % at 1/16, 10 % at 1/64 (tests/hinge/polygon_stiff_term_scale_test.cpp).
  // All three scales must be positive and finite.
  double membrane_stiffness_scale = 1.0;

  // Impactor (full mass; the half model carries half of it) and far end.
  double impactor_mass_kg = 0.257;
  double impactor_velocity_m_s = 0.0;  // toward the chain (downward)
  bool fixed_target = true;
  // Quasi-static use: the impactor plate is driven at a prescribed speed instead of flying
  // (its speed ramps up over `drive_ramp_s`), and a mass-proportional damping force
  // −c m v (c in 1/s) removes the ringing. Both off for impact runs.
  bool driven_impactor = false;
  double drive_speed_m_s = 0.0;
  double drive_ramp_s = 0.0;
  double mass_damping_per_s = 0.0;

  // Kelvin–Voigt damping of the polygon's node-scale vibrations (a numerical convenience,
  // named so that it is never hidden): bar force c_b ℓ̇ and hinge moment c_θ θ̇, with
  // c_b = ζ_m·2√(k_m m/2) and c_θ = ζ_b·2√(k_θ m ℓ0²/2), i.e. ζ is the damping ratio of the
  // shortest bar-stretch and node-wiggle modes; slow ring modes get ζ·ω/ω_max. Without it
  // IDA resolves contact-excited membrane ringing at ~1e-7 s steps.
  double membrane_damping_ratio = 0.0;
  double hinge_damping_ratio = 0.0;
  // false (the default): the hinge damper acts on the total rotation rate, M_damp = c_θ θ̇ — a
  // dashpot beside the whole elastic–plastic hinge, so that it also resists (and takes energy
  // from) the plastic flow. true: on the elastic rate only, M_damp = c_θ (θ̇ − θ̇p) — a
  // Kelvin–Voigt element on the elastic spring, in series with the (visco)plastic slider: it
  // damps elastic vibrations as before but does no work on a steady plastic flow. The yield
  // check and the flow law keep the spring moment k_θ(θ − θp) either way (the damper moment
  // does not load the slider), and the Kelvin–Voigt accumulator books the damper moment's work
  // c_θ (θ̇ − θ̇p) θ̇, so the energy balance closes as before; of it, c_θ (θ̇ − θ̇p) θ̇p is the
  // damper moment's work on the plastic rate (CentralDifferenceStatistics::
  // hinge_damper_plastic_work_j). The central difference takes θ̇p from the step's
  // backward-Euler flow update, an explicit force beside the implicit c_θ θ̇
  // (polygon_central_difference.hpp); IDA's residual and Odeint's rhs take θ̇p = λ̇(M, ā) sign M
  // of the flow law at the state (= θp′ on the solution), with its derivatives in the analytic
  // Jacobian (polygon_ring_forces.cpp).
  bool hinge_damper_on_elastic_rate = false;
};

// Snapshot of the chain for output and measures (full rings, mirrored when half).
struct PolygonShape {
  // [ring][node] mean-line positions of the full ring, node k at material angle 2πk/N.
  std::vector<std::vector<std::array<double, 2>>> nodes;
  std::vector<std::vector<double>> turning;         // [ring][node] τ_k (rad), 2π/N when undeformed
  std::vector<std::vector<double>> plastic_rotation;  // [ring][node] accumulated ā_k (rad)
  std::vector<double> body_faces;  // y of the impactor's contact face, plates' centres, target face
};

struct PolygonEnergies {  // of the modelled structure (the half when half_symmetry)
  double kinetic = 0, elastic = 0, contact = 0;     // contact: penalty potential
  // Integrated from the state accumulators: plastic hinge work, contact damping, the
  // Kelvin–Voigt and mass damping (numerical), work of the driven plate.
  double plastic = 0, contact_damping = 0, damping = 0, external = 0;
};

class PolygonChain final : public DaeSystem, public OdeSystem {
 public:
  explicit PolygonChain(const PolygonChainInput& input);

  // Sizes and layout: per ring, per independent node j: [x, y, vx, vy, θp, ā]; then the
  // bodies [y, v] (impactor, interleaved plates); then four accumulators
  // [plastic work, contact damping, Kelvin–Voigt + mass damping, external work of the driven
  // plate].
  std::size_t size() const override { return size_; }
  int nodes_per_ring() const { return n_full_; }
  int independent_nodes() const { return n_ind_; }
  std::size_t node_offset(int ring, int node) const {
    return static_cast<std::size_t>((ring * n_ind_ + node) * 6);
  }
  std::size_t body_offset(int body) const { return body_base_ + 2 * static_cast<std::size_t>(body); }
  std::size_t accumulator_offset() const { return acc_base_; }
  int body_count() const { return n_bodies_; }
  int ring_count() const { return n_rings_; }
  // Component scales for absolute tolerances (m, m/s, rad, J).
  std::vector<double> component_scales() const;
  // What each component is (node and body positions, their velocities, hinge θp and ā,
  // energy accumulators), so that a solver can weigh the kinds differently.
  enum class Component { Position, Velocity, Plastic, Energy };
  std::vector<Component> component_kinds() const;

  std::vector<double> initial_state() const;
  // y′ at (t, y): the explicit form of the same equations.
  void rhs(double t, const double* y, double* dydt) override;
  void residual(double t, const double* y, const double* yp, double* r) override;

  // Sparse ∂F/∂y + cj ∂F/∂y′ by coloured forward differences on the current contact graph.
  // The accumulator rows keep only their diagonal (nothing depends on them).
  struct Triplet {
    int row, col;
    double value;
  };
  void sparse_jacobian(double t, double cj, const double* y, const double* yp, const double* r,
                       std::vector<Triplet>& out);
  // The same matrix from the derivatives of the force laws, in one pass of the residual code
  // (duplicate (row, col) entries are to be summed). Exact for the membrane, hinge, flow,
  // tie and normal-contact stiffness and for the Kelvin–Voigt dampers; the small curvature
  // terms (hinge moment times the change of the hinge-angle gradient, the slide of a contact
  // point along its segment, the turn of the contact normal) are left out — the matrix only
  // drives Newton's iteration, the residual stays exact. The energy accumulators' rows carry
  // their gradients too: without them Newton leaves each step's dissipated energy one
  // iterate behind, and over ~10⁴ steps the balance drifts by ~3e-3 of the impact energy.
  // tests/hinge/polygon_jacobian_test.cpp holds it against differences of φ.
  void analytic_jacobian(double t, double cj, const double* y, std::vector<Triplet>& out);
  // The same entries, in the same order, added straight into a compressed-column array
  // (polygon_ida.cpp, README "Level 2 per-step cost"): entry k must have the (row, col)
  // keys[k] = row << 32 | col of the last triplet assembly and goes to data[slots[k]]. While
  // the contact pattern is unchanged the sequence is the same, so no triplets are stored
  // and nothing is sorted. Returns false when the sequence differs (a contact opened or
  // closed): `data` is then partly written and the caller reassembles from triplets.
  struct JacobianScatter {
    const std::int64_t* keys = nullptr;
    const std::size_t* slots = nullptr;
    std::size_t count = 0;
    double* data = nullptr;
    std::size_t cursor = 0;
    bool matched = true;
  };
  static std::int64_t jacobian_key(std::size_t row, std::size_t col) {
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(row) << 32) | static_cast<std::uint32_t>(col));
  }
  bool analytic_jacobian_scatter(double t, double cj, const double* y, JacobianScatter& into);
  // The diagonal μ of F = μ y′ − φ, i.e. ∂F/∂y′ (the iteration matrix is −∂φ/∂y + cj diag μ).
  const std::vector<double>& rate_coefficients() const { return mu_; }

  // Generalised internal + contact + tie forces φ (the velocity-row part of rhs times mass),
  // for tests of the elastic stiffness. Same length as the state.
  void generalised_forces(double t, const double* y, double* phi);

  PolygonShape shape(const double* y) const;
  PolygonEnergies energies(double t, const double* y);
  // Contact force on the impactor (full structure, N, positive pushing it back up) and on the
  // target.
  double impactor_force(double t, const double* y);
  double target_force(double t, const double* y);
  // The same two forces from the last evaluation (energies() at a sample), without evaluating
  // again: the forces do not depend on whether an evaluation records its pairs.
  double impactor_force_last() const { return structure_factor() * last_impactor_force_; }
  double target_force_last() const { return structure_factor() * last_target_force_; }
  double impactor_position(double t, const double* y) const;  // displacement from start, + down
  double impactor_velocity(double t, const double* y) const;  // + toward the chain
  // Factor from the modelled structure to the full one (2 for the half model).
  double structure_factor() const { return half_ ? 2.0 : 1.0; }

  // Derived constants (for tests and reports).
  double mean_radius() const { return R_; }
  double bar_length() const { return l0_; }
  double plastic_moment() const { return M0_; }
  double hinge_stiffness() const { return k_theta_; }
  double node_mass() const { return m_node_; }
  long contact_pairs_last() const { return static_cast<long>(pairs_.size()); }
  // What the softened stiff terms cost (membrane_stiffness_scale, the penalty scales), at the
  // state of the last energies() call: the deepest contact penetration (m; node–plate,
  // node–segment, plate–plate) and the largest membrane strain |ℓ/ℓ0 − 1| of a bar.
  double max_penetration_last() const { return last_max_penetration_; }
  double max_membrane_strain_last() const { return last_max_strain_; }
  const PolygonChainInput& input() const { return in_; }

  // Cowper–Symonds flow of one hinge (THEORY §4.3): yield moment M_y(ā) = min(M0 + H ā, cap),
  // overstress |M|/M_y − 1 and rate λ̇ = C ⟨over⟩^q. The one law of the residual and of the
  // central-difference driver's implicit flow update (polygon_flow_update.cpp).
  struct Flow {
    double yield_moment, over, rate;
  };
  Flow flow(double moment, double plastic_sum) const;
  // rhs for the central-difference driver (polygon_central_difference.hpp): first every
  // hinge's θp, ā in y advance over dt by backward Euler at the positions in y
  // (polygon_flow_update.cpp), Δλ = dt λ̇(k_θ(θ − θp_n − sign Δλ), ā_n + Δλ), so that the
  // flow's relaxation time (~0.2 µs for the default Perzyna law, shorter than the explicit
  // step) cannot make it unstable; then y′ as rhs with the updated θp. The update runs inside
  // the evaluation, which has the hinge rotations at hand. `plastic_work` gains the work of
  // the update (modelled structure), `min_relaxation_time` the shortest 1/(∂λ̇/∂θp) met.
  // The work is ½(M_prev + M) Δθp with M_prev the moment after the previous call, so the
  // first call (the driver's, at t0) is made with dt = 0.
  void rhs_with_flow_update(double t, double* y, double dt, double* dydt, double& plastic_work,
                            double& min_relaxation_time);
  // Stable central-difference step of the last evaluation's state (polygon_stable_step.cpp):
  // per node a Gershgorin bound ω² ≤ Σ|K_ij|/m_i on the membrane, hinge, tie and contact
  // stiffness (the contacts as they were in the last evaluation, Hunt–Crossley slope
  // k(1 + χṗ)), and the damping ratio ξ of the Kelvin–Voigt, contact and mass damping rows
  // the same way; dt = min over nodes and bodies of (2/ω)(√(1 + ξ²) − ξ) (Belytschko et al.,
  // Nonlinear FE, §6.3), without safety factor.
  double stable_step() const { return stable_step(kAllStiffness); }
  // The same bound with only the stiffness terms in `terms` (StepTerm bits; the damping rows
  // always): which term sets the step (polygon_stiffness_spectrum.hpp, stable_step_breakdown).
  enum StepTerm : unsigned { kMembrane = 1, kHinges = 2, kTies = 4, kContacts = 8, kAllStiffness = 15 };
  double stable_step(unsigned terms) const;
  // The same bound from a scan of every node (the reference path of stable_step, which visits
  // only the nodes with contact rows and one node of each remaining class): for tests.
  double stable_step_all_nodes(unsigned terms) const;
  // K = −∂φ/∂y of the force laws without the Kelvin–Voigt dampers (analytic_jacobian with
  // c_b = c_θ = 0, cj = 0; polygon_stiffness_spectrum.cpp): the stiffness the step is bound by.
  void stiffness_triplets(double t, const double* y, std::vector<Triplet>& out);
  // Kelvin–Voigt ring dampers applied implicitly by the central-difference driver
  // (polygon_implicit_dampers.cpp). While set, rhs_with_flow_update leaves the bar and hinge
  // dampers out of φ (and out of the damping power) and stable_step leaves them out of ξ;
  // the driver applies them through ring_damper_step. Hunt–Crossley contact and mass
  // damping stay explicit. IDA and Odeint (rhs, residual) are not affected.
  void set_implicit_ring_dampers(bool on) { implicit_dampers_ = on; }
  bool implicit_ring_dampers() const { return implicit_dampers_; }
  // The dampers' forces are −C(x) v, C = Σ_bars c_b g gᵀ + Σ_hinges c_θ g gᵀ on the node
  // velocity rows of each ring (g = ∂ℓ/∂p or ∂θ/∂p; the half model ½ EᵀC_full E, E the
  // mirror expansion, axis nodes' x rows left out), in the units of φ's rows.
  // ring_damper_forces: d = C(x) v with x from y; v and d are state-length arrays of which
  // only the node velocity rows are read and written.
  void ring_damper_forces(const double* y, const double* v, double* d);
  // ring_damper_step: on entry v holds a velocity prediction v*; on exit the solution of
  // (μ + h C(x)) v = μ v* and d = C(x) v (one banded factorisation per ring, O(N)). v may be y.
  void ring_damper_step(const double* y, double h, double* v, double* d);
  double mass_row(std::size_t row) const { return mu_[row]; }  // the diagonal μ of F
  // Elastic-rate hinge dampers (PolygonChainInput::hinge_damper_on_elastic_rate): with the
  // plastic rates θ̇p of the independent hinges in the θp rows of `rate` (state-length; the
  // half model's mirrored hinges take their image's), out = the node forces of the damper
  // moments' plastic part −c_θ θ̇p, i.e. +Σ_hinges c_θ θ̇p g (g = ∂θ/∂p at the positions in y,
  // weighted as ring_damper_forces' C: the half model ½ Eᵀ of the full ring's, axis x rows 0),
  // on the node velocity rows (the other rows untouched). The damper force is then
  // −(C v − out). Returns Σ_hinges w c_θ θ̇p² (w = node weight; modelled structure), so that
  // out·v − that is the damper moments' power on the plastic rate, Σ w c_θ (θ̇ − θ̇p) θ̇p.
  double hinge_plastic_rate_forces(const double* y, const double* rate, double* out);
  bool hinge_damper_on_elastic_rate() const { return in_.hinge_damper_on_elastic_rate && c_hinge_ > 0; }

  // Implicit membrane (polygon_implicit_membrane.cpp; CentralDifferenceOptions::
  // implicit_membrane). While set, stable_step and stiffness_triplets leave the membrane bars
  // out (the driver integrates them implicitly; φ keeps the membrane force), and the damper
  // profile of the full model is laid out with the bars present whatever c_b.
  void set_implicit_membrane(bool on) { implicit_membrane_ = on; }
  bool implicit_membrane() const { return implicit_membrane_; }
  // out = K_m(x) v on the node velocity rows (x from y, v state-length as in
  // ring_damper_forces): the membrane's material tangent K_m = Σ_bars k_m g gᵀ, g = ∂ℓ/∂p =
  // (−e, e) — the bar dampers' pattern with k_m for c_b —, in the half model ½ EᵀK_full E
  // (bars 0…N/2 − 1 once, the axis nodes' x rows 0). The geometric term (N/ℓ)(I − e eᵀ) is
  // left out.
  void membrane_stiffness_product(const double* y, const double* v, double* out);
  // The same with the bar directions of the last membrane_stiffness_product call (the same
  // positions: the driver's second product of a step), without their square roots.
  void membrane_stiffness_product_again(const double* v, double* out) const;
  // As ring_damper_step with C + h K_m(x) for C: on exit (μ + h C + h² K_m) v = μ v* and
  // d = (C + h K_m) v. h > 0.
  void ring_damper_membrane_step(const double* y, double h, double* v, double* d);
  // The driver's whole implicit-membrane solve in one call (polygon_central_difference.hpp's
  // second half-kick): with v* in v's node rows and w = v_{n+½}, on exit kw = K_m(x) w,
  // (μ + h C + h² K_m) v = μ v* + h² K_m w, d = (C + h K_m) v and kv = K_m(x) v. The half
  // model takes K_m's bar directions from the band's assembly (one square root per bar for
  // both); the full ring is membrane_stiffness_product, ring_damper_membrane_step and
  // membrane_stiffness_product_again in turn. h > 0; v may be y, the other arrays distinct.
  void ring_damper_membrane_kick(const double* y, double h, const double* w, double* v, double* d, double* kw,
                                 double* kv);

  // Contact landing (polygon_contact_landing.cpp; CentralDifferenceOptions::
  // contact_landing_depth): while depth > 0, every evaluation notes, over the node–plate and
  // node–segment pairs that close faster than `min_speed`, the shortest time in which one of
  // them would reach the penetration `depth` (pairs within reach, gap ≤ t: (gap + depth)/ṗ)
  // or go `depth` deeper (touching pairs: depth/ṗ) — contact_landing_step, ∞ when none.
  // 0 (the default) notes nothing.
  void set_contact_landing(double depth, double min_speed);
  double contact_landing_step() const { return landing_step_; }

  // The central difference's ring pass over all rings at once, two rings to an SSE2 vector
  // (the hinges four to an AVX one where the CPU has AVX2; polygon_ring_lanes.cpp), where it
  // applies (implicit or no Kelvin–Voigt dampers, no mass damping, a build without FMA): the
  // same operations per ring as the per-ring pass, so the same bits. On by default; off runs
  // the per-ring pass (the tests' reference).
  void set_ring_lanes(bool on) { ring_lanes_ = on; }
  bool ring_lanes() const { return ring_lanes_; }
  long ring_lane_passes() const { return ring_lane_passes_; }  // evaluations that took it

 private:
  struct Body {
    double half_thickness;  // contact faces at y ± h
    double mass;            // modelled mass (halved for the half model)
    bool fixed;
    double fixed_y;
  };
  struct ContactPair {  // node–segment, for the Jacobian's graph
    int slave, master_a, master_b;  // global independent node ids
  };
  struct BodyContact {
    int node;  // global independent node id
    int body;  // −1: target
  };

  // φ(t, y) and, while analytic_jacobian runs, its derivatives; `record` refreshes the
  // contact lists (the Jacobian's graph) and the reported energies. The force laws are
  // summed in the pieces below, one file each.
  void evaluate(double t, const double* y, double* phi, bool record);
  // The sums one evaluation carries across its pieces: the accumulator rows (plastic power,
  // contact-damping power, Kelvin–Voigt and mass damping power), the recoverable energies
  // and the forces on the impactor and the target.
  struct Tally {
    double plastic_power = 0, dissipation = 0, damping = 0, elastic = 0, contact_energy = 0;
    double impactor_force = 0, target_force = 0;
    double max_penetration = 0, max_bar_strain = 0;  // kept by recording evaluations (energies)
  };
  // polygon_ring_forces.cpp: hinges, membrane bars, flow law, node rows.
  void ring_forces(const double* y, double* phi, bool record, Tally& tally);
  // polygon_body_contact.cpp: welded ties, node–plate and plate–plate contact.
  void tie_forces(const double* y, double* phi, bool record, Tally& tally);
  void plate_contact(int ring, int body, bool above, double t, const double* y, double* phi,
                     bool record, Tally& tally);
  void body_body_contact(double t, const double* y, double* phi, Tally& tally);
  // polygon_segment_contact.cpp: ring–ring and inner-wall node–segment contact. The broad
  // phase: per segment a box grown by t (formed at the list builds; between them each listed
  // segment's box is tested from its end points), and per contact pass
  // (slave ring, master ring) and slave node a Verlet list of the segments whose box, grown
  // by t plus `candidate_margin`, held the node when the lists were built; they are rebuilt
  // once some node has moved more than half the margin (so no segment whose t-box can hold
  // the node is missed, and the pairs are exactly those of an all-segments search).
  int contact_segments() const;
  void update_contact_boxes(const double* y);
  void build_candidates(const double* y);
  int contact_pass(int slave_ring, int master_ring, bool self) const;
  bool near_own_segment(int node, int segment) const;
  void node_segment_contact(int slave_ring, int master_ring, bool self, const double* y,
                            double* phi, bool record, Tally& tally);
  double prescribed_speed(double t) const;
  static double wrap_angle(double a);  // to (−π, π]
  double body_y(int body, const double* y) const;
  double body_v(int body, double t, const double* y) const;
  double node_weight(int j) const { return (half_ && (j == 0 || j == n_ind_ - 1)) ? 0.5 : 1.0; }
  void expand_ring(int ring, const double* y);
  double contact_force(double penetration, double rate, double& dissipation) const;
  // The normal force of a node weighted w (half-model axis nodes ½), zero while apart; books
  // its damping power and penalty energy in the tally.
  double contact_load(double w, double penetration, double rate, Tally& tally) const;
  // Jacobian sinks of analytic_jacobian (entries of −∂φ/∂y; rows of axis-node x forces
  // dropped). ring_block adds a 2×2 block ∂F_i/∂(p or v)_m (slot 0 or 2) of full-ring
  // nodes, ring_force_entry a column of ∂F_i, ring_state_entry a row's entries on the x, y
  // of node m's positions (slot 0) or velocities (slot 2).
  // Inline: ~35 000 entries per Test 30 matrix pass through here.
  void jac(std::size_t row, std::size_t col, double value) {
    if (axis_force_row_[row]) return;  // the symmetry plane: no x force on axis nodes
    emit(row, col, value);
  }
  void emit(std::size_t row, std::size_t col, double value) {  // jac without the axis-row filter
    if (scatter_) {
      auto& s = *scatter_;
      if (s.cursor < s.count && s.keys[s.cursor] == jacobian_key(row, col))
        s.data[s.slots[s.cursor]] += value;
      else
        s.matched = false;
      ++s.cursor;
      return;
    }
    jac_->push_back({static_cast<int>(row), static_cast<int>(col), value});
  }
  void emit_kinematic_and_diagonal(double cj);
  std::pair<int, double> independent(int full_node) const;
  void ring_block(int ring, int i, int m, int slot, double dxx, double dxy, double dyx, double dyy);
  void ring_force_entry(int ring, int i, std::size_t col, double dfx, double dfy);
  void ring_state_entry(int ring, std::size_t row, int m, int slot, double jx, double jy);
  void diss_partials(double penetration, double rate, double& d_pen, double& d_rate) const;

  PolygonChainInput in_;
  bool half_;
  int n_full_, n_ind_, n_rings_, n_bodies_;
  std::size_t body_base_, acc_base_, size_;
  double c_bar_ = 0, c_hinge_ = 0;
  double R_, l0_, t_, k_theta_, k_m_, M0_, H_, cap_, C_vp_, q_, m_node_, k_n_, chi_, k_tie_;
  std::vector<double> ring_centre_;
  std::vector<Body> bodies_;  // 0 = impactor, then plates
  double target_y_ = 0.0;
  std::vector<double> mu_;  // the diagonal "mass" of F = μ y′ − φ

  // Scratch (no allocation in the residual).
  std::vector<double> px_, py_, vx_, vy_, theta_p_, fx_, fy_, moment_;
  std::vector<double> bar_l_, bar_nx_, bar_ny_, bar_ex_, bar_ey_, bar_beta_;
  // The ring pass (polygon_ring_forces.cpp): the full-ring nodes and bars it reads (all, or
  // in the half model those that reach an independent node), which bars carry a hinge at
  // their start, and each bar's n/ℓ (∂β/∂p of its far end) shared by its two hinges.
  std::vector<int> ring_nodes_, ring_bars_, ring_hinges_;
  std::vector<std::array<int, 2>> bar_ranges_;  // ring_bars_ as [first, last) ranges
  std::vector<char> ring_hinge_;
  std::vector<double> bar_gx_, bar_gy_;
  std::vector<double> hinge_theta_, hinge_m_, bar_n_;  // θ, moment with damper, bar force
  void ring_node_forces();
  void central_difference_ring_laws(int ring, Tally& tally);
  double hinge_damper_rate(int km, int k, int kp) const;
  double bar_damper_rate(int k, int kp) const;
  double turn_cos_ = 1.0, turn_sin_ = 0.0;  // of the rest turning 2π/N
  void plan_ring_pass();
  void gather_ring(int ring, const double* y, bool velocities);
  void ring_bars(int first, int last, bool reference);
  // Rows of y′ = φ/μ whose μ is not 1 (the node velocities and free bodies): rhs divides
  // only these (x/1 is x).
  std::vector<std::size_t> inertia_rows_;
  std::vector<double> inverse_mu_;  // 1/μ of inertia_rows_ (the central difference's rhs)
  // The same 1/μ per independent node (both velocity rows, every ring alike) and where the
  // bodies' rows start in inertia_rows_: the central difference's rhs walks the node rows as
  // one strided range.
  std::vector<double> node_inverse_mass_;
  std::size_t inertia_body_first_ = 0;
  double last_impactor_force_ = 0.0, last_target_force_ = 0.0;
  double last_contact_energy_ = 0.0, last_elastic_ = 0.0;
  double last_max_penetration_ = 0.0, last_max_strain_ = 0.0;
  std::vector<ContactPair> pairs_;
  std::vector<BodyContact> body_contacts_;
  std::vector<std::array<int, 2>> tie_pairs_;
  std::vector<std::array<int, 2>> body_body_;  // consecutive bodies incl. target (−1)
  std::vector<double> phi_, pert_y_, pert_r_, base_r_;
  std::vector<std::array<double, 4>> seg_box_;  // contact broad phase
  std::vector<int> candidate_start_, candidate_segment_;  // [pass·(n_ind + 1) + j] → range
  std::vector<double> candidate_reference_;               // node x, y when the lists were built
  bool candidates_built_ = false;
  // Of the last build: per pass p [start, end) at 2p, 2p + 1 into candidate_nodes_ (the slave nodes with a
  // non-empty list, ascending).
  std::vector<int> candidate_node_start_, candidate_nodes_;
  std::vector<std::array<double, 4>> candidate_ring_box_;  // build_candidates' scratch
  void segment_box(int ring, int segment, const double* y);
  double candidate_margin_ = 0.0;
  std::vector<Triplet>* jac_ = nullptr;  // set while analytic_jacobian runs evaluate
  JacobianScatter* scatter_ = nullptr;   // set while analytic_jacobian_scatter runs (jac_ too)
  std::vector<Triplet> scatter_unused_;  // jac_'s target then: stays empty
  std::vector<std::array<double, 3>> hinge_gx_, hinge_gy_;  // ∂θ_k/∂p on (k−1, k, k+1)
  std::vector<char> axis_force_row_;
  // Contact rows of the last evaluation for stable_step: per node (then per body) the sums
  // of the contact stiffness and damping entries, weighted as the forces.
  std::vector<double> contact_k_row_, contact_c_row_;
  void add_contact_rows(std::size_t entity, double w, double penetration, double rate);
  // The ring nodes add_contact_rows touched since the last evaluation began (repeats
  // possible), and stable_step's marks of the ones it has visited in one call.
  std::vector<int> contact_row_nodes_;
  mutable std::vector<std::uint64_t> contact_row_mark_;
  mutable std::uint64_t contact_row_epoch_ = 0;
  double stable_step_scan(unsigned terms, bool every_node) const;
  // The flow update of rhs_with_flow_update, set while it runs: Δλ of one hinge, and the
  // update of hinge k of ring r in ring_forces (θp, ā in flow_y_, the moment and work).
  double return_map(double trial_moment, double plastic_sum, double dt, double& min_relaxation_time) const;
  void update_hinge_flow(int ring, int k, double theta);
  double* flow_y_ = nullptr;
  double flow_dt_ = 0.0, flow_work_ = 0.0, flow_relaxation_ = 0.0;
  std::vector<double> flow_moment_;  // [ring·n_ind + j] moment after the last flow update
  // [j] of the ring in the pass while the flow update runs: |M| ≤ M_y, no flow.
  std::vector<char> hinge_elastic_;
  // [j] of the ring in the pass: the flow update's Δθp (explicit elastic-rate hinge dampers).
  std::vector<double> plastic_step_;
  // The flow update of hinge k of ring r at rotation θ from its trial moment (θp, ā in
  // flow_y_, the work, flow_moment_): the hinge's moment after it. Both ring passes use it.
  double flow_hinge(int ring, int k, double theta, double trial);
  std::size_t flow_index(int ring, int k) const {  // flow_moment_ in the lanes' order
    return static_cast<std::size_t>(k) * static_cast<std::size_t>(lanes_) + static_cast<std::size_t>(ring);
  }
  // The ring lanes (polygon_ring_lanes.cpp): lanes_ = rings rounded up to even; value k of
  // ring r at k·lanes_ + r, k over the full ring's nodes, bars and hinges 0…N.
  bool ring_lanes_ = true;
  long ring_lane_passes_ = 0;
  int lanes_ = 0;
  std::vector<double> lane_px_, lane_py_, lane_tp_, lane_ab_, lane_ex_, lane_ey_, lane_gx_, lane_gy_, lane_n_,
      lane_theta_, lane_m_;
  std::vector<std::uint64_t> lane_flowing_;  // [ring][word]: hinges above their yield moment
  bool ring_lanes_apply() const;
  void plan_ring_lanes();
  void ring_lanes_gather(const double* y, double* phi);
  void ring_lanes_bars();
  void ring_lanes_hinges();
  void ring_lanes_flow(double* phi, Tally& tally);
  void ring_lanes_node_forces(double* phi);
  void central_difference_ring_lanes(const double* y, double* phi, Tally& tally);
  double landing_depth_ = 0.0, landing_speed_ = 0.0;
  double landing_step_ = std::numeric_limits<double>::infinity();
  void note_landing(double gap, double rate) {
    if (rate > landing_speed_) landing_step_ = std::min(landing_step_, (gap + landing_depth_) / rate);
  }
  // Implicit ring dampers (polygon_implicit_dampers.cpp): C of one ring in a profile
  // (skyline) lower triangle over its 2 n_ind velocity rows, row i spanning columns
  // kv_first_[i]…i from kv_start_[i]; kv_factor_ the Cholesky factor of μ + h C.
  bool implicit_dampers_ = false;
  // Implicit membrane: the step's h while ring_damper_membrane_step runs (0 otherwise), which
  // adds h k_m to every bar's coefficient in the damper matrix.
  bool implicit_membrane_ = false;
  double membrane_h_ = 0.0;
  std::vector<double> membrane_e_;  // e of every bar of the last membrane_stiffness_product or kick
  double bar_matrix_coefficient() const { return membrane_h_ > 0.0 ? c_bar_ + membrane_h_ * k_m_ : c_bar_; }
  std::vector<int> kv_first_, kv_start_;
  std::vector<double> kv_c_, kv_factor_, kv_b_;
  template <class Sink>
  void for_each_damper_entry(Sink&& sink) const;
  void assemble_ring_dampers(int ring, const double* y);
  // The half model's fast path: the open band (bandwidth 5) of every ring assembled straight
  // from y, interleaved — C(i, i − q) of ring r at (6 i + q) S + r, S the ring count rounded up
  // to even (two rings to an SSE2 vector), then assemble_half_band's element scratch —; the
  // L D Lᵀ factors interleaved alike in kv_band_l_ (D in the diagonal slots, 1/D in kv_inv_diag_).
  std::vector<double> kv_band_c_, kv_band_l_, kv_inv_diag_;
  void assemble_half_band(int ring, const double* y, double* band);
  void half_band_step(const double* y, double h, double* v, double* d);
  // half_band_step in its parts: the arrays sized (once), every ring's band assembled (and,
  // with the implicit membrane, membrane_e_ filled from its bars), the factorisation and solve.
  void prepare_half_band();
  void assemble_half_bands(const double* y);
  void half_band_solve(double h, double* v, double* d);
  std::vector<double> kv_inverse_mu_;  // 1/μ of every row (the membrane kick's h² K_m w / μ)
};

}  // namespace ringcrush::hinge
