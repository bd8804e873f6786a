// The scene's FE section through the wall: the fully plastic moment its Gauss rule carries
// (fe/element/through_wall_plastic_moment.hpp), the line `--explain` prints about it, and the
// warning a chain scene gets when its FE misses M0.
//
// The FE and the hinge model meet on M0 (THEORY §1.2): a chain whose FE section carries
// 1.155 M0 (one element, reduced) or 0.861 M0 (one element, full or selective) yields across
// the wall at once, and its wrap and alternation verdicts compare the mesh, not the models
// (README "FE against the hinge model", session 15). The Table 2 chain scenes therefore carry
// two elements through the wall; the thesis scenes keep the thesis's one and are warned about.
#pragma once

#include <optional>
#include <string>

#include "compare/scene.hpp"

namespace ringcrush::compare {

// A chain scene warns when its FE plastic moment is off M0 by more than this fraction.
inline constexpr double through_wall_warning_tolerance = 0.05;

// M_p(FE) / M0 of the scene's mesh and integration rule.
double fe_plastic_moment_factor(const Scene& s);

// "through-wall section: plastic moment 1.000 M0 (2 Gauss points across each of 2 elements)".
std::string through_wall_section_line(const Scene& s);

// The warning for a chain (rings.count > 1) whose factor is off 1 by more than the tolerance;
// nothing otherwise.
std::optional<std::string> through_wall_warning(const Scene& s);

// Prints through_wall_warning(s) to stderr, once per scene file per process (scene loading
// calls it, so every subcommand that reads a scene warns, and a command that reads the same
// file again does not repeat it).
void warn_through_wall_once(const Scene& s);

}  // namespace ringcrush::compare
