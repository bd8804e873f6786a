// The inner wall against itself, tapered at the edge of its exclusion (issue 4, verification g;
// README "FE dynamics", stability matrix).
//
// A point of the inner wall must never be paired with its own neighbourhood of the wall
// (ContactInput::self_contact_min_separation_rad of reference arc). Dropping the pairs inside
// that arc outright makes its edge a force jump: a node pressed into its own wall near a
// closed side fold loses its whole penalty force k·g when its closest point crosses the
// edge, and HHT's half-step residual (thesis §3.5) stays at about half that jump however
// small the step (measured: free chain, 50 m/s, ×4 mass, t/D 0.03, 7.5e5 N at ring 5's node
// 372, 0.35 mm into its own wall, the closest point clamped at the end of the last piece
// before the edge).
//
// Here the penalty energy of an inner-wall pair is ½ k w(Δ) g², Δ the reference arc between
// the slave and its closest point x(f) on the master (Δ(f) = |Σ c_a(f) φ_a − φ_s|, the node
// angles interpolated by the piece's own shape functions, so Δ is continuous along the C¹
// smoothed wall), and w a C¹ ramp: 0 up to the exclusion, 1 beyond it plus a band. The force
// is the exact gradient of that energy, so it stays a potential force (action = reaction,
// symmetric tangent) and falls continuously to zero at the edge.
#pragma once

#include <array>

#include "fe/contact/ring_pair_contact.hpp"

namespace ringcrush::fe {

// Band of arc beyond ContactInput::self_contact_min_separation_rad over which the penalty
// ramps from 0 to full (the chain model's inner-wall passes). 0.1 rad: about one element of
// arc at 16 elements per half ring, so the ramp spans at least one piece and the pairs that
// were active at full force under the bare cut beyond 0.3 rad are unchanged (every HHT case
// whose folds stay open past 17° of C, e.g. the thesis scene).
inline constexpr double kSelfContactTaperBandRad = 0.1;

// w(Δ) = 0 for Δ ≤ start, 3t² − 2t³ with t = (Δ − start)/band inside the band, 1 beyond
// (C¹: w' = 0 at both ends of the band). band = 0 is the bare cut at `start`.
struct ArcTaper {
  double start = 0, band = 0;
  // Throws std::invalid_argument naming a negative or non-finite start or band.
  ArcTaper(double start_rad, double band_rad);
  // w(Δ) and, if slope is not null, dw/dΔ.
  double weight(double delta, double* slope = nullptr) const;
};

// Reference arc Δ from the slave (angle slave_angle) to the point f of a piece whose node
// angles are piece_angle, and dΔ/df. Angles may wrap: each is taken relative to the slave.
double arc_to_closest_point(const PiecePolynomial& piece, const std::array<double, 5>& piece_angle,
                            double slave_angle, double f, double* slope);
// The same with the piece's node angles already unwrapped about its first node
// (unwrapped_piece_angles; constant per piece, so a search that asks Δ for many slaves does
// not redo the 2π reductions of the piece): bitwise the value above.
std::array<double, 5> unwrapped_piece_angles(const std::array<double, 5>& piece_angle, int count);
double arc_to_closest_point(const PiecePolynomial& piece, const std::array<double, 5>& piece_angle,
                            const std::array<double, 5>& unwrapped, double slave_angle, double f, double* slope);

// Force of a tapered inner-wall pair: ∂(½ k w(Δ(f)) g²)/∂coords for g < 0, else 0, with
// coords = [x_s, y_s, x_1, y_1, …] and f the closest point (as surface_force). Returns w.
// The term through Δ needs ∂f/∂coords, from differentiating (x(f) − x_s)·x'(f) = 0.
double tapered_self_force(const PiecePolynomial& piece, const double* coords, double k, double f, double gap,
                          const ArcTaper& taper, double slave_angle, const std::array<double, 5>& piece_angle,
                          double* force);

}  // namespace ringcrush::fe
