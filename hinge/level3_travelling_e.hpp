// Level 3 travelling hinge E of the ring underneath a wrapping ring (thesis §4.2.3, Fig.
// 4.2.3-2; THEORY §4.5 "Ring underneath: hinges E (θ_E′), C, B; no hinge at A").
//
// Which hinge travels. The thesis: the wrapped ring above "prevents a plastic hinge at A and
// causes its formation at E", which makes C "drop markedly"; contact forces act "mainly on
// the arc A–E and around B"; and (citing Owens & Symonds) "in our model the movement of the
// plastic zone is justified by the variation of the load application point". In the Level 3
// chain A, C, B sit on symmetry points and stay fixed; F of the wrapping ring travels
// (level3_travelling_f.cpp); the wrapping ring's upper arc is the DeRuntz–Hodge quadrant
// (under a point load at A the least-load E is A itself, below, so no separate E forms there
// in a massless chain: the Owens–Symonds E is an inertia effect). The E that travels is the
// ring underneath's: the edge of the cap held by the wrapped ring, moving as that contact
// spreads.
//
// Mechanism E–C–B on the current shape (half ring, cap A–E held: the reference frame):
//   segment E–C rigid, turning about E at ω₁;  segment C–B′ rigid, turning at ω₂;
//   B′ = the bottom contact edge (B itself on a round bottom), sliding on the axis line:
//     ẋ_B′ = −ω₁ (y_C − y_E) − ω₂ (y_B′ − y_C) = 0,
//   crush rate (B′ rising towards the cap)  δ̇ = ω₁ (x_C − x_E) + ω₂ (x_B′ − x_C),
//   dissipation (both halves)  Ḋ = 2 M0 (|ω₁| + h |ω₂ − ω₁| + h |ω₂|), h the Redwood factor
//   the hinges C and B have already hardened to in the ring's earlier crush (1: none; E is new),
//   load by virtual work       P(θ_E) = Ḋ / |δ̇|.
// Undeformed circle (closed form): P(θ_E) = (4 M0/R)(1 + cos θ_E)/(1 + cos θ_E − sin θ_E);
// dP/dθ_E = (4 M0/R)(1 + cos θ_E)/(1 + cos θ_E − sin θ_E)² > 0, so the least load is at the
// symmetry point θ_E = 0 (E = A: the four-hinge DeRuntz–Hodge onset, P = P0).
//
// Shear-free E: the stationary point dP/dθ_E = 0 (Q = 0 at E, the argument of
// level3_travelling_f.cpp) over θ_E ∈ [θ_cap, 89°], where θ_cap is the material edge of the
// held cap; when the least load sits on θ_cap (as on the circle), E is pinned to the edge of
// the contact pressure (the shear jumps there) and travels with it.
#pragma once

#include "level3_mechanism.hpp"

namespace ringcrush::hinge {

struct EHingeRate {
  double theta_e = 0.0;     // material angle of E from the top apex (rad)
  double omega_ec = 0.0;    // rotation rate of E–C (per unit crush rate)
  double omega_cb = 0.0;    // rotation rate of C–B′
  double load = 0.0;        // virtual-work load P(θ_E) (N); +∞ if the mechanism cannot crush
};

// The E–C–B mechanism on `shape` with E at theta_e ∈ (0°−, 90°): throws std::invalid_argument
// outside [0, 89°] or on a bad shape.
EHingeRate level3_e_rate(const Level3Shape& shape, double plastic_moment_nm, double theta_e, double hardening = 1.0);
// The least-load (shear-free) E over [theta_cap, 89°].
EHingeRate level3_shear_free_e(const Level3Shape& shape, double plastic_moment_nm, double theta_cap,
                               double hardening = 1.0);
// The held cap of `lower` under `upper` (both in chain coordinates, as stacked by the
// chain): the largest material angle θ ≤ 89° up to which every point of `lower`'s upper
// quadrant lies within `gap` of `upper`'s mean line (THEORY §4.6's contact band, 1.1 t).
double level3_held_cap(const Level3Shape& upper, const Level3Shape& lower, double gap);

}  // namespace ringcrush::hinge
