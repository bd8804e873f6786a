// Level 3 (THEORY §4.5): few-hinge rigid-plastic mechanisms of the thesis (§4.2.3) and a
// chain of them with mode selection by the dissipation rate of the competing mechanisms.
//
// Mechanisms of one ring (half ring, x = 0 symmetry, material angle θ from the top apex A):
//   Uniform  DeRuntz–Hodge: rigid quadrants turning by φ about the side hinges C (θ = 90°),
//            travelling flattening hinges at A and B; δ = d sin φ, P = P0 (1 + kφ)/cos φ.
//   Wrap     the wrapping ring's lower arc: rigid arc C–F turning about C (hinges C and F,
//            F at θ_F), and the arc F–B yielding along its length (the thesis's "spread
//            yielding along B–C") from its curvature 1/R to −1/(R + t), i.e. inverted over
//            the round top of the next ring. One degree of freedom (the arc curvature κ),
//            closure x_B = 0; the load is dD/dδ from the segment geometry (virtual work),
//            tabulated numerically. Rate-independent, no hardening.
//   Bottom   the ring underneath a wrapping ring (hinges E, C, B, none at A): the cap A–E
//            is held by the wrapped ring, the lower quadrant turns about C and flattens at
//            B; δ = R (sin ψ − sin ψ0), P = P0 (1 + kψ)/cos ψ from the current ψ0.
//   Ecb      the ring underneath turning E (hinges E, C, B′; hinge/level3_ecb.hpp): cap A–E
//            held, E–C turning about E, C–B′ about C, B′ on its line; traced with finite
//            rotations and tabulated like the wrap. Selected against Bottom by least load
//            (Level3RingUnder::LeastLoad), one-way.
//
// The chain (simulate_level3): rings in series between the impactor (mass M) and a fixed
// target, ring inertia neglected (a massless, quasi-static rigid-plastic chain, so the
// force F is common to every ring). The mechanisms whose load equals F flow, sharing the
// impactor velocity so that their loads stay equal (hardening) or, if one softens, that
// one alone; mode selection = the admissible mechanism of least load (dissipation rate per
// unit shortening) at each event. Events: a mechanism reaches F (yield onset), a softening
// mechanism turns hardening, a mechanism reaches its geometric limit (lock), impactor at
// rest. Hinge positions: A, C, B fixed by symmetry; θ_F given, or chosen once to minimise
// the wrap onset load (upper-bound theorem: among fixed-hinge mechanisms the one of least
// load), or travelling by the shear-free condition (Level3HingeF::ShearFree,
// hinge/level3_travelling_f.cpp): at every instant F sits where the virtual-work load of the
// current configuration is stationary in the hinge position, which is where the shear
// vanishes at F; E (of the Ecb mechanism) is fixed where it forms, at the held cap's edge or
// the scene's θ_E, not inside the top flat.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "hybrid_system.hpp"

