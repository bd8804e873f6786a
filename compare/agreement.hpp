// Agreement of two models on one scene (issue 8 item 2): the FE (the verifier) against the
// hinge model, as verdicts with their numbers and thresholds. Every number comes from the
// measures and metrics of compare/ (measures.hpp, run_output.hpp) applied to both RunResults
// alike; nothing here looks inside a model.
//
// Verdicts (all must pass for "agree"):
//  - wrap_rings:   the same rings wrap around their neighbour (flags of rings 1..N−1);
//  - alternation:  both chains alternate or neither does (index vs alternation_threshold),
//                  and, when both alternate, the signs of the neighbour crush differences
//                  agree on at least `pattern_fraction` of the pairs (differences below
//                  `level_tolerance` in crush ratio count as level): the phase of the
//                  alternation. When neither alternates the signs are shown, not decisive;
//
//  - crush:        largest |c_FE − c_hinge| over the rings;
//  - peak_force (of the force averaged over a 0.2 ms window: run_output peak_mean_force),
//    mean_force, absorbed_energy: relative errors against the FE.
// The arrest time is reported beside them but decides nothing: the hinge model's rings have
// no elastic ringing, so "at rest" means different things in the two.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/run_result.hpp"

namespace ringcrush::compare {

// Default thresholds. Why these sizes: crush ratios of a Test 30 chain span 0…0.95 and the
// thesis's own FE/experiment difference is ~0.1 per ring (thesis §4.2.1); the FE impactor
// force rings at the elements' contact frequency, so its peak is only a coarse check.
struct AgreementThresholds {
  double crush_ratio = 0.15;        // absolute, per ring
  double pattern_fraction = 0.75;
  double level_tolerance = 0.05;
  double peak_force = 0.5;          // relative
  double peak_force_window_s = 2e-4;  // the peak is of the force averaged over this window
  double mean_force = 0.25;         // relative
  double absorbed_energy = 0.15;    // relative
};

struct Verdict {
  std::string key;          // "wrap_rings", "alternation", "crush", ...
  std::string description;  // one line for people
  double value = 0;         // the measured number (mismatches, error, ...)
  double threshold = 0;
  bool pass = false;
  std::string detail;       // e.g. "FE wraps 1,3; hinge wraps 1"
};

struct RingComparison {
  int ring = 0;  // 1-based
  double fe_crush_ratio = 0, hinge_crush_ratio = 0, difference = 0;
  bool fe_wrap = false, hinge_wrap = false;
  std::string fe_mode, hinge_mode;
};

struct Agreement {
  std::vector<Verdict> verdicts;
  std::vector<RingComparison> rings;
  double fe_alternation_index = 0, hinge_alternation_index = 0;
  double fe_arrest_time_s = -1, hinge_arrest_time_s = -1;
  bool agree = false;
};

// Throws std::invalid_argument when the runs cannot be compared (different ring counts,
// static runs, missing final state).
Agreement assess_agreement(const RunResult& fe, const RunResult& hinge, const AgreementThresholds& t = {});

nlohmann::json to_json(const Agreement& a, const AgreementThresholds& t);

// "1,3,5" (1-based) or "none".
std::string wrapped_rings_text(const std::vector<bool>& wrap);

}  // namespace ringcrush::compare
