// ringcrush validate SCENE… — parse and check scene files; writes nothing.
#include <fmt/format.h>

#include "compare/cli/commands.hpp"
#include "compare/scene.hpp"

namespace ringcrush::compare::cli {

namespace {
void add_validate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("validate", "Check scene files (TOML) and report the first error in each");
  auto files = std::make_shared<std::vector<std::string>>();
  cmd->add_option("scenes", *files, "Scene files")->required()->check(CLI::ExistingFile);
  cmd->callback([files] {
    for (const auto& f : *files) {
      const Scene s = load_scene(f);
      fmt::print("{}: ok — {} ring(s), {} joints, {} analysis\n", f, s.rings.count,
                 to_string(s.joints.type), to_string(s.analysis.type));
    }
  });
}

const CommandRegistration registration{90, add_validate_command};
}  // namespace

}  // namespace ringcrush::compare::cli
