// One Level 2 polygon ring crushed quasi-statically between plates (issue 7 verification a),
// shared by the DeRuntz–Hodge and Redwood checks: driven top plate at 1 m/s (ramped over
// 1 mm) with light mass-proportional damping (200 s⁻¹: ≈ 0.6 % of P0 as drag), hinges in the
// rate-independent limit of the flow law (Perzyna q = 1, D = 1e5 s⁻¹: overstress ≈ 1e-4), to
// δ = 0.52 d. The load saw-tooths (−5 %…+11 %) as a travelling hinge passes a node, so the
// checks average it over a band of δ/d.
#pragma once

#include <algorithm>
#include <functional>

#include "hinge/polygon_simulation.hpp"
#include "hinge/ring_laws.hpp"

namespace ringcrush::hinge::plates_crush {

inline const RingSection test30_section{0.0508, 0.0016, 0.0125};

inline PolygonRunOutput crush_between_plates(PolygonChainInput in, double rtol) {
  in.rings = 1;
  in.driven_impactor = true;
  in.drive_speed_m_s = 1.0;
  in.drive_ramp_s = 1e-3;
  in.mass_damping_per_s = 200.0;
  in.cowper_symonds_d_per_s = 1e5;
  in.cowper_symonds_q = 1.0;
  in.membrane_damping_ratio = 1.0;
  in.hinge_damping_ratio = 1.0;
  PolygonRunOptions o;
  o.end_time_s = in.drive_ramp_s + 0.52 * test30_section.mean_diameter() / in.drive_speed_m_s;
  o.stop_at_arrest = false;
  o.output_interval_s = o.end_time_s / 500;
  o.relative_tolerance = rtol;
  o.absolute_scale = rtol;
  return run_polygon_chain(in, o);
}

// P / P_reference(δ) over δ/d ∈ [0.2, 0.5] of a crush_between_plates run: mean, extremes
// and the number of samples.
struct LoadBand {
  double mean = 0, low = 1e300, high = 0;
  int samples = 0;
};

inline LoadBand load_band(const PolygonRunOutput& out, const std::function<double(double)>& reference) {
  const double d = test30_section.mean_diameter();
  LoadBand b;
  const auto& h = out.history;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    const double delta = h.impactor_displacement_m[i];
    if (delta < 0.2 * d || delta > 0.5 * d) continue;
    const double r = h.impactor_force_n[i] / reference(delta);
    b.mean += r;
    b.low = std::min(b.low, r);
    b.high = std::max(b.high, r);
    ++b.samples;
  }
  if (b.samples > 0) b.mean /= b.samples;
  return b;
}

}  // namespace ringcrush::hinge::plates_crush
