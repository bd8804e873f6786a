#pragma once
#include <string_view>

namespace ringcrush::compare {
// Project version and git revision of the build (enters summaries and result caches).
std::string_view version();
}  // namespace ringcrush::compare
