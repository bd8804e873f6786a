// ringcrush export-calculix SCENE -o DIR — the scene as a CalculiX deck (issue 5 item 3;
// compare/calculix_export.hpp), for a cross-check of ringcrush's FE with another code:
//
//   ringcrush export-calculix data/scenes/thesis_static.toml -o results/ccx_static
//   cd results/ccx_static && ccx -i thesis_static
//
// Writes DIR/<scene>.inp and DIR/README.txt (what is mapped, what is approximated) into a
// results directory that appears complete or not at all. A correct run prints the deck's
// node and element counts and the directory; a dynamic scene (ring chain) is written as a
// *DYNAMIC deck of 20-node bricks and the run says what it holds (rigid bodies, mass,
// velocity, contact gaps). A scene the deck cannot carry (a static chain, plane strain,
// friction) exits 2 naming the feature.
#include <fmt/format.h>

#include <fstream>

#include "compare/calculix_export.hpp"
#include "compare/cli/commands.hpp"
#include "compare/results_dir.hpp"

namespace ringcrush::compare::cli {
namespace {

struct ExportOptions {
  std::string scene;
  std::string output;
  bool full_width = false;
  bool rigid_plates = false;
};

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
  if (!f) throw std::runtime_error("export-calculix: cannot write " + p.string());
}

void run_export(const ExportOptions& o) {
  const Scene s = load_scene(o.scene);
  const CalculixDeck deck =
      calculix_deck(s, o.full_width ? CalculixSection::FullWidth : CalculixSection::PlaneStressSlab,
                    o.rigid_plates ? CalculixPlates::RigidBodies : CalculixPlates::Strips);
  ResultsDir out(o.output);
  write_text(out.file(s.name + ".inp"), deck.deck);
  write_text(out.file("README.txt"), deck.readme);
  out.commit();
  if (deck.dynamic) {
    fmt::print("export-calculix {}: *DYNAMIC deck, {} nodes, {} elements ({} ring {}); impactor *RIGID BODY, "
               "reference node {}, {:g} kg in the deck at {:g} m/s; forces and masses of the chain = {:g} x the "
               "deck's\n",
               s.name, deck.nodes, deck.elements, deck.ring_elements, deck.ring_element_type,
               deck.driven_reference_node, deck.impactor_mass_kg, deck.impactor_velocity_m_s, deck.load_factor);
    fmt::print("  contact: {} GAPUNI elements ({} ring to ring, {} inner wall, the rest rigid faces)\n",
               deck.gap_elements, deck.ring_ring_gaps, deck.inner_wall_gaps);
  } else {
    fmt::print("export-calculix {}: {} nodes, {} elements ({} ring); driven plate reference node {}; ring load = {:g} "
               "x the plate's reaction\n",
               s.name, deck.nodes, deck.elements, deck.ring_elements, deck.driven_reference_node, deck.load_factor);
  }
  for (const auto& a : deck.approximations) fmt::print("  approximation: {}\n", a);
  fmt::print("wrote {}/{}.inp\n", out.target().string(), s.name);
}

void add_export_command(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  auto* cmd = app.add_subcommand("export-calculix",
                                 "Write a scene (static ring or dynamic chain) as a CalculiX (ccx) deck on ringcrush's own mesh");
  cmd->add_option("scene", o->scene, "Scene file (.toml)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Output directory (written completely or not at all)")->required();
  cmd->add_flag("--full-width", o->full_width,
                "Section thickness = ring width (ccx's 3-D slab, near plane strain) instead of the plane-stress thin "
                "slab");
  cmd->add_flag("--rigid-plates", o->rigid_plates,
                "Static scenes: plates as *RIGID BODY strips, the deck in 20-node bricks (load at the driven "
                "reference node)");
  cmd->callback([o] { run_export(*o); });
}

const CommandRegistration registration{25, add_export_command};
}  // namespace

}  // namespace ringcrush::compare::cli
