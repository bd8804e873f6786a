// One Level 2 polygon ring crushed quasi-statically between plates (issue 7 verification a),
// shared by the DeRuntz–Hodge and Redwood checks: driven top plate at 1 m/s (ramped over
// 1 mm) with light mass-proportional damping (200 s⁻¹: ≈ 0.6 % of P0 as drag), hinges in the
// rate-independent limit of the flow law (Perzyna q = 1, D = 1e5 s⁻¹: overstress ≈ 1e-4), to
// δ = 0.52 d. The load saw-tooths (−5 %…+11 %) as a travelling hinge passes a node, so the
// checks average it over a band of δ/d.
#pragma once

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

}  // namespace ringcrush::hinge::plates_crush
