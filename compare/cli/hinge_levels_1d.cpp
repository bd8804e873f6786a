// Registers the one-dimensional hinge levels (THEORY §4.2) with `ringcrush hinge`.
#include "compare/hinge_run_1d.hpp"

namespace ringcrush::compare {
namespace {
const HingeLevelRegistration level0{"0", run_hinge_level0};
const HingeLevelRegistration level1{"1", run_hinge_level1};
const HingeLevelRegistration shock{"shock", run_hinge_shock};
}  // namespace
}  // namespace ringcrush::compare
