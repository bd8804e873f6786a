// The run loop shared by the 1-D chain levels: integrate a hybrid chain model, record its
// history (all steps, or only the first and last for sweeps and benchmarks) and its final
// crush. Internal to hinge/chain_level*.cpp.
#pragma once

#include <vector>

#include "chain_1d.hpp"

namespace ringcrush::hinge {

template <typename Model>
ChainResult run_chain(Model& model, const ChainInput& input, const HybridOptions& options,
                      bool record_history, std::vector<double>& y) {
  ChainResult result;
  auto& h = result.history;
  h.ring_crush_m.assign(input.rings, {});
  h.ring_plastic_j.assign(input.rings, {});
  y = model.initial_state();
  result.initial_kinetic_energy_j =
      0.5 * input.impactor_mass_kg * input.impactor_velocity_m_s * input.impactor_velocity_m_s;
  std::vector<double> last;
  double t_last = 0.0;
  bool first = true;
  result.outcome = run_hybrid(model, 0.0, y, options, [&](double t, const std::vector<double>& s) {
    if (record_history || first) {
      model.record(t, s, h);
      first = false;
    } else {
      last = s;
      t_last = t;
    }
  });
  if (!record_history && !last.empty()) model.record(t_last, last, h);
  result.events = std::move(model.events);
  result.arrest_time_s = model.arrest_time();
  for (int i = 0; i < input.rings; ++i) result.final_crush_m.push_back(h.ring_crush_m[i].back());
  return result;
}

}  // namespace ringcrush::hinge
