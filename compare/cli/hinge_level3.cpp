// Registers hinge Level 3 (THEORY §4.5, compare/hinge_run_level3.hpp) with `ringcrush hinge`.
#include "compare/hinge_run_level3.hpp"

namespace ringcrush::compare {
namespace {
const HingeLevelRegistration level3{"3", [](const Scene& s, const HingeRunOptions& o) {
                                      return run_hinge_level3(s, o);
                                    }};
}  // namespace
}  // namespace ringcrush::compare
