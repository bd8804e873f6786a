// FeInput: everything the FE core needs to run one ring crush, as plain data (DESIGN.md
// "The contract": fe knows neither TOML nor the command line; compare/ builds this from a
// Scene). SI units throughout.
#pragma once

#include <numbers>
#include <vector>

namespace ringcrush::fe {

struct HardeningPoint {
  double yield_stress_pa;
  double plastic_strain;  // equivalent plastic strain (PEEQ) at which the yield stress applies
};

struct MaterialInput {
  double youngs_modulus_pa = 202e9;
  double poisson_ratio = 0.3;
  // Isotropic hardening, piecewise linear in PEEQ, flat after the last point (thesis
  // *PLASTIC table). First point at PEEQ 0, strains strictly increasing.
  std::vector<HardeningPoint> hardening{{273e6, 0.0}, {320e6, 0.02113}};
};

struct RingInput {
  double outer_radius_m = 25.4e-3;
  double inner_radius_m = 23.8e-3;
  double width_m = 12.5e-3;  // plane-stress thickness of the CPS8 section
};

// Gauss rules of the CPS8 element (thesis §3.6.1.4).
enum class Integration {
  Full,       // 3×3
  Reduced,    // 2×2
  Selective,  // 3×3 with the in-plane volumetric strain taken from the 2×2 (Barlow) points
};

struct MeshInput {
  int elements_around = 22;  // per HALF ring (a full ring gets twice as many)
  int elements_through = 1;
  // Element size ratio far/near the hinge locations: elements are finest at the contact
  // points (φ = 0, π) and at the sides (φ = π/2) and `grading` times coarser half-way
  // (the thesis deck: 5.625° vs 11.25°, grading 2).
  double grading = 1.0;
  bool half_ring = true;  // x ≥ 0 with the x = 0 symmetry (thesis); false: full ring
};

struct ContactInput {
  // Penalty stiffness of a contact node = penalty_scale · E · L · w / h, with w the node's
  // tributary length on the surface and h the element size through the wall: the stiffness
  // of the material column under the node (scene key `contact_penalty_scale`).
  double penalty_scale = 1.0;
  // Thesis §3.6.3 junction smoothing of the quadratic master segments (ISL22 SMOOTH):
  // fraction of each segment's parameter length replaced by a Hermite cubic at a junction.
  // 0 = no smoothing; must lie in [0, 0.5).
  double smoothing = 0.25;
  bool self_contact = true;  // inner wall against itself (lock-up)
  // Symmetric, no one-sided penetration: RingContact (static) runs both halves as slave and
  // as master; the chain model runs every inner node against the whole inner wall
  // (ring_pair_contact.hpp). false: the lower half on the upper only.
  bool self_contact_two_pass = true;
  // Inner-wall points closer than this (reference arc angle) are joined by the wall itself
  // and never paired. 0.2 rad (11.5°, about three wall thicknesses of inner arc at t/D 0.03):
  // the legs of a side fold closed by lock-up touch much nearer the fold than the former π/3,
  // which let them pass through each other unseen and stopped the high-energy HHT runs (README
  // "FE dynamics", stability matrix; tests/fe/fold_contact_test.cpp). A wall bent into a crease
  // of radius 0.02 mm still pairs no point with its own neighbourhood (same test).
  double self_contact_min_separation_rad = 0.2;
  // Chain surface contact (ring↔ring, inner wall; fe/contact/contact_arrival.hpp): a new
  // (node, surface) pair may start acting only if first seen at most this fraction of the
  // penalty's reach (one through-wall element depth) inside; once acting it stays so, past
  // the reach, until its gap opens. A real contact is first seen shallow (a step moves a node
  // a small part of the wall depth); one first seen deep is a node behind its own creased
  // wall (scene key `contact_arrival_depth`, in (0, 1]; 1: any pair within the reach).
  double arrival_depth = 0.5;
  // Coulomb friction, penalty-regularised, at the rigid plates (fe/contact/plate_friction.hpp)
  // and on the inner wall against itself (slip along the smoothed surface, ring_contact.hpp);
  // scene key `friction_coefficient`. 0 = frictionless, the thesis: the friction code is then
  // skipped entirely and the tangent stays symmetric (LDLᵀ); otherwise LU.
  double friction_coefficient = 0.0;
  // Tangential (stick) penalty of a contact node = tangential_penalty_scale · E · L · w / h,
  // scaled exactly as the normal penalty (scene key `friction_penalty_scale`): the elastic
  // slip before sliding is μ f_n / k_t = μ · (normal penetration) · penalty_scale /
  // tangential_penalty_scale, about 2 µm at 0.1 and μ = 0.2 on the thesis crush, far below an
  // increment's travel. Measured on the thesis crush (μ = 0.3): 0.01 … 0.3 give the same load
  // to 0.1 %; at 0.3 and above Newton chatters between stick and slip at the edge of the
  // contact zones and runs fail with μ = 0.1–0.3, hence 0.1.
  double tangential_penalty_scale = 0.1;
};

struct StaticSolverInput {
  double crush_m = 0.046;           // driven (top) plate travel
  double initial_increment = 0.01;  // fractions of the total travel (thesis *STATIC line)
  double min_increment = 1e-5;
  double max_increment = 0.01;
  int max_iterations = 10;          // thesis CYCLE: M iter of §3.4
  int max_increments = 5000;
  double force_tolerance_n = 6.0;   // PTOL: largest residual force component, half model
  // Largest Newton correction / largest displacement increment of the step; both tests
  // must pass (residual alone can be met by a stiff contact before the state settles).
  double correction_tolerance = 1e-2;
  bool line_search = true;          // named robustness option (STYLE.md practice 13)
  int frames = 20;                  // field snapshots over the run (0: none)
};

struct FeInput {
  RingInput ring;
  MaterialInput material;
  MeshInput mesh;
  Integration integration = Integration::Selective;
  ContactInput contact;
  StaticSolverInput solver;
};

// Throws std::invalid_argument naming the first inconsistent value.
void validate(const FeInput& input);

}  // namespace ringcrush::fe
