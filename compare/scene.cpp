// Scene parsing and validation. The reader below consumes keys as it reads them, so that
// whatever is left over in a table is an unknown key and an error (a typo must never be
// silently ignored in an engineering input).
#include "scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>
#include <toml++/toml.h>

#include "compare/through_wall_section.hpp"

namespace ringcrush::compare {

SceneError::SceneError(std::string file, std::string key, std::string reason)
    : std::runtime_error(fmt::format("{}: {}: {}", file, key.empty() ? "(file)" : key, reason)),
      file_(std::move(file)), key_(std::move(key)), reason_(std::move(reason)) {}

double Material::hardening_modulus() const {
  if (hardening.size() < 2) return 0.0;
  const auto& a = hardening[0];
  const auto& b = hardening[1];
  return (b.yield_stress_pa - a.yield_stress_pa) / (b.plastic_strain - a.plastic_strain);
}

std::string to_string(JointType t) {
  switch (t) {
    case JointType::Welded: return "welded";
    case JointType::Free: return "free";
    case JointType::Plates: return "plates";
  }
  return "?";
}

std::string to_string(AnalysisType t) { return t == AnalysisType::Static ? "static" : "dynamic"; }

namespace {

const char* type_name(toml::node_type t) {
  switch (t) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date or time";
  }
}

// Reads one TOML table, remembering which keys were used.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string prefix, const std::string& file)
      : table_(table), prefix_(std::move(prefix)), file_(file) {}

  std::string path(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
  }
  [[noreturn]] void fail(std::string_view key, const std::string& reason) const {
    throw SceneError(file_, path(key), reason);
  }
  bool has(std::string_view key) const { return table_.contains(key); }

