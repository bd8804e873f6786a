// Shape outputs of the models that have ring shapes (issue 7 item 4; hinge Levels 2 and 3):
// the mean lines over time as ParaView polylines (frames/shape_NNNN.vtp + shapes.pvd, one
// closed polyline per ring with the plastic rotation, when the model has one, and the turning
// angle of the polyline as point data, body faces as lines) and an SVG of the final shapes
// over the first ones (shapes_final.svg). Both read RunResult::shape_frames only.
#pragma once

#include <cstddef>
#include <vector>

#include "compare/results_dir.hpp"
#include "compare/run_result.hpp"
#include "compare/scene.hpp"

namespace ringcrush::compare {

// Indices of `frames` evenly spaced samples out of `samples` (first and last included,
// no repeats); empty when frames ≤ 0 or there are no samples.
std::vector<std::size_t> frame_samples(std::size_t samples, int frames);

// Nothing is written when r.shape_frames is empty.
void write_shape_frames(const RunResult& r, ResultsDir& out);
void write_final_shapes_svg(const RunResult& r, const Scene& scene, ResultsDir& out);

}  // namespace ringcrush::compare
