#include "compare/deck_scene.hpp"

#include <fmt/format.h>

#include "fe/deck/deck_reader.hpp"

namespace ringcrush::compare {

namespace fd = ringcrush::fe::deck;

namespace {
// Lengths and ratios measured off the generated nodes carry rounding noise from the
// generation (0.05079999999999999 for 50.8 mm): 12 significant digits, far below any mesh
// or material tolerance, print them as the deck wrote them.
std::string measured(double v) { return fmt::format("{:.12g}", v); }
}  // namespace

std::string scene_toml_from_deck(const fd::DeckParameters& d, const std::string& source) {
  // {} prints the shortest text that reads back to the same double: values the deck gives
  // (E, yield stresses, times, tolerances) go through exactly.
  std::string t;
  auto line = [&t](const std::string& s) { t += s + "\n"; };
  line(fmt::format("# Generated from the ABAQUS deck {} by ringcrush check-deck --scene.", source));
  line(fmt::format("title = \"{} (deck {})\"", d.rings.size() == 1 ? "Single ring" : "Ring chain", source));
  line("\n[rings]");
  line(fmt::format("count = {}", d.rings.size()));
  line(fmt::format("outer_diameter_m = {}", measured(2.0 * d.outer_radius_m)));
  line(fmt::format("wall_thickness_m = {}", measured(d.outer_radius_m - d.inner_radius_m)));
  line(fmt::format("width_m = {}", d.width_m));
  line(fmt::format("pitch_m = {}", measured(d.pitch_m)));
  line("section = \"plane_stress\"   # CPS8");
  line("\n[rings.material]");
  line(fmt::format("youngs_modulus_Pa = {}", d.youngs_modulus_pa));
  line(fmt::format("poisson_ratio = {}", d.poisson_ratio));
  if (d.density_kg_m3) {
    line(fmt::format("density_kg_m3 = {}", *d.density_kg_m3));
  } else {
    if (d.dynamic) throw std::invalid_argument("deck " + source + ": a dynamic deck needs *DENSITY");
    // The static deck has no *DENSITY; a static run never uses it, the scene format needs one.
    line("density_kg_m3 = 7850.0   # not in the deck (no *DENSITY); unused by a static run");
  }
  if (d.hardening.empty()) throw std::invalid_argument("deck " + source + ": the ring material has no *PLASTIC");
  std::string table;
  for (const auto& p : d.hardening)
    table += fmt::format("{}[{}, {}]", table.empty() ? "" : ", ", p.yield_stress, p.plastic_strain);
  line("hardening = [" + table + "]");
  if (d.rings.size() > 1) {
    line("\n[joints]");
    line(fmt::format("type = \"{}\"", d.welded ? "welded" : "free"));
  }
  if (d.dynamic) {
    line("\n[impactor]");
    line(fmt::format("mass_kg = {}", *d.impactor_mass_kg));
    line(fmt::format("velocity_m_s = {}", *d.impactor_velocity_m_s));
  }
  line("\n[far_end]");
  line(fmt::format("type = \"{}\"", d.fixed_target ? "fixed" : "free"));
  line("\n[analysis]");
  line(fmt::format("type = \"{}\"", d.dynamic ? "dynamic" : "static"));
  if (d.dynamic)
    line(fmt::format("end_time_s = {}", d.period));
  else
    line(fmt::format("crush_m = {}", d.crush_m));
  line(fmt::format("symmetry = \"{}\"", d.half_model ? "half" : "full"));
  line("\n[fe]");
  line(fmt::format("solver = \"{}\"", d.dynamic ? "hht" : "static"));
  line(fmt::format("elements_around = {}", d.elements_around));
  line(fmt::format("elements_through = {}", d.elements_through));
  line(fmt::format("grading = {}", measured(d.grading)));
  line("integration = \"selective\"   # thesis §3.6.1.4");
  if (d.ptol_n) line(fmt::format("ptol_N = {}", *d.ptol_n));
  if (d.dynamic) {
    if (d.hht_alpha) line(fmt::format("hht_alpha = {}", *d.hht_alpha));
    line(fmt::format("initial_step_s = {}", d.initial_increment));
    if (d.haftol_n) line(fmt::format("haftol_N = {}", *d.haftol_n));
  } else {
    line(fmt::format("initial_increment = {}", d.initial_increment));
    if (d.min_increment) line(fmt::format("min_increment = {}", *d.min_increment));
    if (d.max_increment) line(fmt::format("max_increment = {}", *d.max_increment));
    if (d.max_iterations) line(fmt::format("max_iterations = {}", *d.max_iterations));
  }
  if (d.contact_smoothing) line(fmt::format("contact_smoothing = {}", *d.contact_smoothing));
  line(fmt::format("friction_coefficient = {}", d.friction_coefficient));
  return t;
}

Scene scene_from_deck(const std::filesystem::path& deck_file) {
  const fd::DeckParameters params = fd::deck_parameters(fd::load_deck(deck_file));
  Scene s = parse_scene(scene_toml_from_deck(params, deck_file.string()), deck_file.string());
  return s;
}

}  // namespace ringcrush::compare
