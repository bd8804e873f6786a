// Hinge length of the Level 2 polygon ring that reproduces Redwood's hardening curve
// (issue 7 verification a; THEORY §1.4, §4.3).
//
// Redwood's ring hardens as M = M0 (1 + k θ), k = E′/(3 σ0 α): the plastic rotation θ of each
// hinge concentrated on a length α t. A polygon node with the same law, H_θ = E′ I/(α t),
// gets less than the whole hinge rotation — it spreads over the nodes a travelling hinge
// passes and the neighbours of the side hinges — and the ring carries only 0.82–0.89 of
// Redwood's load at α = 2 (δ/d 0.2–0.5, N = 48). The fitted hinge length l_h below replaces
// α t in H_θ = E′ I / l_h so that a single polygon ring between plates follows Redwood's curve
// for the given α:
//
//   l_h / ℓ0 = 0.119 α + 0.0432 α²,   ℓ0 the polygon's bar length,
//
// fitted on the Test 30 ring (D/t = 31.75, E′ = 2.224 GPa, rigid–plastic flow) at α = 1 and 2
// (mean of P/P_Redwood over δ/d ∈ [0.2, 0.5] equal to 1) and checked at α = 4 (the fit gives
// l_h = 2.348 t·(ℓ0/3.22 mm) against 2.366 measured). It scales with ℓ0 — the spread is a
// physical length, so at N = 96 the same α needs half the N = 48 value — which
// tests/hinge/polygon_redwood_test.cpp checks at N = 48 and 96. Outside α ∈ [1, 4] it is an
// extrapolation and refused.
#pragma once

namespace ringcrush::hinge {

// l_h (m) for Redwood's α and the polygon's bar length ℓ0 (m); std::invalid_argument for
// α outside [1, 4] or ℓ0 ≤ 0.
double redwood_hinge_length(double alpha, double bar_length_m);

}  // namespace ringcrush::hinge
