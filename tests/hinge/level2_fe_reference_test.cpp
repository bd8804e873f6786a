// Level 2 against the stored FE reference (data/reference/fe_explicit_velocity.csv: the explicit
// FE on the thesis scene at 15–50 m/s and on Test 30), issue 7 (d): with the calibrated
// Kelvin–Voigt ratios (Level2Settings, README "FE against the hinge model") the central
// difference agrees with the FE at 15 and 45 m/s on the wrap flags, the alternation pattern,
// the crush per ring and the absorbed (plastic) energy — the verdicts of compare/agreement at
// their default thresholds. With the former ζ_b = 1 the alternation fails at both speeds and
// the absorbed energy at 45 m/s (0.78 of the FE's).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "compare/agreement.hpp"
#include "compare/hinge_run_2d.hpp"
#include "compare/measures.hpp"
#include "compare/scene.hpp"

using namespace ringcrush::compare;

namespace {

const std::string source_dir = RINGCRUSH_SOURCE_DIR;

// One row of the reference as the FE RunResult the agreement reads: final crush per ring,
// wrap flags and the plastic work.
std::map<std::string, RunResult> load_reference() {
  std::ifstream in(source_dir + "/data/reference/fe_explicit_velocity.csv");
  if (!in) throw std::runtime_error("cannot open the FE reference");
  std::string line;
  std::vector<std::string> header;
  std::map<std::string, RunResult> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    RunResult fe;
    fe.model = "fe";
    fe.analysis = AnalysisType::Dynamic;
    for (int ring = 1; ring <= 6; ++ring) {
      fe.crush_ratio.push_back(std::stod(row.at("crush_" + std::to_string(ring))));
      fe.wrap_around.push_back(row.at("wrap_" + std::to_string(ring)) == "1");
    }
    fe.plastic_j = {std::stod(row.at("plastic_J"))};
    rows[row.at("case")] = fe;
  }
  return rows;
}

struct Level2Case {
  RunResult result;
  double energy_balance_error;
};

Level2Case run_thesis_scene(double velocity_m_s) {
  Scene scene = load_scene(source_dir + "/data/scenes/thesis_dynamic.toml");
  scene.impactor->velocity_m_s = velocity_m_s;
  scene.outputs.fields = false;
  HingeRunOptions o;
  o.level = "2";
  o.integrator = HingeIntegrator::CentralDifference;
  const Level2Run run = run_level2(scene, o, level2_settings(scene, o.integrator));
  return {run.result, run.raw.energy_balance_error};
}

const Verdict& verdict(const Agreement& a, const std::string& key) {
  for (const auto& v : a.verdicts)
    if (v.key == key) return v;
  throw std::logic_error("no verdict " + key);
}

void expect_agreement(const RunResult& fe, const Level2Case& hinge, double crush_tolerance) {
  const Agreement a = assess_agreement(fe, hinge.result);
  for (const char* key : {"wrap_rings", "alternation", "crush", "absorbed_energy"}) {
    const Verdict& v = verdict(a, key);
    EXPECT_TRUE(v.pass) << key << ": " << v.value << " against " << v.threshold << " (" << v.detail << ")";
  }
  EXPECT_LE(verdict(a, "crush").value, crush_tolerance) << verdict(a, "crush").detail;
  EXPECT_LT(hinge.energy_balance_error, 1e-3);
}

}  // namespace

TEST(Level2FeReference, ThesisSceneAt15MetresPerSecond) {
  const auto reference = load_reference();
  expect_agreement(reference.at("thesis_v15"), run_thesis_scene(15.0), 0.10);
}

TEST(Level2FeReference, ThesisSceneAt45MetresPerSecond) {
  const auto reference = load_reference();
  expect_agreement(reference.at("thesis_v45"), run_thesis_scene(45.0), 0.10);
}

// The reference itself: the FE's own verdict-level facts the calibration leans on (thesis
// §4.2): no wrap at 15 m/s, rings 1–5 wrapped from 35 m/s on, the alternation index above the
// threshold at 20–30 m/s and below it from 40 m/s.
TEST(Level2FeReference, ReferenceCarriesTheThesisVelocityTrend) {
  const auto reference = load_reference();
  ASSERT_EQ(reference.size(), 11u);
  for (bool w : reference.at("thesis_v15").wrap_around) EXPECT_FALSE(w);
  for (const char* c : {"thesis_v35", "thesis_v40", "thesis_v45", "thesis_v50"})
    for (int ring = 0; ring < 5; ++ring) EXPECT_TRUE(reference.at(c).wrap_around[ring]) << c << " ring " << ring + 1;
  for (const char* c : {"thesis_v20", "thesis_v25", "thesis_v30"})
    EXPECT_GT(alternation(reference.at(c).crush_ratio).index, alternation_threshold) << c;
  for (const char* c : {"thesis_v40", "thesis_v45", "thesis_v50"})
    EXPECT_LT(alternation(reference.at(c).crush_ratio).index, alternation_threshold) << c;
}
