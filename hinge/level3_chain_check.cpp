// Level 3 chain: the statics check and the travelling E evaluated on the output states.
//
// The massless chain (hinge/level3_mechanism.hpp): every ring carries the impactor force F;
// with ring inertia (hinge/level3_inertia.cpp) each ring its own top and bottom forces and
// its d'Alembert load (Level3RingLoads). At each output state each ring's shape is checked
// for |M| ≤ M_p under them
// (level3_statics_check; M_p the hinge moment of the ring's mechanism, M0 with k = 0), and every ring under a wrap gets its held cap (from the wrapping
// ring's shape stacked on it), its E (fixed or shear-free) and the E–C–B load, held against
// the load of the bottom mechanism it flows in (THEORY §4.5: mode selection by the
// dissipation rate of the competing mechanisms).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "level3_statics.hpp"
#include "level3_travelling_e.hpp"

namespace ringcrush::hinge {

namespace {

double bottom_load(const Level3Ring& r, double psi) {
  return r.collapse_load() * (1.0 + r.hardening_k * psi) / std::cos(psi);
}

}  // namespace

void level3_check_states(const Level3Input& in, const WrapMechanism& w, const std::vector<Level3RingResult>& states,
                         double force_n, double time_s, std::vector<Level3RingResult>& rings,
                         const std::vector<Level3RingLoads>& loads) {
  const double M0 = in.ring.plastic_moment_nm, t = in.ring.wall_thickness_m;
  std::vector<Level3Shape> shapes;
  double top = 0.0;
  for (const auto& s : states) {  // stacked: each top a wall thickness below the ring above
    shapes.push_back(level3_ring_shape(in.ring, w, s, top, 48));  // 48 points a quadrant: ratio to ~1e-4
    top = shapes.back().bottom_y - t;
  }
  const double load = std::max(force_n, 0.0);
  const double lock = in.ring.mean_diameter() - t;  // inner walls touch (ring_laws, THEORY §1.3)
  for (std::size_t i = 0; i < states.size() && i < rings.size(); ++i) {
    auto& rr = rings[i];
    // A locked ring carries the load through its touching inner walls, a contact the two-point
    // statics leaves out: it is not checked (nor is its E, which could not turn).
    if (states[i].crush_m >= lock * (1.0 - 1e-9)) continue;
    // The hinge moment of the ring's flowing mechanism: Redwood's hardening raises it to
    // M0 (1 + kφ) (uniform) or M0 (1 + kψ) (bottom, and E–C–B: its C and B′ carry the bottom
    // mechanism's 1 + kψ_s and more, its new E less — the bottom value is kept); the wrap has
    // none (level3_mechanism.hpp).
    const auto& si = states[i];
    const double hard = si.mode == Level3Mode::Wrap ? 1.0
                        : si.reinforced             ? 1.0 + in.ring.hardening_k * si.bottom_angle
                                                    : 1.0 + in.ring.hardening_k * si.uniform_angle;
    // With inertia each ring under its own contact forces and d'Alembert loads (the same
    // meaning: the largest |M|/M_p of the best field outside the hinges).
    const auto st = loads.empty() ? level3_statics_check(shapes[i], load, M0 * hard)
                                  : level3_statics_check(shapes[i], loads[i], M0 * hard);
    if (st.peak_ratio > rr.peak_moment_ratio) {
      rr.peak_moment_ratio = st.peak_ratio;
      rr.peak_moment_angle_deg = st.angle_deg;
      rr.peak_moment_time_s = time_s;
      rr.peak_moment_angles_deg = st.peak_angles_deg;
    }
    // E–C–B against the bottom mechanism while the ring flows in the bottom mode (once E has
    // turned the chain has made that choice itself: level3_mechanism.cpp).
    if (!states[i].reinforced || i == 0 || states[i].ecb_started) continue;
    rr.held_cap = level3_held_cap(shapes[i - 1], shapes[i], 1.1 * t);
    // C and B of the E–C–B are the bottom mechanism's hinges, hardened to 1 + kψ; E is new.
    const auto e = in.hinge_e == Level3HingeE::ShearFree ? level3_shear_free_e(shapes[i], M0, rr.held_cap, hard)
                                                          : level3_e_rate(shapes[i], M0, in.theta_e, hard);
    rr.theta_e = e.theta_e;
    rr.e_mechanism_load_n = e.load;
    rr.bottom_load_n = bottom_load(in.ring, states[i].bottom_angle);
    if (rr.e_onset_load_n <= 0.0) {  // the first state under the wrap: the competing loads
      rr.e_onset_load_n = e.load;
      rr.bottom_onset_load_n = rr.bottom_load_n;
      rr.theta_e_onset = e.theta_e;
      rr.held_cap_onset = rr.held_cap;
    }
    if (e.load < rr.bottom_load_n) {
      if (rr.e_cheaper_states == 0) rr.e_cheaper_time_s = time_s;
      ++rr.e_cheaper_states;
    }
  }
}

void level3_check_history(const Level3Input& in, Level3Result& res) {
  // Statics check and E on the output states (first and last only without a history): at
  // most ~200 evenly spread, plus every state where a ring changes mechanism (the events,
  // where the loads jump), plus the last — a check costs ≈ 0.2 ms, the runs keep thousands.
  const auto& h = res.history;
  const bool own = !h.ring_loads.empty();  // with inertia: each ring's own loads
  const std::size_t ns = h.time_s.size(), stride = std::max<std::size_t>(1, ns / 200);
  auto changed = [&](std::size_t k) {
    if (k == 0) return true;
    for (std::size_t i = 0; i < h.ring_state[k].size(); ++i) {
      const auto &a = h.ring_state[k][i], &b = h.ring_state[k - 1][i];
      if (a.wrap_started != b.wrap_started || a.reinforced != b.reinforced || a.ecb_started != b.ecb_started) return true;
    }
    return false;
  };
  for (std::size_t k = 0; k < ns; ++k)
    if (k % stride == 0 || k + 1 == ns || changed(k))
      level3_check_states(in, res.wrap, h.ring_state[k], h.force_n[k], h.time_s[k], res.rings,
                          own ? h.ring_loads[k] : std::vector<Level3RingLoads>{});
  for (auto& rr : res.rings)
    for (auto& hg : rr.hinges)
      if (hg.name == "E" && !rr.ecb_started) hg.angle_deg = rr.theta_e * 180.0 / std::numbers::pi;
}

}  // namespace ringcrush::hinge
