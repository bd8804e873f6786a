#include "compare/agreement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "compare/measures.hpp"
#include "compare/run_output.hpp"

namespace ringcrush::compare {
namespace {

int sign_of_step(double a, double b, double level) {
  const double d = b - a;
  return std::abs(d) < level ? 0 : (d > 0 ? 1 : -1);
}

// Relative error against the FE value; a zero FE value with a zero hinge value is agreement.
double relative_error(double fe, double hinge) {
  if (fe == 0.0) return hinge == 0.0 ? 0.0 : 1.0;
  return std::abs(hinge - fe) / std::abs(fe);
}

Verdict relative_verdict(std::string key, std::string what, double fe, double hinge, double threshold,
                         const char* unit, double scale) {
  Verdict v;
  v.key = std::move(key);
  v.description = std::move(what);
  v.value = relative_error(fe, hinge);
  v.threshold = threshold;
  v.pass = v.value <= threshold;
  v.detail = fmt::format("FE {:.4g} {}, hinge {:.4g} {}", fe * scale, unit, hinge * scale, unit);
  return v;
}

}  // namespace

std::string wrapped_rings_text(const std::vector<bool>& wrap) {
  std::string s;
  for (std::size_t i = 0; i < wrap.size(); ++i)
    if (wrap[i]) {
      if (!s.empty()) s += ',';
      s += std::to_string(i + 1);
    }
  return s.empty() ? "none" : s;
}

Agreement assess_agreement(const RunResult& fe, const RunResult& hinge, const AgreementThresholds& t) {
  if (fe.analysis != AnalysisType::Dynamic || hinge.analysis != AnalysisType::Dynamic)
    throw std::invalid_argument("compare: both runs must be dynamic impacts");
  const std::size_t n = fe.crush_ratio.size();
  if (n == 0) throw std::invalid_argument("compare: the FE run has no final crush per ring");
  if (hinge.crush_ratio.size() != n)
    throw std::invalid_argument(fmt::format("compare: the FE run has {} rings, the hinge run {}", n,
                                            hinge.crush_ratio.size()));
  auto wraps = [n](const RunResult& r) {
    std::vector<bool> w(n, false);
    for (std::size_t i = 0; i < std::min(n, r.wrap_around.size()); ++i) w[i] = r.wrap_around[i];
    return w;
  };
  const std::vector<bool> wf = wraps(fe), wh = wraps(hinge);

  Agreement a;
  for (std::size_t i = 0; i < n; ++i) {
    RingComparison c;
    c.ring = static_cast<int>(i) + 1;
    c.fe_crush_ratio = fe.crush_ratio[i];
    c.hinge_crush_ratio = hinge.crush_ratio[i];
    c.difference = c.hinge_crush_ratio - c.fe_crush_ratio;
    c.fe_wrap = wf[i];
    c.hinge_wrap = wh[i];
    c.fe_mode = i < fe.mode.size() ? fe.mode[i] : "";
    c.hinge_mode = i < hinge.mode.size() ? hinge.mode[i] : "";
    a.rings.push_back(c);
  }

  {
    Verdict v;
    v.key = "wrap_rings";
    v.description = "same rings wrap around their neighbour";
    int mismatches = 0;
    for (std::size_t i = 0; i < n; ++i) mismatches += wf[i] != wh[i] ? 1 : 0;
    v.value = mismatches;
    v.threshold = 0;
    v.pass = mismatches == 0;
    v.detail = fmt::format("FE wraps {}; hinge wraps {}", wrapped_rings_text(wf), wrapped_rings_text(wh));
    // Where the flags differ, the inverted arcs that decided them (the flag is S > 0.25 πR,
    // compare/measures.hpp): how far each model is from the threshold is what a reader weighs.
    auto arc_mm = [](const RunResult& r, std::size_t i) {
      return i < r.inverted_arc_m.size() ? fmt::format("{:.1f} mm", r.inverted_arc_m[i] * 1e3) : std::string("n/a");
    };
    for (std::size_t i = 0; i < n; ++i)
      if (wf[i] != wh[i]) v.detail += fmt::format("; ring {} inverted arc FE {}, hinge {}", i + 1, arc_mm(fe, i), arc_mm(hinge, i));
    a.verdicts.push_back(v);
  }
  {
    const Alternation af = alternation(fe.crush_ratio), ah = alternation(hinge.crush_ratio);
    a.fe_alternation_index = af.index;
    a.hinge_alternation_index = ah.index;
    const bool alt_f = af.index > alternation_threshold, alt_h = ah.index > alternation_threshold;
    int same = 0, pairs = 0;
    std::string pf, ph;
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const int sf = sign_of_step(fe.crush_ratio[i], fe.crush_ratio[i + 1], t.level_tolerance);
      const int sh = sign_of_step(hinge.crush_ratio[i], hinge.crush_ratio[i + 1], t.level_tolerance);
      same += sf == sh ? 1 : 0;
      ++pairs;
      pf += sf > 0 ? '+' : sf < 0 ? '-' : '0';
      ph += sh > 0 ? '+' : sh < 0 ? '-' : '0';
    }
    Verdict v;
    v.key = "alternation";
    v.description = "same alternation pattern (index vs threshold, signs of crush steps)";
    v.value = pairs > 0 ? static_cast<double>(same) / pairs : 1.0;
    v.threshold = t.pattern_fraction;
    // The step signs decide only when both chains alternate: they say whether the two alternate
    // in phase (the same rings crushed). When neither does, the crush profile is flat and its
    // steps sit at the level cut (THEORY §4.7: an index on a flat distribution means little);
    // the profile is then held by the crush verdict, and the signs are shown without deciding.
    const bool signs_decide = alt_f && alt_h;
    v.pass = alt_f == alt_h && (!signs_decide || v.value >= t.pattern_fraction);
    v.detail = fmt::format("index FE {:.2f} ({}), hinge {:.2f} ({}), threshold {:.2f}; steps FE {} hinge {}{}",
                           af.index, alt_f ? "alternates" : "does not", ah.index, alt_h ? "alternates" : "does not",
                           alternation_threshold, pf, ph, signs_decide || alt_f != alt_h ? "" : " (neither alternates: the steps do not decide)");
    a.verdicts.push_back(v);
  }
  {
    Verdict v;
    v.key = "crush";
    v.description = "largest crush-ratio difference over the rings";
    std::size_t worst = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (std::abs(a.rings[i].difference) > std::abs(a.rings[worst].difference)) worst = i;
    v.value = std::abs(a.rings[worst].difference);
    v.threshold = t.crush_ratio;
    v.pass = v.value <= t.crush_ratio;
    v.detail = fmt::format("ring {}: FE {:.3f}, hinge {:.3f}", worst + 1, a.rings[worst].fe_crush_ratio,
                           a.rings[worst].hinge_crush_ratio);
    a.verdicts.push_back(v);
  }
  a.verdicts.push_back(relative_verdict("peak_force",
                                        fmt::format("peak impactor force ({:g} ms mean), relative error",
                                                    1e3 * t.peak_force_window_s),
                                        peak_mean_force(fe, t.peak_force_window_s),
                                        peak_mean_force(hinge, t.peak_force_window_s), t.peak_force, "kN", 1e-3));
  a.verdicts.push_back(relative_verdict("mean_force", "mean crushing force, relative error", mean_force(fe),
                                        mean_force(hinge), t.mean_force, "kN", 1e-3));
  a.verdicts.push_back(relative_verdict("absorbed_energy", "energy absorbed (plastic), relative error",
                                        absorbed_energy(fe), absorbed_energy(hinge), t.absorbed_energy, "J", 1.0));
  a.fe_arrest_time_s = arrest_time(fe);
  a.hinge_arrest_time_s = arrest_time(hinge);
  a.agree = std::all_of(a.verdicts.begin(), a.verdicts.end(), [](const Verdict& v) { return v.pass; });
  return a;
}