  const toml::node* find(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  double number(std::string_view key) {
    const toml::node* n = find(key);
    if (!n) fail(key, "missing required value");
    return as_number(*n, key);
  }
  double number(std::string_view key, double fallback) {
    return has(key) ? number(key) : (find(key), fallback);
  }
  double as_number(const toml::node& n, std::string_view key) const {
    double v;
    if (auto f = n.as_floating_point()) v = f->get();
    else if (auto i = n.as_integer()) v = static_cast<double>(i->get());
    else fail(key, fmt::format("expected a number, got {}", type_name(n.type())));
    if (!std::isfinite(v)) fail(key, "must be finite (NaN or infinity given)");
    return v;
  }

  long integer(std::string_view key, std::optional<long> fallback = std::nullopt) {
    const toml::node* n = find(key);
    if (!n) {
      if (fallback) return *fallback;
      fail(key, "missing required value");
    }
    auto i = n->as_integer();
    if (!i) fail(key, fmt::format("expected an integer, got {}", type_name(n->type())));
    return static_cast<long>(i->get());
  }

  bool boolean(std::string_view key, bool fallback) {
    const toml::node* n = find(key);
    if (!n) return fallback;
    auto b = n->as_boolean();
    if (!b) fail(key, fmt::format("expected true or false, got {}", type_name(n->type())));
    return b->get();
  }

  std::string string(std::string_view key, std::optional<std::string> fallback = std::nullopt) {
    const toml::node* n = find(key);
    if (!n) {
      if (fallback) return *fallback;
      fail(key, "missing required value");
    }
    auto s = n->as_string();
    if (!s) fail(key, fmt::format("expected a string, got {}", type_name(n->type())));
    return s->get();
  }

  template <typename Enum>
  Enum choice(std::string_view key, std::initializer_list<std::pair<const char*, Enum>> options,
              std::optional<Enum> fallback = std::nullopt) {
    std::optional<std::string> fallback_text;
    if (fallback)
      for (auto& [name, value] : options)
        if (value == *fallback) fallback_text = name;
    const std::string s = string(key, fallback_text);
    std::string allowed;
    for (auto& [name, value] : options) {
      if (s == name) return value;
      allowed += (allowed.empty() ? "" : ", ") + fmt::format("\"{}\"", name);
    }
    fail(key, fmt::format("\"{}\" is not one of {}", s, allowed));
  }

  TableReader sub(std::string_view key, bool required) {
    const toml::node* n = find(key);
    if (!n) {
      if (required) fail(key, "missing required table");
      return TableReader(empty_table(), path(key), file_);
    }
    auto t = n->as_table();
    if (!t) fail(key, fmt::format("expected a table, got {}", type_name(n->type())));
    return TableReader(*t, path(key), file_);
  }

  const toml::array& array(std::string_view key) {
    const toml::node* n = find(key);
    if (!n) fail(key, "missing required value");
    auto a = n->as_array();
    if (!a) fail(key, fmt::format("expected an array, got {}", type_name(n->type())));
    return *a;
  }

  // Every key not read is unknown.
  void finish() const {
    for (auto&& [k, v] : table_) {
      if (!used_.count(std::string(k.str())))
        fail(k.str(), "unknown key (check the spelling against data/scenes/README.md)");
    }
  }

 private:
  static const toml::table& empty_table() {
    static const toml::table empty;
    return empty;
  }
  const toml::table& table_;
  std::string prefix_;
  const std::string& file_;
  std::set<std::string> used_;
};

void require(bool ok, const TableReader& r, std::string_view key, const std::string& reason) {
  if (!ok) r.fail(key, reason);
}

Material read_material(TableReader r) {
  Material m;
  m.youngs_modulus_pa = r.number("youngs_modulus_Pa");
  require(m.youngs_modulus_pa > 0, r, "youngs_modulus_Pa", "must be positive");
  m.poisson_ratio = r.number("poisson_ratio");
  require(m.poisson_ratio >= 0 && m.poisson_ratio < 0.5, r, "poisson_ratio", "must lie in [0, 0.5)");
  m.density_kg_m3 = r.number("density_kg_m3");
  require(m.density_kg_m3 > 0, r, "density_kg_m3", "must be positive");

  const auto& table = r.array("hardening");
  const std::string key = "hardening";
  if (table.empty()) r.fail(key, "needs at least one [yield_stress_Pa, plastic_strain] pair");
  if (table.size() > 10000) r.fail(key, "more than 10000 points");
  for (std::size_t i = 0; i < table.size(); ++i) {
    const std::string item = fmt::format("hardening[{}]", i);
    auto pair = table[i].as_array();
    if (!pair || pair->size() != 2)
      r.fail(item, "expected a pair [yield_stress_Pa, plastic_strain]");
    HardeningPoint p{r.as_number(*pair->get(0), item), r.as_number(*pair->get(1), item)};
    if (!(p.yield_stress_pa > 0)) r.fail(item, "yield stress must be positive");
    if (i == 0 && p.plastic_strain != 0.0) r.fail(item, "the first point must be at plastic strain 0");
    if (i > 0) {
      const auto& prev = m.hardening.back();
      if (!(p.plastic_strain > prev.plastic_strain))
        r.fail(item, "plastic strains must increase strictly");
      if (p.yield_stress_pa < prev.yield_stress_pa)
        r.fail(item, "the hardening table decreases (softening is not supported)");
    }
    m.hardening.push_back(p);
  }
  r.finish();
  return m;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& file) {
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw SceneError(file, fmt::format("line {}, column {}", where.line, where.column),
                     fmt::format("not valid TOML: {}", e.description()));
  }
  Scene s;
  s.source = file;
  s.text = text;
  s.name = std::filesystem::path(file).stem().string();
  TableReader top(root, "", file);
  s.title = top.string("title", s.name);

