#include "compare/hinge_levels.hpp"

namespace ringcrush::compare {

std::map<std::string, HingeLevelRunner>& hinge_level_registry() {
  static std::map<std::string, HingeLevelRunner> registry;
  return registry;
}

}  // namespace ringcrush::compare