namespace ringcrush::hinge {

struct Level3Ring {
  double outer_diameter_m = 0.0;
  double wall_thickness_m = 0.0;
  double plastic_moment_nm = 0.0;  // M0 of the whole width
  double hardening_k = 0.0;        // Redwood's E′/(3σ0α); 0: DeRuntz–Hodge
  double mean_diameter() const { return outer_diameter_m - wall_thickness_m; }
  double mean_radius() const { return 0.5 * mean_diameter(); }
  double collapse_load() const { return 8.0 * plastic_moment_nm / mean_diameter(); }  // P0
  void validate() const;
};

// Ecb: the ring underneath flowing in the E–C–B mechanism (hinge/level3_ecb.hpp).
enum class Level3Mode { Uniform, Wrap, Bottom, Ecb };
std::string to_string(Level3Mode);

// Uniform (DeRuntz–Hodge) mechanism in closed form: load, slope dP/dδ and work at crush δ.
double level3_uniform_load(const Level3Ring& r, double crush);
double level3_uniform_energy(const Level3Ring& r, double crush);

// A load table in δ (nodes `crush` increasing, `load` there): cubic Hermite load, its slope
// and its exact integral from crush[0] (so a mechanism's work is ∫ P dδ of what the chain
// integrates). Used by the wrap and the E–C–B tables.
double level3_table_load(const std::vector<double>& crush, const std::vector<double>& load, double q);
double level3_table_slope(const std::vector<double>& crush, const std::vector<double>& load, double q);
double level3_table_energy(const std::vector<double>& crush, const std::vector<double>& load, double q);

// The wrap mechanism of the lower arc, tabulated over κ ∈ [1/R, −1/(R+t)].
struct WrapMechanism {
  double theta_f = 0.0;               // F (rad from the top apex); travelling: at the onset
  std::vector<double> curvature;      // κ_j (travelling: the curvature at B)
  std::vector<double> crush;          // δ_j (rise of B relative to C), increasing
  std::vector<double> dissipation;    // D_j = ∫ M0 (2|dα| + 2|d(κS) − dα| + 2S|dκ|)
  std::vector<double> load;           // dD/dδ at the nodes
  std::vector<double> chord_angle;    // α_j of the rigid chord F→C
  // Travelling F only (empty for a fixed F): θ_F at each node, the accumulated hinge
  // rotations at C and F (one half), and the tangent angle of every cell of the lower
  // quadrant (C → B, edges `cell_edges`) at each node, for the shapes.
  std::vector<double> hinge_f, rotation_c, rotation_f;
  std::vector<std::vector<double>> tangent;
  std::vector<double> cell_edges;  // arc length from C of the cell edges (one more than cells)
  bool travelling() const { return !tangent.empty(); }
  double theta_f_at(double q) const;  // θ_F at wrap crush q (linear between the nodes)
  double capacity() const { return crush.back(); }
  // Piecewise-linear load in δ and its exact integral (so the work is consistent).
  double load_at(double q) const;
  double slope_at(double q) const;
  double energy_at(double q) const;
};
WrapMechanism level3_wrap_mechanism(const Level3Ring& r, double theta_f, int samples = 120);
// θ_F ∈ [100°, 170°] minimising the wrap onset load (golden section).
double level3_optimal_theta_f(const Level3Ring& r);

// Travelling F (hinge/level3_travelling_f.cpp). The lower quadrant C → B as n cells of
// tangent angle β_k (arc length from C; undeformed β = −π/2 − u/R). The instantaneous wrap
// mechanism on such a configuration with F at θ_F: C–F turns rigidly about C (rate ω_C),
// hinge F (ω_F), the arc F–B bends at unit curvature rate; B stays on the axis with a
// horizontal tangent. load = dissipation rate / rate of rise of B (virtual work). Cells:
// `edges` (arc length from C, cells + 1 values), or n equal cells if empty.
struct WrapRate {
  double theta_f, omega_c, omega_f, crush_rate, load;
};
std::vector<double> level3_undeformed_tangent(const Level3Ring& r, int cells);
WrapRate level3_wrap_rate(const Level3Ring& r, const std::vector<double>& tangent, double theta_f,
                          const std::vector<double>& edges = {});
// The shear-free F of the undeformed ring from the closed-form integrals of the circle.
WrapRate level3_onset_shear_free_rate(const Level3Ring& r);
// The shear-free F of a configuration: the stationary point (least load) of level3_wrap_rate
// over θ_F ∈ [91°, 179°].
WrapRate level3_shear_free_rate(const Level3Ring& r, const std::vector<double>& tangent,
                                const std::vector<double>& edges = {});
// The wrap traced with F travelling (shear-free at every step), tabulated as
// level3_wrap_mechanism (midpoint rule, one step per table interval; n = cells).
WrapMechanism level3_travelling_wrap_mechanism(const Level3Ring& r, int samples = 60, int cells = 90);

// How F is placed when no θ_F is given.
enum class Level3HingeF { LeastOnsetLoad, ShearFree };
std::string to_string(Level3HingeF);
// How E of a ring under a wrap is placed (hinge/level3_travelling_e.hpp): Fixed at
// Level3Input::theta_e, or ShearFree: the least-load E–C–B hinge on the current shape beyond
// the cap held by the wrapped ring, re-found at every output state. E is reported (hinge map,
// E–C–B load against the flowing bottom mechanism); the chain's bottom mechanism does not
// turn E. With Level3RingUnder::LeastLoad the E–C–B flows (hinge/level3_ecb.hpp) with E
// placed by this option when the ring is reinforced, moved out to the top flat's edge if on it.
enum class Level3HingeE { Fixed, ShearFree };
std::string to_string(Level3HingeE);

// The mechanisms of the ring underneath a wrap (THEORY §4.5): Bottom only (the chain before
// session 7), or LeastLoad: the least load of Bottom and E–C–B (hinge/level3_ecb.hpp) at
// every event. Once E has turned the ring stays in E–C–B (level3_mechanism.cpp, select).
enum class Level3RingUnder { Bottom, LeastLoad };
std::string to_string(Level3RingUnder);

struct Level3Input {
  int rings = 6;
  Level3Ring ring;
  bool plates = false;              // joints are plates: no ring can wrap its neighbour
  double impactor_mass_kg = 0.0;
  double impactor_velocity_m_s = 0.0;
  double theta_f = -1.0;            // >= 0: F fixed there; < 0: placed by hinge_f
  Level3HingeF hinge_f = Level3HingeF::LeastOnsetLoad;
  double theta_e = 0.7853981633974483;  // edge of the held cap (reported only)
  Level3HingeE hinge_e = Level3HingeE::Fixed;  // E of the flowing E–C–B: chosen once, at the reinforcement
  Level3RingUnder ring_under = Level3RingUnder::LeastLoad;
  // Ring inertia (hinge/level3_inertia.cpp): false, the massless chain above (one common F);
  // true, each ring's mass m_r at its centre and, in the Uniform mode, Level 1's distributed
  // inertia J(φ), a force per ring from the dynamics (needs ring_mass_kg > 0).
  bool inertia = false;
  double ring_mass_kg = 0.0;  // m_r of the whole ring (Level 1's RingLaw::mass_kg)
  void validate() const;
};

struct Level3Hinge {
  std::string name;        // "A", "C", "B", "F", "E", "B-F arc"
  double angle_deg;        // material angle from the top apex
  double first_yield_s;    // −1: never
  double rotation_rad;     // accumulated plastic rotation (arc: curvature change × length)
};

struct Level3RingResult {
  double crush_m = 0.0;              // δ_i (approach of the loading points)
  double uniform_crush_m = 0.0, wrap_crush_m = 0.0, bottom_crush_m = 0.0;
  double uniform_angle = 0.0;        // φ
  double wrap_curvature = 0.0;       // κ of the arc F–B (1/R undeformed; travelling: at B)
  double wrap_theta_f = 0.0;         // current θ_F (rad; 0 before the wrap)
  double bottom_angle = 0.0;         // ψ
  // E–C–B (hinge/level3_ecb.hpp): its crush, E (rad), ψ at the switch, and the rotations β
  // of E–C about E and q of C–B′ (rad); ecb_started once E has turned.
  double ecb_crush_m = 0.0, ecb_theta_e = 0.0, ecb_psi = 0.0, ecb_rotation_e = 0.0, ecb_rotation_cb = 0.0;
  bool ecb_started = false;
  Level3Mode mode = Level3Mode::Uniform;  // Wrap if its wrap was selected, Bottom / Ecb if under a wrap
  bool wrap_started = false;
  bool reinforced = false;           // under a wrapping ring
  std::vector<Level3Hinge> hinges;
  double plastic_work_j = 0.0;
  // Statics check (hinge/level3_statics.hpp) over the output states: the largest lower-bound
  // ratio max|M|/M_p under the chain force (with ring inertia: the ring's own contact forces
  // and d'Alembert load, Level3RingLoads), where and when (ratio > 1: another hinge needed);
  // M_p = M0 times the flowing mechanism's Redwood factor (1 + kφ, 1 + kψ; 1 for the wrap).
  double peak_moment_ratio = 0.0, peak_moment_angle_deg = 0.0, peak_moment_time_s = 0.0;
  std::vector<double> peak_moment_angles_deg;  // every place the field reaches that peak
  // Under a wrap, at the last state: the held cap edge, E (Fixed: theta_e; ShearFree: the
  // least-load E), the E–C–B load there and the bottom mechanism's load (both N).
  double held_cap = 0.0, theta_e = 0.0, e_mechanism_load_n = 0.0, bottom_load_n = 0.0;
  int e_cheaper_states = 0;  // checked states where E–C–B needed less load than the bottom mode
  double e_cheaper_time_s = -1.0;  // the first of them (−1: none); locked states are skipped
  // The same at the first output state under the wrap (the reinforcement event).
  double held_cap_onset = 0.0, theta_e_onset = 0.0, e_onset_load_n = 0.0, bottom_onset_load_n = 0.0;
};

// A ring with inertia (hinge/level3_inertia.cpp) carries different contact forces at top and
// bottom; the difference accelerates its mass (d'Alembert). Its loads for the statics check
// (hinge/level3_statics.hpp), one per ring and output state:
struct Level3RingLoads {
  double top_n = 0.0;         // contact force from above, pushing the ring toward the target (N)
  double bottom_n = 0.0;      // contact force from below, pushing it back (N)
  double mass_kg = 0.0;       // m_r, spread evenly along the mean line
  double centre_accel_m_s2 = 0.0;  // ẅ of the ring's centre toward the target: top − bottom = m_r ẅ
  // The DeRuntz–Hodge relative motion (the Uniform mode's own inertia J(φ), THEORY §1.3):
  // quadrant angle φ, its rate and acceleration; false in the modes whose own inertia the
  // chain neglects (Wrap, Bottom, E–C–B: only the centre translates).
  bool uniform_motion = false;
  double phi = 0.0, phi_rate = 0.0, phi_accel = 0.0;
  double radius_m = 0.0;  // mean radius R (the relative motion's lever)
};

struct Level3History {
  std::vector<double> time_s, impactor_displacement_m, impactor_velocity_m_s, force_n;
  std::vector<std::vector<double>> ring_crush_m;  // [ring][sample]
  std::vector<double> kinetic_j, plastic_j;
  // With ring inertia only (empty otherwise): the kinetic energy lost in plastic impacts so
  // far, and the force carried by each ring [ring][sample] (compression > 0).
  std::vector<double> impact_loss_j;
  std::vector<std::vector<double>> ring_force_n;
  std::vector<std::vector<Level3RingLoads>> ring_loads;  // [sample][ring] (inertia only)
  // [sample][ring] the mechanism state of each ring (crushes, angles, curvature, mode; no
  // hinge list or work), enough for level3_ring_shape: the shapes over time.
  std::vector<std::vector<Level3RingResult>> ring_state;
};

struct Level3Event {
  double time_s;
  std::string kind;   // "hinge_formed", "mode_selected", "ring_locked", "impactor_arrested"
  int ring;
  std::string detail;
};

struct Level3Result {
  Level3History history;
  std::vector<Level3RingResult> rings;
  std::vector<Level3Event> events;
  HybridOutcome outcome;
  double theta_f = 0.0;                     // at the wrap onset (travelling F moves on)
  WrapMechanism wrap;                       // the table the chain ran with
  double initial_kinetic_energy_j = 0.0;
  double plastic_work_closed_form_j = 0.0;  // Σ mechanism works from the final state
  double lock_loss_j = 0.0;                 // kinetic energy lost if the whole chain locks
  double impact_loss_j = 0.0;               // with inertia: plastic impacts and mode switches
  double energy_balance_error() const;      // max |KE + Dp + lock + impacts − KE0| / KE0
};

Level3Result simulate_level3(const Level3Input& in, const HybridOptions& options,
                             bool record_history = true);
// The chain with ring inertia (in.inertia; hinge/level3_inertia.cpp); simulate_level3
// dispatches to it.
Level3Result simulate_level3_inertial(const Level3Input& in, const HybridOptions& options,
                                      bool record_history = true);
// The inertial chain's analytic IDA Jacobian against one-sided second-order difference
// quotients of its right-hand side, at every state its run samples (each accepted step, both
// sides of each event): the largest difference of an entry over the largest entry of its
// column, the states and the columns compared (those of the crushing rings' rates and crushes).
struct Level3JacobianCheck {
  double worst_relative = 0.0;
  long states = 0;
  long columns = 0;
  double worst_time_s = 0.0;  // where the worst column is: time, ring (0-based), rate or crush
  int worst_ring = -1;
  bool worst_is_rate = false;
};
Level3JacobianCheck level3_inertial_jacobian_check(const Level3Input& in, const HybridOptions& options);

// Mean line of ring i's half (θ ∈ [0, π], 2 + 4·n points) in chain coordinates: ring top
// at y = top_y; the state of a Level3RingResult. Points as {x, y}; angles in `theta`.
struct Level3Shape {
  std::vector<std::array<double, 2>> points;
  std::vector<double> theta;
  double bottom_y = 0.0;  // y of B
};
Level3Shape level3_ring_shape(const Level3Ring& r, const WrapMechanism& w,
                              const Level3RingResult& s, double top_y, int n = 24);

}  // namespace ringcrush::hinge
