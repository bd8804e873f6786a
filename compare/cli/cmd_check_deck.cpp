// ringcrush check-deck DECK.inp… — read an ABAQUS 4.8 deck (the thesis's Anexo I keywords),
// generate its mesh and print what it defines and the ringcrush parameters it amounts to;
// writes nothing. A deck error prints "DECK:LINE: reason" and exits with 2.
//   ringcrush check-deck data/thesis/thesis_dynamic.inp
//   ringcrush check-deck --scene data/thesis/thesis_static.inp   # the equivalent scene TOML
#include <fmt/format.h>

#include "compare/cli/commands.hpp"
#include "compare/deck_scene.hpp"
#include "fe/deck/deck_reader.hpp"
#include "fe/deck/deck_summary.hpp"

namespace ringcrush::compare::cli {

namespace {
namespace fd = ringcrush::fe::deck;

void add_check_deck_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("check-deck", "Read ABAQUS 4.8 decks, build the mesh and print a summary");
  auto files = std::make_shared<std::vector<std::string>>();
  auto scene = std::make_shared<bool>(false);
  cmd->add_option("decks", *files, "ABAQUS input decks (.inp)")->required()->check(CLI::ExistingFile);
  cmd->add_flag("--scene", *scene, "Print the equivalent scene TOML instead of the summary");
  cmd->callback([files, scene] {
    int rejected = 0;
    for (const auto& f : *files) {
      try {
        const fd::DeckModel model = fd::load_deck(f);
        const fd::DeckParameters params = fd::deck_parameters(model);
        if (*scene) {
          const std::string toml = scene_toml_from_deck(params, f);
          (void)parse_scene(toml, f);  // the scene must be valid before it is printed
          fmt::print("{}", toml);
          continue;
        }
        fmt::print("{}: ok\n{}{}", f, fd::describe(model), fd::describe(params));
      } catch (const fd::DeckError& e) {
        fmt::print(stderr, "{}:{}: {}\n", f, e.line(), e.reason());
        ++rejected;
      } catch (const std::exception& e) {
        fmt::print(stderr, "{}: {}\n", f, e.what());
        ++rejected;
      }
    }
    // main() turns this into exit status 2 (exit_bad_input).
    if (rejected > 0) throw std::invalid_argument(fmt::format("{} deck(s) rejected", rejected));
  });
}

const CommandRegistration registration{92, add_check_deck_command};
}  // namespace

}  // namespace ringcrush::compare::cli