nlohmann::json to_json(const Agreement& a, const AgreementThresholds& t) {
  nlohmann::json j;
  j["agree"] = a.agree;
  for (const auto& v : a.verdicts)
    j["verdicts"][v.key] = {{"pass", v.pass},
                            {"value", v.value},
                            {"threshold", v.threshold},
                            {"description", v.description},
                            {"detail", v.detail}};
  nlohmann::json rings = nlohmann::json::array();
  for (const auto& r : a.rings)
    rings.push_back({{"ring", r.ring},
                     {"fe_crush_ratio", r.fe_crush_ratio},
                     {"hinge_crush_ratio", r.hinge_crush_ratio},
                     {"difference", r.difference},
                     {"fe_wrap_around", r.fe_wrap},
                     {"hinge_wrap_around", r.hinge_wrap},
                     {"fe_mode", r.fe_mode},
                     {"hinge_mode", r.hinge_mode}});
  j["rings"] = std::move(rings);
  j["alternation_index"] = {{"fe", a.fe_alternation_index}, {"hinge", a.hinge_alternation_index}};
  auto time_or_null = [](double s) { return s >= 0 ? nlohmann::json(s) : nlohmann::json(); };
  j["arrest_time_s"] = {{"fe", time_or_null(a.fe_arrest_time_s)}, {"hinge", time_or_null(a.hinge_arrest_time_s)}};
  j["thresholds"] = {{"crush_ratio", t.crush_ratio},     {"pattern_fraction", t.pattern_fraction},
                     {"level_tolerance", t.level_tolerance}, {"peak_force", t.peak_force},
                     {"peak_force_window_s", t.peak_force_window_s},
                     {"mean_force", t.mean_force},       {"absorbed_energy", t.absorbed_energy},
                     {"alternation_index", alternation_threshold}};
  return j;
}

}  // namespace ringcrush::compare
