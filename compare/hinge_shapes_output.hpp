// Level 2 shape outputs (issue 7 item 4): the polygon rings' mean lines over time as
// ParaView polylines (frames/shape_NNNN.vtp + shapes.pvd, one closed polyline per ring with
// the accumulated plastic rotation ā and the turning angle as point data, plates as lines)
// and an SVG of the final shapes over the undeformed ones (shapes_final.svg).
#pragma once

#include "compare/hinge_run_2d.hpp"
#include "compare/results_dir.hpp"
#include "compare/scene.hpp"

namespace ringcrush::compare {

// Writes `frames` evenly spaced samples (first and last included) of run.raw.history.
void write_level2_shape_frames(const Level2Run& run, const Scene& scene, ResultsDir& out, int frames);
void write_level2_final_svg(const Level2Run& run, const Scene& scene, ResultsDir& out);

}  // namespace ringcrush::compare
