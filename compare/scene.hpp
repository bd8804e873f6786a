// Scene: the one description of a ring-chain problem that every model runs from
// (DESIGN.md "The contract"). Parsed from TOML once, validated once, then immutable.
// All values SI; the TOML keys carry their units (e.g. `outer_diameter_m`).
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ringcrush::compare {

// A scene that cannot be run: names the file, the key and the reason.
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, std::string key, std::string reason);
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, key_, reason_;
};

struct HardeningPoint {
  double yield_stress_pa;
  double plastic_strain;
};

struct Material {
  double youngs_modulus_pa;
  double poisson_ratio;
  double density_kg_m3;
  // Isotropic hardening, piecewise linear in equivalent plastic strain, flat after the
  // last point (thesis *PLASTIC). First point at plastic strain 0.
  std::vector<HardeningPoint> hardening;

  double initial_yield_stress() const { return hardening.front().yield_stress_pa; }
  // Slope of the first hardening segment (E′ of Tables 1–2); 0 for a single point.
  double hardening_modulus() const;
};

enum class SectionState { PlaneStress, PlaneStrain };

struct Rings {
  int count;
  double outer_diameter_m;
  double wall_thickness_m;
  double width_m;
  double pitch_m;  // distance between neighbouring ring centres (= D when touching)
  SectionState section;
  Material material;
};

enum class JointType { Welded, Free, Plates };
struct Joints {
  JointType type;
  double plate_mass_kg = 0.0;       // plates only
  double plate_thickness_m = 0.0;   // plates only
};

struct Impactor {
  double mass_kg;       // physical (full) mass; a half model uses half of it
  double velocity_m_s;  // speed toward the chain (dynamic analyses)
};

enum class FarEnd { Fixed, Free };
enum class AnalysisType { Static, Dynamic };
enum class Symmetry { Half, Full };

struct Analysis {
  AnalysisType type;
  double crush_m = 0.0;        // static: driven-plate travel
  double end_time_s = 0.0;     // dynamic: latest end
  bool stop_at_rest = true;    // dynamic: end once the impactor stops and rings are at rest
  Symmetry symmetry = Symmetry::Half;
};

enum class Integration { Full, Reduced, Selective };
enum class FeSolver { Static, Hht, Explicit };
enum class ExplicitStepBound { Element, Assembled };

struct FeSettings {
  int elements_around = 48;          // per half ring (the thesis's 48)
  int elements_through = 1;
  double grading = 1.0;              // element size ratio far/near the contact points
  Integration integration = Integration::Selective;
  FeSolver solver = FeSolver::Static;
  double hht_alpha = -0.105;         // Hilber: α ∈ [−1/3, 0]
  double initial_step_s = 5e-7;
  double haftol_n = 1e4;             // half-step residual tolerance (thesis §3.5)
  double ptol_n = 6.0;               // force residual tolerance (thesis PTOL)
  double initial_increment = 0.01;   // static: fraction of the total travel
  double min_increment = 1e-5;       // static: a smaller increment ends the run (thesis *STATIC)
  double max_increment = 0.01;       // static: largest increment (thesis *STATIC)
  int max_iterations = 10;           // static: Newton iterations per increment (thesis CYCLE)
  double contact_smoothing = 0.25;   // Hermite junction smoothing of slide lines (thesis SMOOTH)
  double contact_penalty_scale = 1.0;
  // Dynamic FE: > 0 lowers the penalty scale until the stiffest contact spring costs at most
  // this fraction of the explicit element step (fe/contact/penalty_step_cap.hpp); 0 = off.
  double contact_penalty_step_fraction = 0.0;
  // Dynamic FE: a new ring↔ring or inner-wall contact pair acts only if first seen at most
  // this fraction of the through-wall element depth inside (fe/contact/contact_arrival.hpp).
  double contact_arrival_depth = 0.5;
  double friction_coefficient = 0.0;
  double friction_penalty_scale = 0.1;  // tangential (stick) penalty, scaled as the normal one
  // Explicit step Δt = explicit_safety · 2/ω_max. The defaults (assembled, 0.8) were decided on
  // the stability matrix's hard cells (README "FE dynamics", session 12): the assembled
  // estimate lost no case the element bound brought to rest, and 0.8 of it is 0.77 of the true
  // limit; safety 0.9 lost a welded 100 m/s ×4 t/D 0.02 case that 0.8 brings to rest (and so
  // did 0.78: that cell's lock-up is a matter of trajectory, but 0.9 is not shown to keep it).
  double explicit_safety = 0.8;
  // Explicit: ω_max of the stable step from the assembled power-iteration estimate × 1.05,
  // never above the element bound (fe/dynamics/assembled_eigenvalue.hpp: 15 % fewer steps on
  // the thesis scene; an estimate, the default) or the element bound (element eigenvalues plus
  // the contact springs: a bound, 7 % below the assembled estimate's step).
  ExplicitStepBound step_bound = ExplicitStepBound::Assembled;
  double bulk_viscosity = 0.06;      // explicit: linear bulk viscosity b1 (ABAQUS/Explicit default)
  // Explicit only, off by default (a change of the physics; fe/dynamics/mass_scaling.hpp):
  // ABAQUS *FIXED MASS SCALING, DT= / TYPE=BELOW MIN (target step, s; 0 = off) and FACTOR= /
  // TYPE=UNIFORM (density multiplier ≥ 1; 1 = off).
  double mass_scaling_dt = 0.0;
  double mass_scaling_factor = 1.0;
  double energy_error_limit = 0.05;  // stop when |balance error| / KE0 exceeds this
};

