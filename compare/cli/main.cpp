// ringcrush — ring chains crushed by an impact: FE, hinge models and their comparison.
//
//   ringcrush formula data/scenes/thesis_static.toml -o results/formula
//   ringcrush validate data/scenes/test30_welded.toml
//
// Exit status: 0 success, 1 a run failed (with a diagnosis), 2 bad input or usage,
// 3 `compare` ran both models and they disagree.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>

#include "compare/cli/commands.hpp"
#include "compare/scene.hpp"
#include "compare/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ringcrush: thin-walled ring chains under impact — FE, plastic-hinge models, "
               "and the thesis load formula (see README.md)"};
  app.set_version_flag("--version", std::string(ringcrush::compare::version()));
  app.require_subcommand(1);
  auto& commands = ringcrush::compare::cli::command_registry();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [order, add] : commands) add(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return ringcrush::compare::cli::exit_bad_input;
  } catch (const ringcrush::compare::SceneError& e) {
    std::cerr << "ringcrush: invalid scene: " << e.what() << '\n';
    return ringcrush::compare::cli::exit_bad_input;
  } catch (const std::invalid_argument& e) {
    std::cerr << "ringcrush: invalid input: " << e.what() << '\n';
    return ringcrush::compare::cli::exit_bad_input;
  } catch (const std::exception& e) {
    std::cerr << "ringcrush: failed: " << e.what() << '\n';
    return ringcrush::compare::cli::exit_failure;
  }
  return ringcrush::compare::cli::command_exit_status();
}

namespace ringcrush::compare::cli {
int& command_exit_status() {
  static int status = exit_ok;
  return status;
}

std::vector<std::pair<int, CommandFactory>>& command_registry() {
  static std::vector<std::pair<int, CommandFactory>> registry;
  return registry;
}
}  // namespace ringcrush::compare::cli
