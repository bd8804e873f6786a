// Agreement verdicts, RunResult JSON round trip and the HTML report, on synthetic runs
// (issue 8 verification a: measures on crafted results).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "compare/agreement.hpp"
#include "compare/explain.hpp"
#include "compare/measures.hpp"
#include "compare/report_html.hpp"
#include "compare/run_output.hpp"
#include "compare/run_result_io.hpp"
#include "compare/scene.hpp"

using namespace ringcrush::compare;

namespace {

// A dynamic run whose impactor decelerates uniformly from v0 under force F over `steps`.
RunResult synthetic(const std::vector<double>& crush, const std::vector<bool>& wrap, double force = 1000.0) {
  RunResult r;
  r.model = "fe";
  r.scene = "synthetic";
  r.analysis = AnalysisType::Dynamic;
  const double mass = 0.25, v0 = 30.0, a = force / mass, t_end = v0 / a;
  for (int k = 0; k <= 50; ++k) {
    const double t = t_end * k / 50.0;
    r.time_s.push_back(t);
    r.impactor_velocity_m_s.push_back(v0 - a * t);
    r.impactor_displacement_m.push_back(v0 * t - 0.5 * a * t * t);
    r.impactor_force_n.push_back(force);
    r.kinetic_j.push_back(0.5 * mass * std::pow(v0 - a * t, 2));
    r.plastic_j.push_back(0.5 * mass * v0 * v0 - r.kinetic_j.back());
  }
  r.crush_ratio = crush;
  r.wrap_around = wrap;
  r.ring_crush_m.assign(crush.size(), std::vector<double>(r.time_s.size(), 0.0));
  for (std::size_t i = 0; i < crush.size(); ++i) r.mode.push_back(wrap[i] ? "wrapped" : "flattened");
  r.ring_outline_m = {{{0.0, 0.0}, {0.01, 0.01}, {0.0, 0.02}}};
  r.outline_half = true;
  r.events.push_back({1e-3, "contact_closed", 1, "ring 2"});
  r.extra["note"] = "x";
  return r;
}

const std::vector<double> alternating{0.9, 0.3, 0.85, 0.35, 0.8, 0.4};
const std::vector<double> monotone{0.9, 0.8, 0.7, 0.6, 0.5, 0.4};
const std::vector<bool> wraps_135{true, false, true, false, true, false};

double verdict(const Agreement& a, const std::string& key, bool* pass = nullptr) {
  for (const auto& v : a.verdicts)
    if (v.key == key) {
      if (pass) *pass = v.pass;
      return v.value;
    }
  ADD_FAILURE() << "no verdict " << key;
  return NAN;
}

}  // namespace

TEST(Agreement, IdenticalRunsAgree) {
  const RunResult fe = synthetic(alternating, wraps_135), hinge = synthetic(alternating, wraps_135);
  const Agreement a = assess_agreement(fe, hinge);
  EXPECT_TRUE(a.agree);
  EXPECT_EQ(a.verdicts.size(), 6u);
  EXPECT_DOUBLE_EQ(verdict(a, "crush"), 0.0);
  EXPECT_DOUBLE_EQ(verdict(a, "mean_force"), 0.0);
  EXPECT_GT(a.fe_alternation_index, alternation_threshold);
}

TEST(Agreement, DifferentWrapRingsFail) {
  std::vector<bool> only1{true, false, false, false, false, false};
  bool pass = true;
  const Agreement a = assess_agreement(synthetic(alternating, wraps_135), synthetic(alternating, only1));
  EXPECT_DOUBLE_EQ(verdict(a, "wrap_rings", &pass), 2.0);
  EXPECT_FALSE(pass);
  EXPECT_FALSE(a.agree);
  EXPECT_EQ(wrapped_rings_text(only1), "1");
}

// Where the flags differ the detail gives both inverted arcs (what decided the flags), and only
// there; a run without per-ring arcs reads "n/a".
TEST(Agreement, WrapDetailGivesTheInvertedArcsOfTheRingsThatDiffer) {
  RunResult fe = synthetic(alternating, wraps_135);
  RunResult hinge = synthetic(alternating, {true, false, false, false, true, false});
  fe.inverted_arc_m = {0.042, 0.004, 0.0261, 0.0079, 0.0238, 0.004};
  hinge.inverted_arc_m = {0.0418, 0.0032, 0.0161, 0.0, 0.0257, 0.0};
  std::string detail;
  for (const auto& v : assess_agreement(fe, hinge).verdicts)
    if (v.key == "wrap_rings") detail = v.detail;
  EXPECT_EQ(detail, "FE wraps 1,3,5; hinge wraps 1,5; ring 3 inverted arc FE 26.1 mm, hinge 16.1 mm");
  hinge.inverted_arc_m.clear();
  for (const auto& v : assess_agreement(fe, hinge).verdicts)
    if (v.key == "wrap_rings") detail = v.detail;
  EXPECT_NE(detail.find("ring 3 inverted arc FE 26.1 mm, hinge n/a"), std::string::npos) << detail;
}