// central_difference: explicit leapfrog, Level 2 only (hinge/polygon_central_difference.hpp).
enum class HingeIntegrator { Ida, Odeint, CentralDifference };
inline const char* hinge_integrator_name(HingeIntegrator i) {
  return i == HingeIntegrator::Ida ? "ida" : i == HingeIntegrator::Odeint ? "odeint" : "central_difference";
}
struct HingeSettings {
  std::string level = "1";  // "0", "1", "2", "3" or "shock"
  HingeIntegrator integrator = HingeIntegrator::Ida;
  double relative_tolerance = 1e-8;
  double absolute_tolerance = 1e-10;
  double redwood_alpha = 2.0;
  // Level 2 hinge hardening length: α t at every node, or fitted so that one polygon ring
  // follows Redwood's curve for α (hinge/redwood_hinge_length.hpp).
  enum class HardeningLength { AlphaT, RedwoodFit } hardening_length = HardeningLength::AlphaT;
  int nodes_per_ring = 48;
  // Level 2 stiff terms (compare/hinge_run_2d.hpp Level2Settings): the membrane bars' EA and
  // the contact and tie penalties × these, in (0, 1]; 1 is the model as it was. Softer terms
  // let the central difference take longer steps (README "Level 2: softer stiff terms").
  // Unset: the integrator's default (level2_settings: 1/4 for the central difference, 1 else).
  std::optional<double> level2_membrane_stiffness_scale;
  std::optional<double> level2_penalty_stiffness_scale;
  // The central difference's membrane bars implicit (hinge/polygon_central_difference.hpp,
  // CentralDifferenceOptions::implicit_membrane): they leave the step bound. Unset: on for the
  // central difference (compare/hinge_run_2d.hpp kImplicitMembranePenaltyScale). IDA and Odeint
  // ignore it.
  std::optional<bool> level2_implicit_membrane;
  // Level 2 Kelvin–Voigt damping ratios ζ, ≥ 0 (hinge/polygon_chain.hpp PolygonChainInput: the
  // membrane bars and the hinge rotations, each a fraction of its element's critical damping).
  // A numerical device: the FE dissipates ≤ 0.16 % of the impact energy outside plasticity, and
  // what the dampers take the FE puts into plastic work (README "FE against the hinge model",
  // sessions 14, 16 and 18). Unset: Level2Settings' defaults (ζ_m 1, ζ_b 0.15).
  std::optional<double> membrane_damping_ratio;
  std::optional<double> hinge_damping_ratio;
  // Level 2 hinge damper on the total rotation rate, c_θ θ̇ ("total", the default), or on its
  // elastic part, c_θ (θ̇ − θ̇p) ("elastic": no work on a steady plastic flow;
  // hinge/polygon_chain.hpp PolygonChainInput::hinge_damper_on_elastic_rate).
  enum class Level2HingeDamper { Total, Elastic } level2_hinge_damper = Level2HingeDamper::Total;
  // Level 2 hinge flow law λ̇ = (2 l_h/t) D ⟨|M|/M_y − 1⟩^q (compare/hinge_run_2d.hpp
  // Level2Settings flow_d_per_s, flow_q): D (1/s, > 0) and q (≥ 1). Unset: the Perzyna
  // regularisation of the rate-independent hinge (1e4, 1); mild-steel Cowper–Symonds is 40.4, 5.
  // A larger D is a stiffer regularisation, nearer the FE's rate-independent material.
  std::optional<double> level2_flow_rate_per_s;
  std::optional<double> level2_flow_exponent;
  // Level 3 hinge F of the wrap (hinge/level3_mechanism.hpp): fixed where the wrap starts at
  // least load, or travelling by the shear-free condition; level3_theta_f_deg >= 0 fixes it.
  enum class Level3HingeF { LeastOnsetLoad, ShearFree } level3_hinge_f = Level3HingeF::LeastOnsetLoad;
  double level3_theta_f_deg = -1.0;
  // Level 3 hinge E of a ring under a wrap (hinge/level3_travelling_e.hpp): fixed at 45°, or
  // the least-load (shear-free) E beyond the held cap, re-found at every output state.
  enum class Level3HingeE { Fixed, ShearFree } level3_hinge_e = Level3HingeE::Fixed;
  // Level 3 ring under a wrap: the bottom mechanism only, or the least load of bottom and
  // E–C–B at every event (hinge/level3_ecb.hpp).
  enum class Level3RingUnder { Bottom, LeastLoad } level3_ring_under = Level3RingUnder::LeastLoad;
  // Level 3 ring inertia (hinge/level3_inertia.cpp): false, the massless chain (one force F).
  bool level3_inertia = false;
};

struct Outputs {
  bool history = true;
  bool fields = true;      // ParaView frames
  int frames = 20;         // number of field frames over the run
  bool plots = true;       // SVG
};

struct Scene {
  std::string name;         // file stem
  std::string title;
  std::filesystem::path source;
  std::string text;         // the TOML it was parsed from (cache keys, sweep cases)
  Rings rings;
  Joints joints;
  std::optional<Impactor> impactor;  // dynamic analyses
  FarEnd far_end = FarEnd::Fixed;
  Analysis analysis;
  FeSettings fe;
  HingeSettings hinge;
  Outputs outputs;
};

Scene load_scene(const std::filesystem::path& file);
// Parses TOML text; `file` is used in messages only.
Scene parse_scene(const std::string& text, const std::string& file);

std::string to_string(JointType);
std::string to_string(AnalysisType);

}  // namespace ringcrush::compare
