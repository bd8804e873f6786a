// What a run of a scene will compute, and why (issue 8 item 7, `ringcrush fe SCENE --explain`,
// `ringcrush compare SCENE --explain`): the outputs a scene asks for decide what is built,
// and this says so before anything runs. Each line names one thing computed or skipped and
// the scene value that decides it. Pure: reads the Scene and the inputs built from it.
#pragma once

#include <string>
#include <vector>

#include "compare/scene.hpp"

namespace ringcrush::compare {

// Throws what fe_static_input / fe_chain_input throw for scenes the FE does not run.
std::vector<std::string> explain_fe(const Scene& scene);
std::vector<std::string> explain_hinge(const Scene& scene);

}  // namespace ringcrush::compare
