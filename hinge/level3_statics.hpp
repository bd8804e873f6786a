// Level 3 statics check (lower-bound check of a mechanism, THEORY §4.5; thesis §4.2.3).
//
// A rigid-plastic mechanism gives an upper bound on the collapse load (its virtual-work
// load). It is the true collapse mechanism only if a moment field in equilibrium with that
// load stays within |M| ≤ M0 everywhere (the lower-bound theorem). The check here takes the
// current half-ring shape (Level3Shape, θ from A at 0 to B at π, x = 0 the symmetry plane),
// puts the ring's load P as two point contacts — P/2 on the half at the top contact edge and
// P/2 at the bottom contact edge (the outermost points of the top and bottom flats, where a
// flattening hinge hands the load over, as in the DeRuntz–Hodge mechanism) — and finds, over
// the two redundants of the half ring (the horizontal force H and the moment M_A at the
// section through A; the shear there is zero by symmetry), the least possible max |M|/M0.
//   ratio ≤ 1: a statically admissible field exists at yield or below; the mechanism load is
//              the collapse load (both bounds meet when ratio = 1).
//   ratio > 1: no field can carry P with |M| ≤ M0: under these contacts the mechanism is not
//              the collapse mechanism — another hinge (at `angle_deg`, where |M| peaks) would
//              form first; P/ratio is a lower bound on the true collapse load.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "level3_mechanism.hpp"

namespace ringcrush::hinge {

// The top and bottom contact edges of a half-ring shape (see above): the index of the last
// shape point on each flat and the edge itself. A flat drawn as a polyline generally ends
// between two shape points (the tangent point of the arc that follows); the edge is placed
// there by fitting y = y_flat − a (x − x₀)² through the next two points (exact for a parabola,
// O(h³) off for the drawn circular arcs) so the load's lever arm does not depend on where
// the points fall.
struct Level3Contacts {
  std::size_t top = 0, bottom = 0;
  std::array<double, 2> top_edge{}, bottom_edge{};
};
Level3Contacts level3_contact_edges(const Level3Shape& shape);

struct Level3Statics {
  double peak_ratio = 0.0;          // min over (H, M_A) of max |M|/M0 along the half ring
  double angle_deg = 0.0;           // material angle of the first point at that peak
  // Every place the optimal field reaches the peak (runs of adjacent points merged): the
  // optimum touches it at ≥ 2 places (equioscillation), the hinges of the collapse field.
  std::vector<double> peak_angles_deg;
  double horizontal_force_n = 0.0;  // H at the section through A (the optimum)
  double moment_a_nm = 0.0;         // M_A (the optimum)
  std::vector<double> moment_nm;    // M at every shape point (the optimal field)
};

// load_n: the ring's contact force P (> 0 or 0); M0 > 0. Throws std::invalid_argument on a
// shape with fewer than 3 points, a non-increasing θ, or a negative / non-finite load.
Level3Statics level3_statics_check(const Level3Shape& shape, double load_n, double plastic_moment_nm);

// Acceleration {x, y} of the material point at angle θ ∈ [0, π] from the top in the
// DeRuntz–Hodge mechanism, in the frame of the ring's centre (THEORY §1.3: flat of material
// length Rφ, arcs rolling about the travelling hinges; the lower half mirrors the upper).
std::array<double, 2> level3_uniform_relative_accel(double radius_m, double theta, double phi, double phi_rate,
                                                    double phi_accel);

// The check under a ring's own loads: top_n/2 down at the top contact edge, bottom_n/2 up at
// the bottom one, and on every shape point the d'Alembert load −m a of its share of the half
// ring's mass (θ-spacing, m_r/2π per radian), a = the centre's acceleration plus the
// DeRuntz–Hodge relative one. With mass 0 and top = bottom = P it is level3_statics_check
// (shape, P, M0). Throws std::invalid_argument on a non-finite force, acceleration or rate, a
// negative mass, a relative motion without a radius, and on loads out of balance
// (|top − bottom − m_r ẅ| > 1e-9 of the largest).
Level3Statics level3_statics_check(const Level3Shape& shape, const Level3RingLoads& loads, double plastic_moment_nm);

// One output state of the chain (hinge/level3_chain_check.cpp): every ring's statics check
// under the chain force (the largest ratio kept in `rings` with its angle and time) and, for
// a ring under a wrap, the held cap, E and the E–C–B load against the bottom mechanism's.
// With ring inertia, `loads` holds each ring's own loads (one per state; force_n unused);
// empty: every ring under force_n.
void level3_check_states(const Level3Input& in, const WrapMechanism& w, const std::vector<Level3RingResult>& states,
                         double force_n, double time_s, std::vector<Level3RingResult>& rings,
                         const std::vector<Level3RingLoads>& loads = {});

// The checks over a run (simulate_level3 and simulate_level3_inertial): at most ~200 evenly
// spread output states, every mechanism change and the last; the E of a ring that did not
// turn it reported at its checked angle.
void level3_check_history(const Level3Input& in, Level3Result& res);

}  // namespace ringcrush::hinge