  {
    auto r = top.sub("rings", true);
    const long count = r.integer("count");
    require(count >= 1 && count <= 1000, r, "count", "must be between 1 and 1000");
    s.rings.count = static_cast<int>(count);
    s.rings.outer_diameter_m = r.number("outer_diameter_m");
    require(s.rings.outer_diameter_m > 0, r, "outer_diameter_m", "must be positive");
    s.rings.wall_thickness_m = r.number("wall_thickness_m");
    require(s.rings.wall_thickness_m > 0, r, "wall_thickness_m", "must be positive");
    require(s.rings.wall_thickness_m < 0.5 * s.rings.outer_diameter_m, r, "wall_thickness_m",
            "must be less than half the outer diameter (t < D/2)");
    s.rings.width_m = r.number("width_m");
    require(s.rings.width_m > 0, r, "width_m", "must be positive");
    s.rings.section = r.choice<SectionState>(
        "section", {{"plane_stress", SectionState::PlaneStress}, {"plane_strain", SectionState::PlaneStrain}},
        SectionState::PlaneStress);
    s.rings.pitch_m = r.number("pitch_m", s.rings.outer_diameter_m);
    s.rings.material = read_material(r.sub("material", true));
    r.finish();
  }
  {
    auto r = top.sub("joints", s.rings.count > 1);
    s.joints.type = r.choice<JointType>(
        "type", {{"welded", JointType::Welded}, {"free", JointType::Free}, {"plates", JointType::Plates}},
        JointType::Free);
    if (s.joints.type == JointType::Plates) {
      s.joints.plate_mass_kg = r.number("plate_mass_kg");
      require(s.joints.plate_mass_kg > 0, r, "plate_mass_kg", "must be positive");
      s.joints.plate_thickness_m = r.number("plate_thickness_m");
      require(s.joints.plate_thickness_m > 0, r, "plate_thickness_m", "must be positive");
    } else {
      for (const char* k : {"plate_mass_kg", "plate_thickness_m"})
        if (r.has(k)) r.fail(k, "only meaningful with type = \"plates\"");
    }
    r.finish();
  }
  const double min_pitch = s.rings.outer_diameter_m + s.joints.plate_thickness_m;
  if (s.rings.pitch_m < min_pitch * (1 - 1e-12))
    throw SceneError(file, "rings.pitch_m",
                     fmt::format("{} m makes neighbouring rings overlap (at least {} m)",
                                 s.rings.pitch_m, min_pitch));
  {
    auto r = top.sub("analysis", true);
    s.analysis.type = r.choice<AnalysisType>(
        "type", {{"static", AnalysisType::Static}, {"dynamic", AnalysisType::Dynamic}});
    s.analysis.symmetry = r.choice<Symmetry>(
        "symmetry", {{"half", Symmetry::Half}, {"full", Symmetry::Full}}, Symmetry::Half);
    if (s.analysis.type == AnalysisType::Static) {
      s.analysis.crush_m = r.number("crush_m");
      require(s.analysis.crush_m > 0, r, "crush_m", "must be positive");
      const double room = s.rings.count * s.rings.outer_diameter_m;
      require(s.analysis.crush_m < room, r, "crush_m",
              fmt::format("must be less than the chain height {} m", room));
    } else {
      s.analysis.end_time_s = r.number("end_time_s");
      require(s.analysis.end_time_s > 0, r, "end_time_s", "must be positive");
      s.analysis.stop_at_rest = r.boolean("stop_at_rest", true);
    }
    r.finish();
  }
  if (top.has("impactor") || s.analysis.type == AnalysisType::Dynamic) {
    auto r = top.sub("impactor", true);
    Impactor imp;
    imp.mass_kg = r.number("mass_kg");
    require(imp.mass_kg > 0, r, "mass_kg", "must be positive");
    imp.velocity_m_s = r.number("velocity_m_s", 0.0);
    if (s.analysis.type == AnalysisType::Dynamic)
      require(imp.velocity_m_s > 0, r, "velocity_m_s",
              "an impact needs a positive speed toward the chain");
    else
      require(imp.velocity_m_s >= 0, r, "velocity_m_s", "must not be negative");
    s.impactor = imp;
    r.finish();
  }
  {
    auto r = top.sub("far_end", false);
    s.far_end = r.choice<FarEnd>("type", {{"fixed", FarEnd::Fixed}, {"free", FarEnd::Free}},
                                 FarEnd::Fixed);
    if (s.far_end == FarEnd::Free && s.analysis.type == AnalysisType::Static)
      r.fail("type", "a static crush needs a fixed far end");
    r.finish();
  }
  {
    auto r = top.sub("fe", false);
    auto& f = s.fe;
    f.elements_around = static_cast<int>(r.integer("elements_around", f.elements_around));
    require(f.elements_around >= 8 && f.elements_around <= 4096 && f.elements_around % 2 == 0, r,
            "elements_around", "must be an even number between 8 and 4096");
    f.elements_through = static_cast<int>(r.integer("elements_through", f.elements_through));
    require(f.elements_through >= 1 && f.elements_through <= 16, r, "elements_through",
            "must be between 1 and 16");
    f.grading = r.number("grading", f.grading);
    require(f.grading >= 1.0 && f.grading <= 100.0, r, "grading", "must lie in [1, 100]");
    f.integration = r.choice<Integration>(
        "integration",
        {{"full", Integration::Full}, {"reduced", Integration::Reduced}, {"selective", Integration::Selective}},
        f.integration);
    f.solver = r.choice<FeSolver>(
        "solver", {{"static", FeSolver::Static}, {"hht", FeSolver::Hht}, {"explicit", FeSolver::Explicit}},
        s.analysis.type == AnalysisType::Static ? FeSolver::Static : FeSolver::Explicit);
    if ((f.solver == FeSolver::Static) != (s.analysis.type == AnalysisType::Static))
      r.fail("solver", "\"static\" is the solver for static analyses and only for them");
    f.hht_alpha = r.number("hht_alpha", f.hht_alpha);
    require(f.hht_alpha >= -1.0 / 3.0 && f.hht_alpha <= 0.0, r, "hht_alpha",
            "must lie in [-1/3, 0] (Hilber's convention)");
    f.initial_step_s = r.number("initial_step_s", f.initial_step_s);
    require(f.initial_step_s > 0, r, "initial_step_s", "must be positive");
    f.haftol_n = r.number("haftol_N", f.haftol_n);
    require(f.haftol_n > 0, r, "haftol_N", "must be positive");
    f.ptol_n = r.number("ptol_N", f.ptol_n);
    require(f.ptol_n > 0, r, "ptol_N", "must be positive");
    f.initial_increment = r.number("initial_increment", f.initial_increment);
    require(f.initial_increment > 0 && f.initial_increment <= 1, r, "initial_increment",
            "must lie in (0, 1]");
    f.min_increment = r.number("min_increment", std::min(f.min_increment, f.initial_increment));
    require(f.min_increment > 0 && f.min_increment <= f.initial_increment, r, "min_increment",
            "must lie in (0, initial_increment]");
    f.max_increment = r.number("max_increment", std::max(f.max_increment, f.initial_increment));
    require(f.max_increment >= f.initial_increment && f.max_increment <= 1, r, "max_increment",
            "must lie in [initial_increment, 1]");
    f.max_iterations = static_cast<int>(r.integer("max_iterations", f.max_iterations));
    require(f.max_iterations >= 2 && f.max_iterations <= 200, r, "max_iterations",
            "must lie in [2, 200]");
    f.contact_smoothing = r.number("contact_smoothing", f.contact_smoothing);
    require(f.contact_smoothing >= 0 && f.contact_smoothing < 0.5, r, "contact_smoothing",
            "must lie in [0, 0.5)");
    f.contact_penalty_scale = r.number("contact_penalty_scale", f.contact_penalty_scale);
    require(f.contact_penalty_scale > 0, r, "contact_penalty_scale", "must be positive");
    f.contact_penalty_step_fraction = r.number("contact_penalty_step_fraction", f.contact_penalty_step_fraction);
    require(f.contact_penalty_step_fraction == 0 ||
                (f.contact_penalty_step_fraction > 0 && f.contact_penalty_step_fraction <= 0.5),
            r, "contact_penalty_step_fraction", "must be 0 (off) or lie in (0, 0.5]");
    f.contact_arrival_depth = r.number("contact_arrival_depth", f.contact_arrival_depth);
    require(f.contact_arrival_depth > 0 && f.contact_arrival_depth <= 1, r, "contact_arrival_depth",
            "must lie in (0, 1] (a fraction of the through-wall element depth)");
    f.friction_coefficient = r.number("friction_coefficient", f.friction_coefficient);
    require(f.friction_coefficient >= 0 && f.friction_coefficient <= 2, r,
            "friction_coefficient", "must lie in [0, 2]");
    f.friction_penalty_scale = r.number("friction_penalty_scale", f.friction_penalty_scale);
    require(f.friction_penalty_scale > 0, r, "friction_penalty_scale", "must be positive");
    f.explicit_safety = r.number("explicit_safety", f.explicit_safety);
    require(f.explicit_safety > 0 && f.explicit_safety <= 1, r, "explicit_safety",
            "must lie in (0, 1]");
    f.step_bound = r.choice<ExplicitStepBound>(
        "step_bound", {{"element", ExplicitStepBound::Element}, {"assembled", ExplicitStepBound::Assembled}},
        f.step_bound);
    f.bulk_viscosity = r.number("bulk_viscosity", f.bulk_viscosity);
    require(f.bulk_viscosity >= 0 && f.bulk_viscosity < 1, r, "bulk_viscosity", "must lie in [0, 1)");
    f.mass_scaling_dt = r.number("mass_scaling_dt", f.mass_scaling_dt);
    require(std::isfinite(f.mass_scaling_dt) && f.mass_scaling_dt >= 0, r, "mass_scaling_dt",
            "must be >= 0 s (0: off)");
    f.mass_scaling_factor = r.number("mass_scaling_factor", f.mass_scaling_factor);
    require(std::isfinite(f.mass_scaling_factor) && f.mass_scaling_factor >= 1, r, "mass_scaling_factor",
            "must be >= 1 (1: off)");
    f.energy_error_limit = r.number("energy_error_limit", f.energy_error_limit);
    require(f.energy_error_limit > 0, r, "energy_error_limit", "must be positive");
    r.finish();
  }
  {
    auto r = top.sub("hinge", false);
    auto& h = s.hinge;
    // The level may be written as a number or as "shock".
    if (const toml::node* n = r.find("level")) {
      if (auto i = n->as_integer()) h.level = std::to_string(i->get());
      else if (auto str = n->as_string()) h.level = str->get();
      else r.fail("level", fmt::format("expected 0, 1, 2, 3 or \"shock\", got {}", type_name(n->type())));
      if (h.level != "0" && h.level != "1" && h.level != "2" && h.level != "3" && h.level != "shock")
        r.fail("level", fmt::format("\"{}\" is not one of 0, 1, 2, 3, \"shock\"", h.level));
    }
    h.integrator = r.choice<HingeIntegrator>(
        "integrator",
        {{"ida", HingeIntegrator::Ida},
         {"odeint", HingeIntegrator::Odeint},
         {"central_difference", HingeIntegrator::CentralDifference}},
        h.integrator);
    require(h.integrator != HingeIntegrator::CentralDifference || h.level == "2", r, "integrator",
            "\"central_difference\" is for level 2 only (the polygon rings); use \"ida\" or \"odeint\"");
    h.relative_tolerance = r.number("relative_tolerance", h.relative_tolerance);
    require(h.relative_tolerance > 0 && h.relative_tolerance < 1, r, "relative_tolerance",
            "must lie in (0, 1)");
    h.absolute_tolerance = r.number("absolute_tolerance", h.absolute_tolerance);
    require(h.absolute_tolerance > 0, r, "absolute_tolerance", "must be positive");
    h.redwood_alpha = r.number("redwood_alpha", h.redwood_alpha);
    require(h.redwood_alpha > 0, r, "redwood_alpha", "must be positive");
    h.hardening_length = r.choice<HingeSettings::HardeningLength>(
        "hardening_length",
        {{"alpha_t", HingeSettings::HardeningLength::AlphaT}, {"redwood_fit", HingeSettings::HardeningLength::RedwoodFit}},
        h.hardening_length);
    require(h.hardening_length != HingeSettings::HardeningLength::RedwoodFit ||
                (h.redwood_alpha >= 1 && h.redwood_alpha <= 4),
            r, "hardening_length", "\"redwood_fit\" is fitted for redwood_alpha in [1, 4]");
    h.nodes_per_ring = static_cast<int>(r.integer("nodes_per_ring", h.nodes_per_ring));
    for (auto [key, value] : {std::pair{"level2_membrane_stiffness_scale", &h.level2_membrane_stiffness_scale},
                              std::pair{"level2_penalty_stiffness_scale", &h.level2_penalty_stiffness_scale}}) {
      if (!r.has(key)) continue;
      *value = r.number(key, 1.0);
      require(**value > 0 && **value <= 1, r, key, fmt::format("{} must lie in (0, 1] (1: the unscaled model)", **value));
    }
    if (r.has("level2_implicit_membrane")) h.level2_implicit_membrane = r.boolean("level2_implicit_membrane", false);
    for (auto [key, value] : {std::pair{"membrane_damping_ratio", &h.membrane_damping_ratio},
                              std::pair{"hinge_damping_ratio", &h.hinge_damping_ratio}}) {
      if (!r.has(key)) continue;
      *value = r.number(key, 0.0);
      require(**value >= 0, r, key, fmt::format("{} must be >= 0 (a fraction of critical damping; 0: none)", **value));
    }
    h.level2_hinge_damper = r.choice<HingeSettings::Level2HingeDamper>(
        "level2_hinge_damper",
        {{"total", HingeSettings::Level2HingeDamper::Total}, {"elastic", HingeSettings::Level2HingeDamper::Elastic}},
        h.level2_hinge_damper);
    if (r.has("level2_flow_rate_per_s")) {
      h.level2_flow_rate_per_s = r.number("level2_flow_rate_per_s", 0.0);
      require(std::isfinite(*h.level2_flow_rate_per_s) && *h.level2_flow_rate_per_s > 0, r, "level2_flow_rate_per_s",
              fmt::format("{} must be positive and finite (1/s)", *h.level2_flow_rate_per_s));
    }
    if (r.has("level2_flow_exponent")) {
      h.level2_flow_exponent = r.number("level2_flow_exponent", 0.0);
      require(std::isfinite(*h.level2_flow_exponent) && *h.level2_flow_exponent >= 1, r, "level2_flow_exponent",
              fmt::format("{} must be finite and >= 1", *h.level2_flow_exponent));
    }
    h.level3_hinge_f = r.choice<HingeSettings::Level3HingeF>(
        "level3_hinge_f",
        {{"least_onset_load", HingeSettings::Level3HingeF::LeastOnsetLoad},
         {"shear_free", HingeSettings::Level3HingeF::ShearFree}},
        h.level3_hinge_f);
    h.level3_theta_f_deg = r.number("level3_theta_f_deg", h.level3_theta_f_deg);
    h.level3_hinge_e = r.choice<HingeSettings::Level3HingeE>(
        "level3_hinge_e",
        {{"fixed", HingeSettings::Level3HingeE::Fixed}, {"shear_free", HingeSettings::Level3HingeE::ShearFree}},
        h.level3_hinge_e);
    h.level3_ring_under = r.choice<HingeSettings::Level3RingUnder>(
        "level3_ring_under",
        {{"bottom", HingeSettings::Level3RingUnder::Bottom}, {"least_load", HingeSettings::Level3RingUnder::LeastLoad}},
        h.level3_ring_under);
    h.level3_inertia = r.boolean("level3_inertia", h.level3_inertia);
    require(h.level3_theta_f_deg < 0 || (h.level3_theta_f_deg > 90 && h.level3_theta_f_deg < 180), r,
            "level3_theta_f_deg",
            fmt::format("{} must lie in (90, 180) (or be negative: F placed by level3_hinge_f)", h.level3_theta_f_deg));
    require(h.level3_theta_f_deg < 0 || h.level3_hinge_f != HingeSettings::Level3HingeF::ShearFree, r,
            "level3_theta_f_deg",
            fmt::format("{} fixes F; it cannot be combined with level3_hinge_f = \"shear_free\"", h.level3_theta_f_deg));
    require(h.nodes_per_ring >= 8 && h.nodes_per_ring <= 4096 && h.nodes_per_ring % 4 == 0, r,
            "nodes_per_ring", "must be a multiple of 4 between 8 and 4096");
    r.finish();
  }
  {
    auto r = top.sub("outputs", false);
    s.outputs.history = r.boolean("history", s.outputs.history);
    s.outputs.fields = r.boolean("fields", s.outputs.fields);
    s.outputs.plots = r.boolean("plots", s.outputs.plots);
    s.outputs.frames = static_cast<int>(r.integer("frames", s.outputs.frames));
    require(s.outputs.frames >= 0 && s.outputs.frames <= 100000, r, "frames",
            "must lie between 0 and 100000");
    r.finish();
  }
  top.finish();
  return s;
}

Scene load_scene(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(file.string(), "", "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  Scene s = parse_scene(text.str(), file.string());
  warn_through_wall_once(s);  // a chain whose FE section misses M0 (through_wall_section.hpp)
  return s;
}

}  // namespace ringcrush::compare
