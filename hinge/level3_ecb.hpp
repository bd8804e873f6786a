// Level 3 E–C–B mechanism of the ring underneath a wrapping ring as a FLOWING mode (thesis
// §4.2.3: the wrapped ring "prevents a plastic hinge at A and causes its formation at E", and
// C "drops markedly"; THEORY §4.5; issue 7 item 2). The onset rate of the same mechanism on a
// drawn shape is hinge/level3_travelling_e.hpp (level3_e_rate); this is its finite-rotation
// trace on the chain's analytic ring state.
//
// Ring frame of level3_ring_shape (C = (R, 0), axis x = 0). The state it starts from: upper
// quadrant DeRuntz–Hodge at φ (frozen when the ring was reinforced), lower quadrant at ψ_s
// (the bottom mechanism's angle at the switch). Cap A–E held (the reference frame):
//   E–C rigid, turning anticlockwise by β about E:   C(β) = E + Rot(β)(C₀ − E);
//   C–B′ rigid, turning clockwise by q about C:      B′ = C(β) + Rot(−q)(B′₀ − C₀);
//   B′ = the bottom flat's edge (B on a round bottom) slides on the line x = x_B′₀ (the flat
//   B–B′ is inextensible and B stays on the axis by symmetry), which gives β(q);
//   crush δ(q) = y_B′(q) − y_B′₀ (B′ rising towards the held cap).
// Hinge rotations: E β, C β + q, B′ q, all growing monotonically along the trace. Hinge moment
// M0 (1 + k θ_h) (Redwood's law of the other modes), θ_h the hinge's rotation counted from
// e_start at E (φ at the top flat's edge, where the uniform mechanism's travelling hinge sits;
// 0 on the rigid quadrant beyond it) and from ψ_s at C and B′ (they carried the bottom
// mechanism), so
//   D(q) = 2 M0 [G(e_start, β) + G(ψ_s, β + q) + G(ψ_s, q)],   G(a, Δ) = Δ + k (a Δ + Δ²/2)
// (both halves), exactly; the load P = dD/dδ = (dD/dq)/(dδ/dq) at the table nodes, exactly
// too; at q = 0 it is level3_e_rate's virtual-work load with hardening 1 + kψ_s at C and B′.
// The trace ends (geometric limit) where C–B′ turns level (B′ at its reach), β(q) has no
// solution (C level with E), or B′ stops rising, whichever first.
//
// Position of E: fixed at formation. The thesis's hinges turn "about fixed positions"
// (§4.2.3); once E turns, the cap A–E is one rigid body pressed by the wrapped ring, so the
// contact edge the shear-free E sits on (level3_travelling_e.hpp: dP/dθ_E > 0 on every state
// tried, E pinned to the cap edge) is carried with the cap and does not sweep new material;
// a travelling E would need the cap to deform, which no hinge of this mechanism allows.
// So θ_E is chosen once, when the ring is reinforced (level3_mechanism.cpp: the scene's E,
// moved out to the top flat's edge φ if it lies on the flat), and the trace is one degree of
// freedom. Second-order overlaps it leaves (rigid-plastic kinematics, no contact law): the
// arc beyond E rises above the held cap by ≈ Rβ²/2 and the arc beside B′ dips below the flat
// by ≈ Rq²/2 (0.79 mm each at the limit of Test 30's ring from φ = ψ = 60.6°, t = 1.6 mm).
#pragma once

#include <array>
#include <vector>

#include "level3_mechanism.hpp"

namespace ringcrush::hinge {

// The three hinge points of the E–C–B mechanism on the ring state (φ, ψ, θ_E), ring frame.
struct EcbPoints {
  std::array<double, 2> e, c, b;  // E, C, B′
  // Rotation E's hardening counts from: φ when E sits on the top flat's edge — the place of
  // the uniform mechanism's travelling hinge, which carries Redwood's 1 + kφ like every hinge
  // of that mechanism (§4.1.2) — and 0 for an E out on the rigid quadrant (no plastic work
  // there yet).
  double e_start = 0.0;
};
EcbPoints level3_ecb_points(const Level3Ring& r, double phi, double psi, double theta_e);

// One point of the trace: β and the crush at q, the rates per unit q and the load.
struct EcbPose {
  double q = 0.0, beta = 0.0, crush = 0.0;
  double dbeta = 0.0, dcrush = 0.0;  // dβ/dq, dδ/dq
  double dissipation = 0.0, load = 0.0;
  bool valid = false;  // false past the geometric limit
};
EcbPose level3_ecb_pose(const Level3Ring& r, const EcbPoints& p, double psi, double q);

// The virtual-work load at the onset (q = 0) on the state (φ, ψ, θ_E): what the chain holds
// against the bottom mechanism's load while the ring flows in the bottom mode.
double level3_ecb_onset_load(const Level3Ring& r, double phi, double psi, double theta_e);

// The trace tabulated over q ∈ [0, q_lim] (uniform in q), interpolated like the wrap table
// (cubic Hermite in δ, work = its exact integral).
struct EcbMechanism {
  double phi = 0.0, psi = 0.0, theta_e = 0.0;
  EcbPoints points;
  std::vector<double> q, beta, crush, dissipation, load;
  double capacity() const { return crush.back(); }
  double load_at(double d) const;
  double slope_at(double d) const;
  double energy_at(double d) const;
  // q and β at crush d (linear between the nodes; for the shapes and the hinge map).
  double q_at(double d) const;
  double beta_at(double d) const;
};
// Draws the E–C–B state of `s` (s.ecb_started) on the bottom-mode polyline of the ring frame
// (level3_ring_shape before its offset): E inserted, the points beyond E up to C turned with
// E–C (rigid arc), the arc C–B′ turned with C–B′ (rigid arc), the flat B–B′ raised with B′,
// the cap A–E left round. Returns y of B′.
double level3_ecb_draw(const Level3Ring& r, const Level3RingResult& s, std::vector<std::array<double, 2>>& points,
                       std::vector<double>& theta);

EcbMechanism level3_ecb_mechanism(const Level3Ring& r, double phi, double psi, double theta_e, int samples = 120);

}  // namespace ringcrush::hinge
