// Geometric measures of deformed rings and chains (THEORY.md §4.6), implemented once and fed
// by every model (FE nodes, polygon-ring nodes, hinge-model crushes). Pure functions.
//
// Conventions: the chain axis is y, ring 1 on top, the impactor coming down from +y. A ring
// shape is its mean line (or its outer surface, see RingShape::surface_offset) as points
// ordered by material angle θ measured from the ring's top apex A (θ = 0) through the side
// C (θ = π/2) to the bottom B (θ = π); a full ring continues to 2π, a half ring (the x ≥ 0
// symmetry model of the thesis) stops at π and its lengths and angles are doubled.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace ringcrush::compare {

struct RingShape {
  std::vector<Eigen::Vector2d> points;   // current positions
  std::vector<double> material_angle;    // θ of each point in the reference ring (rad)
  bool half = false;                     // points cover θ ∈ [0, π] only (x = 0 symmetry)
  // Added to the y-extent of the points to get the outer extent: t for a mean line,
  // 0 when the points are already on the outer surface.
  double surface_offset = 0.0;
};

// Extent H of the ring along the chain axis (outer surface).
double axial_extent(const RingShape& ring);
// Crush δ = H0 − H and crush ratio c = δ/D of a ring of outer diameter D.
double crush(const RingShape& ring, double outer_diameter);
double crush_ratio(const RingShape& ring, double outer_diameter);

// Wrapped angle W of `upper` over `lower` (degrees): the material-angle extent of the cap of
// `lower`'s points, contiguous from its top apex, that lie within `cap_distance` of
// `upper`'s polyline (THEORY §4.6: 1.1 t between mean lines). Whole-ring angle (a half
// ring's extent is doubled), in [0, 360].
double wrapped_angle_deg(const RingShape& upper, const RingShape& lower, double cap_distance);

// Inverted arc of the ring's lower half (θ ∈ [π/2, 3π/2]): the points whose curvature has
// reversed sign, i.e. whose turning angle is opposite to the ring's overall turning by more
// than `turning_tolerance` rad (default: a tenth of 2π/N, N points per whole ring).
//   length S (m): the arc those points span;
//   turning T (deg): how far they turn back, Σ |turning| over them (the integral of the
//   reversed curvature over the arc, ∫⟨−κ⟩ ds).
// Whole-ring values (doubled for a half ring; a half ring's end points A and B, on the
// symmetry axis, turn against their mirrored neighbour and count once).
struct InvertedArc {
  double length_m = 0.0;
  double turning_deg = 0.0;
};
InvertedArc inverted_arc(const RingShape& ring, double turning_tolerance = -1.0);
double inverted_arc_length(const RingShape& ring, double turning_tolerance = -1.0);

// The wrap-around flag (issue "Hinge model II" item 3, THEORY §4.6–4.7): a quarter of the lower
// half reversed, in length or in angle — S > 0.25 π R or T > 45° (a quarter of the lower half's
// 180° of turning). The wrapped angle W cannot tell a wrap from two flattened rings lying on
// each other, and in free chains a wrapped arc can bridge the next ring's apex with a small gap
// so that W, contiguous from the apex, reads 0: W is reported as supporting evidence only.
// Why both: S alone (sessions 6–17) reads a reversal concentrated in a fold short, and the
// shorter the finer the mesh: the FE's free Test 30 ring 1 turns its lower half back by 75°,
// as much as the welded ring 1 (77°), but two thirds of it in one fold at B, so S was 19.3 mm
// on 48 × 2 and 15.8 mm on 72 × 2 while T stayed at 75–79° (data/fold_diagnosis/, README
// "FE against the hinge model", session 18). T alone misses the wide, gentle reversals of rings
// flattened at 40–50 m/s (S 25–32 mm at T 13–20° in Level 2). On the 13 FE reference cases
// and their Level 2 runs every ring below both thresholds has T ≤ 34° and S ≤ 19.3 mm.
struct WrapThresholds {
  double min_inverted_arc_fraction = 0.25;
  double min_inverted_turning_deg = 45.0;
};

bool wrap_flag(const InvertedArc& arc, double mean_radius, const WrapThresholds& thresholds = {});

struct WrapMeasure {
  double wrapped_angle_deg = 0.0;
  double inverted_arc_m = 0.0;
  double inverted_turning_deg = 0.0;
  bool wrap_around = false;
};

// Wrap-around of ring i over ring i+1, with the flag from wrap_flag(). lower == nullptr when
// ring i has no ring below it to wrap around — the last ring (on the target) or any ring of a
// plated chain: W = 0 and no flag, whatever S is (a ring flattened beyond c ≈ 0.84 against a
// plate has inverted kinks of S ≈ 20–24 mm, above the threshold, in the FE Test 31 plated run;
// the inverted arc measures a wrap only when there is a ring to wrap over).
WrapMeasure measure_wrap(const RingShape& ring, const RingShape* lower, double mean_radius,
                         double wall_thickness, const WrapThresholds& thresholds = {});

// Heights of the ring's top and bottom halves (thesis §4.2.1: ring 2 "keeps its top nearly
// intact while its bottom flattens"): the outer surface's extent above and below the side
// point C (material angle π/2, and 3π/2 on a full ring, averaged), each divided by the
// undeformed outer radius, so an intact ring gives 1 and 1 and a half flattened against
// its neighbour gives a value near t/(D/2). Unlike the crush (the sum of the two losses) it
// tells which half gave way.
struct HalfHeights {
  double top = 0.0;     // (y_max − y_C) / (D/2)
  double bottom = 0.0;  // (y_C − y_min) / (D/2)
};
HalfHeights half_heights(const RingShape& ring, double outer_diameter);

// Deformation mode of a ring from its final crush ratio and wrap flag: "wrapped" when the
// flag is set, else "flattened" (c ≥ 0.5), "crushed" (c ≥ 0.1) or "intact".
std::string deformation_mode(double crush_ratio, bool wrap_around);

struct Alternation {
  double lag1 = 0.0;               // A1: −Σ r_i r_{i+1} / Σ r_i² of the detrended crushes
  double amplitude = 0.0;          // A2: mean |c_{i+1} − c_i|
  double sign_change_fraction = 0.0;  // sign changes of c_{i+1} − c_i over N − 2
  double index = 0.0;              // max(0, A1) × sign_change_fraction: 0 for monotone
};

// Alternation of the final crush ratios along the chain (ring 1 first). The detrending fit
// excludes the last (target-end) ring; differences smaller than `difference_tolerance`
// count neither as a rise nor as a fall. Chains of fewer than 3 rings give all zeros.
Alternation alternation(const std::vector<double>& crush_ratio, double difference_tolerance = 0.05);

// Threshold above which a chain is said to alternate (documented in README "Measures").
inline constexpr double alternation_threshold = 0.3;

}  // namespace ringcrush::compare