TEST(Agreement, AlternatingAgainstMonotoneFails) {
  bool pass = true;
  const Agreement a = assess_agreement(synthetic(alternating, wraps_135), synthetic(monotone, wraps_135));
  verdict(a, "alternation", &pass);
  EXPECT_FALSE(pass);
  EXPECT_NEAR(a.hinge_alternation_index, 0.0, 1e-12);
}

// Both alternate, out of phase (the even rings crushed in one, the odd in the other): the
// step signs decide, and every one differs.
TEST(Agreement, AlternationOutOfPhaseFails) {
  const std::vector<double> shifted{0.3, 0.9, 0.35, 0.85, 0.4, 0.8};
  bool pass = true;
  const Agreement a = assess_agreement(synthetic(alternating, wraps_135), synthetic(shifted, wraps_135));
  EXPECT_DOUBLE_EQ(verdict(a, "alternation", &pass), 0.0);
  EXPECT_FALSE(pass);
  EXPECT_GT(a.hinge_alternation_index, alternation_threshold);
}

// Neither alternates (the plated Test 30 chain, session 16: FE steps 0-000, hinge 0-0++): the
// flat profile's steps sit at the 0.05 level cut, so their signs are shown and do not decide;
// the crush verdict holds the profile. The same steps between two alternating chains fail.
TEST(Agreement, StepSignsDoNotDecideWhenNeitherAlternates) {
  const std::vector<double> fe_flat{0.72, 0.72, 0.66, 0.66, 0.70, 0.71};
  const std::vector<double> hinge_flat{0.67, 0.68, 0.62, 0.63, 0.68, 0.74};
  const std::vector<bool> none(6, false);
  bool pass = false;
  const Agreement a = assess_agreement(synthetic(fe_flat, none), synthetic(hinge_flat, none));
  EXPECT_LT(a.fe_alternation_index, alternation_threshold);
  EXPECT_LT(a.hinge_alternation_index, alternation_threshold);
  EXPECT_LT(verdict(a, "alternation", &pass), 0.75);  // the signs differ on 2 of 5 steps
  EXPECT_TRUE(pass);
  for (const auto& v : a.verdicts) {
    if (v.key == "alternation") {
      EXPECT_NE(v.detail.find("neither alternates"), std::string::npos) << v.detail;
    }
  }
}

TEST(Agreement, CrushErrorAgainstThreshold) {
  auto shifted = alternating;
  shifted[3] += 0.14;  // below the 0.15 default
  bool pass = false;
  Agreement a = assess_agreement(synthetic(alternating, wraps_135), synthetic(shifted, wraps_135));
  EXPECT_NEAR(verdict(a, "crush", &pass), 0.14, 1e-12);
  EXPECT_TRUE(pass);
  shifted[3] += 0.02;
  a = assess_agreement(synthetic(alternating, wraps_135), synthetic(shifted, wraps_135));
  EXPECT_NEAR(verdict(a, "crush", &pass), 0.16, 1e-12);
  EXPECT_FALSE(pass);
}

TEST(Agreement, ForceAndEnergyErrorsAreRelativeToTheFe) {
  // Same impulse-free synthetic motion, hinge force 40 % higher: mean force error 0.4.
  bool pass = true;
  const Agreement a = assess_agreement(synthetic(alternating, wraps_135, 1000.0), synthetic(alternating, wraps_135, 1400.0));
  EXPECT_NEAR(verdict(a, "peak_force", &pass), 0.4, 1e-9);
  EXPECT_TRUE(pass);  // 0.5 threshold
  EXPECT_NEAR(verdict(a, "mean_force", &pass), 0.4, 1e-6);
  EXPECT_FALSE(pass);
  // Both absorb all of KE0 at arrest: energy agrees.
  EXPECT_NEAR(verdict(a, "absorbed_energy", &pass), 0.0, 1e-9);
}

TEST(Agreement, IncomparableRunsAreRefused) {
  EXPECT_THROW(assess_agreement(synthetic(alternating, wraps_135), synthetic({0.5, 0.5}, {false, false})),
               std::invalid_argument);
  RunResult s = synthetic(alternating, wraps_135);
  s.analysis = AnalysisType::Static;
  EXPECT_THROW(assess_agreement(s, synthetic(alternating, wraps_135)), std::invalid_argument);
}

TEST(RunResultJson, RoundTripKeepsEveryField) {
  const RunResult r = synthetic(alternating, wraps_135);
  const RunResult back = run_result_from_json(nlohmann::json::parse(run_result_to_json(r).dump()));
  EXPECT_EQ(back.model, r.model);
  EXPECT_EQ(back.time_s, r.time_s);
  EXPECT_EQ(back.impactor_force_n, r.impactor_force_n);
  EXPECT_EQ(back.plastic_j, r.plastic_j);
  EXPECT_EQ(back.crush_ratio, r.crush_ratio);
  EXPECT_EQ(back.wrap_around, r.wrap_around);
  EXPECT_EQ(back.ring_crush_m, r.ring_crush_m);
  EXPECT_EQ(back.mode, r.mode);
  EXPECT_EQ(back.ring_outline_m, r.ring_outline_m);
  EXPECT_EQ(back.outline_half, r.outline_half);
  ASSERT_EQ(back.events.size(), 1u);
  EXPECT_EQ(back.events[0].kind, "contact_closed");
  EXPECT_EQ(back.extra, r.extra);
}

TEST(RunResultJson, NonFiniteAndMissingFieldsAreErrors) {
  RunResult r = synthetic(alternating, wraps_135);
  r.kinetic_j[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(run_result_to_json(r), std::runtime_error);
  auto j = run_result_to_json(synthetic(alternating, wraps_135));
  j.erase("crush_ratio");
  try {
    run_result_from_json(j);
    FAIL() << "missing field accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("crush_ratio"), std::string::npos);
  }
}

TEST(ReportHtml, SelfContainedPageWithVerdictsAndCharts) {
  const Scene scene = load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/test30_welded.toml");
  const RunResult fe = synthetic(alternating, wraps_135), hinge = synthetic(monotone, wraps_135);
  const Agreement a = assess_agreement(fe, hinge);
  ReportInput in;
  in.scene = &scene;
  in.fe = &fe;
  in.hinge = &hinge;
  in.agreement = &a;
  const std::string html = render_report_html(in);
  EXPECT_NE(html.find("the models disagree"), std::string::npos);
  EXPECT_NE(html.find("same alternation pattern"), std::string::npos);
  std::size_t svgs = 0;
  for (std::size_t p = html.find("<svg"); p != std::string::npos; p = html.find("<svg", p + 1)) ++svgs;
  EXPECT_EQ(svgs, 5u);  // bars, velocity, force, energies, shapes
  EXPECT_EQ(html.find("nan"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("http://") , html.find("http://www.w3.org/2000/svg"));  // no external resources
}

TEST(Metrics, PeakMeanForceIgnoresAShortSpike) {
  RunResult r = synthetic(alternating, wraps_135, 1000.0);  // constant 1 kN over ~7.5 ms
  r.impactor_force_n[1] = 20000.0;                          // one-sample spike (~0.15 ms)
  EXPECT_DOUBLE_EQ(peak_force(r), 20000.0);
  const double dt = r.time_s[1] - r.time_s[0];
  // A window of 10 samples sees the spike's triangle (area 19 kN × dt) spread over 10 dt.
  EXPECT_NEAR(peak_mean_force(r, 10 * dt), 1000.0 + 19000.0 / 10.0, 1e-6);
  EXPECT_NEAR(peak_mean_force(r, 40 * dt), 1000.0 + 19000.0 / 40.0, 1e-6);
}

TEST(Explain, SaysWhatIsComputedAndWhy) {
  const std::string dir = std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/";
  auto joined = [](const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
  };
  const std::string st = joined(explain_fe(load_scene(dir + "thesis_static.toml")));
  EXPECT_NE(st.find("no mass matrix"), std::string::npos);
  EXPECT_NE(st.find("half-ring"), std::string::npos);
  Scene dyn = load_scene(dir + "test30_plates.toml");
  std::string d = joined(explain_fe(dyn));
  EXPECT_NE(d.find("explicit central difference"), std::string::npos);
  EXPECT_NE(d.find("5 rigid plates"), std::string::npos);
  EXPECT_NE(d.find("hinge model is not built"), std::string::npos);
  dyn.outputs.fields = false;
  d = joined(explain_fe(dyn));
  EXPECT_NE(d.find("no field frames"), std::string::npos);
  EXPECT_NE(joined(explain_hinge(dyn)).find("FE model is not built"), std::string::npos);
}
