// Level 2 against the stored FE reference with two elements through the wall
// (data/reference/fe_explicit_48x2.csv: the explicit FE, 48 × 2 CPS8 per half ring, on the
// thesis scene at 15–50 m/s and on Test 30), issue 7 (d). One CPS8 through the wall misses the
// plastic moment by its Gauss rule (1.155 or 0.861 M0, README "FE against the hinge model",
// session 15), so the 48 × 2 file is the reference Level 2 is held to. With its default
// Kelvin–Voigt ratios (Level2Settings) the central difference agrees with the FE at 15 and
// 45 m/s on the wrap flags, the alternation pattern, the crush per ring and the absorbed
// (plastic) energy — the verdicts of compare/agreement at their default thresholds. At the
// former ζ_b = 0.3 the 45 m/s case failed the crush (rings 3 and 5, 0.18) and, while the
// crush-step signs decided also for chains that do not alternate (before session 16), the
// alternation: the hinge dampers took 13 % of the
// kinetic energy there, the FE dissipates 0.1 % outside plasticity (session 16, h62).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "compare/agreement.hpp"
#include "compare/hinge_run_2d.hpp"
#include "compare/measures.hpp"
#include "compare/scene.hpp"

using namespace ringcrush::compare;

namespace {

const std::string source_dir = RINGCRUSH_SOURCE_DIR;

struct ReferenceRow {
  RunResult fe;      // final crush per ring, wrap flags and plastic work, as the agreement reads them
  double velocity_m_s = 0.0;
  bool thesis_scene = false;
};

std::map<std::string, ReferenceRow> load_reference(const std::string& file = "fe_explicit_48x2.csv") {
  std::ifstream in(source_dir + "/data/reference/" + file);
  if (!in) throw std::runtime_error("cannot open the FE reference");
  std::string line;
  std::vector<std::string> header;
  std::map<std::string, ReferenceRow> rows;
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
    ReferenceRow r;
    r.fe.model = "fe";
    r.fe.analysis = AnalysisType::Dynamic;
    for (int ring = 1; ring <= 6; ++ring) {
      r.fe.crush_ratio.push_back(std::stod(row.at("crush_" + std::to_string(ring))));
      r.fe.wrap_around.push_back(row.at("wrap_" + std::to_string(ring)) == "1");
    }
    r.fe.plastic_j = {std::stod(row.at("plastic_J"))};
    r.velocity_m_s = std::stod(row.at("velocity_m_s"));
    r.thesis_scene = row.at("base_scene") == "thesis_dynamic";
    rows[row.at("case")] = r;
  }
  return rows;
}

struct Level2Case {
  RunResult result;
  double energy_balance_error;
};

Level2Case run_scene(const std::string& name, std::optional<double> velocity_m_s = std::nullopt) {
  Scene scene = load_scene(source_dir + "/data/scenes/" + name + ".toml");
  if (velocity_m_s) scene.impactor->velocity_m_s = *velocity_m_s;
  scene.outputs.fields = false;
  HingeRunOptions o;
  o.level = "2";
  o.integrator = HingeIntegrator::CentralDifference;
  const Level2Run run = run_level2(scene, o, level2_settings(scene, o.integrator));
  return {run.result, run.raw.energy_balance_error};
}

Level2Case run_thesis_scene(double velocity_m_s) { return run_scene("thesis_dynamic", velocity_m_s); }

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

// The speed at which the alternation index first falls through the threshold going up in
// speed, by linear interpolation between neighbouring speeds (data/sweeps/level2_damping/
// transition.py); empty when it does not.
std::optional<double> transition_speed(const std::vector<std::pair<double, double>>& speed_index) {
  for (std::size_t i = 0; i + 1 < speed_index.size(); ++i) {
    const auto [v0, a0] = speed_index[i];
    const auto [v1, a1] = speed_index[i + 1];
    if (a0 > alternation_threshold && a1 <= alternation_threshold)
      return v0 + (v1 - v0) * (a0 - alternation_threshold) / (a0 - a1);
  }
  return std::nullopt;
}

// The FE's transition speed over the reference's thesis-scene speeds.
std::optional<double> fe_transition_speed(const std::map<std::string, ReferenceRow>& reference) {
  std::vector<std::pair<double, double>> speed_index;
  for (const auto& [name, row] : reference)
    if (row.thesis_scene) speed_index.emplace_back(row.velocity_m_s, alternation(row.fe.crush_ratio).index);
  std::sort(speed_index.begin(), speed_index.end());
  return transition_speed(speed_index);
}

}  // namespace

TEST(Level2FeReference, ThesisSceneAt15MetresPerSecond) {
  const auto reference = load_reference();
  expect_agreement(reference.at("thesis_v15").fe, run_thesis_scene(15.0), 0.10);
}

TEST(Level2FeReference, ThesisSceneAt45MetresPerSecond) {
  const auto reference = load_reference();
  expect_agreement(reference.at("thesis_v45").fe, run_thesis_scene(45.0), 0.10);
}

// Issue 7 (d) at the transition: the FE's chain stops alternating at 34.6 m/s (its index 0.54
// at 32.5, 0.26 at 35 m/s, interpolated), Level 2's at 35.6 m/s (0.51 at 34, 0.40 at 35, 0.25
// at 36 m/s): 1.0 m/s later, within the FE's 2.5 m/s sampling. At the former ζ_b = 0.3 it was
// 1.6 m/s later (36.3 m/s), and this test fails there. Level 2 is run from 34 m/s up until its
// index falls through the threshold (3 runs).
TEST(Level2FeReference, AlternationStopsWithinOneAndAHalfMetresPerSecondOfTheFe) {
  const auto fe_speed = fe_transition_speed(load_reference());
  ASSERT_TRUE(fe_speed.has_value());
  EXPECT_GT(*fe_speed, 30.0);
  EXPECT_LT(*fe_speed, 35.0);

  std::vector<std::pair<double, double>> level2;
  for (double v = 34.0; v <= 40.0; v += 1.0) {
    level2.emplace_back(v, alternation(run_thesis_scene(v).result.crush_ratio).index);
    if (level2.back().second <= alternation_threshold) break;
  }
  ASSERT_GT(level2.front().second, alternation_threshold) << "Level 2 no longer alternates at 34 m/s";
  const auto level2_speed = transition_speed(level2);
  ASSERT_TRUE(level2_speed.has_value()) << "Level 2 still alternates at 40 m/s";
  EXPECT_NEAR(*level2_speed, *fe_speed, 1.5) << "Level 2 " << *level2_speed << " m/s, FE " << *fe_speed << " m/s";
}

// The reference itself: the FE's own verdict-level facts the comparison leans on (thesis §4.2):
// no wrap at 15 m/s, rings 1–4 wrapped from 35 m/s on and ring 5 from 37.5 m/s on, the
// alternation index above the threshold at 20–32.5 m/s and below it from 35 m/s.
TEST(Level2FeReference, ReferenceCarriesTheThesisVelocityTrend) {
  const auto reference = load_reference();
  ASSERT_EQ(reference.size(), 13u);
  for (bool w : reference.at("thesis_v15").fe.wrap_around) EXPECT_FALSE(w);
  for (const char* c : {"thesis_v35", "thesis_v37.5", "thesis_v40", "thesis_v45", "thesis_v50"})
    for (int ring = 0; ring < 4; ++ring) EXPECT_TRUE(reference.at(c).fe.wrap_around[ring]) << c << " ring " << ring + 1;
  for (const char* c : {"thesis_v37.5", "thesis_v40", "thesis_v45", "thesis_v50"})
    EXPECT_TRUE(reference.at(c).fe.wrap_around[4]) << c << " ring 5";
  for (const char* c : {"thesis_v20", "thesis_v25", "thesis_v30", "thesis_v32.5"})
    EXPECT_GT(alternation(reference.at(c).fe.crush_ratio).index, alternation_threshold) << c;
  for (const char* c : {"thesis_v35", "thesis_v37.5", "thesis_v40", "thesis_v45", "thesis_v50"})
    EXPECT_LT(alternation(reference.at(c).fe.crush_ratio).index, alternation_threshold) << c;
}

// Issue 7 (d) over the whole welded velocity study (the thesis chain, 48 × 2 FE at 15–50 m/s, ten
// speeds). Away from the alternation transition every verdict the comparison reads passes:
// the wrap flags ring by ring, the alternation pattern, the crush per ring within 0.15 and the
// plastic work within 15 %. Through the transition Level 2 runs the FE's sequence of regimes
// 1–2.5 m/s late (session 18: the alternation stops at 35.6 against 34.6 m/s, ring 4 wraps from
// 36.5 against ≤ 35 m/s, ring 5's crush dips near 40 against 37.5 m/s; Level 2's dampers take
// 4–5 % of the impact energy there, which is ≈ 1 m/s of impact speed): at the FE's samples
// within 3.5 m/s of its transition speed (one 2.5 m/s sampling step beyond the 1 m/s offset:
// 32.5, 35, 37.5 m/s) the verdicts may fail, and the test holds the crush per ring within 0.3
// and the wrap flags to one ring. The transition speed itself is
// AlternationStopsWithinOneAndAHalfMetresPerSecondOfTheFe.
TEST(Level2FeReference, WeldedVelocityStudyAgreesAwayFromTheTransition) {
  const auto reference = load_reference();
  const auto fe_transition = fe_transition_speed(reference);
  ASSERT_TRUE(fe_transition.has_value());
  int away = 0, near = 0;
  for (const auto& [name, row] : reference) {
    if (!row.thesis_scene) continue;
    const Level2Case hinge = run_thesis_scene(row.velocity_m_s);
    const Agreement a = assess_agreement(row.fe, hinge.result);
    EXPECT_LT(hinge.energy_balance_error, 1e-3) << name;
    if (std::abs(row.velocity_m_s - *fe_transition) > 3.5) {
      ++away;
      for (const char* key : {"wrap_rings", "alternation", "crush", "absorbed_energy"}) {
        const Verdict& v = verdict(a, key);
        EXPECT_TRUE(v.pass) << name << " " << key << ": " << v.value << " (" << v.detail << ")";
      }
    } else {
      ++near;
      EXPECT_LE(verdict(a, "crush").value, 0.3) << name << ": " << verdict(a, "crush").detail;
      EXPECT_LE(verdict(a, "wrap_rings").value, 1.0) << name << ": " << verdict(a, "wrap_rings").detail;
      EXPECT_TRUE(verdict(a, "absorbed_energy").pass) << name << ": " << verdict(a, "absorbed_energy").detail;
    }
  }
  EXPECT_EQ(away, 7);  // 15, 20, 25, 30, 40, 45, 50 m/s
  EXPECT_EQ(near, 3);  // 32.5, 35, 37.5 m/s
}

// Test 30 (27.7 m/s, 0.257 kg) in its three joint variants against the 48 × 2 FE: every verdict
// passes. Welded and free, both models wrap rings 1, 3 and 5 (issue 7 (d): ring 1 wraps ring 2
// in the free chain too, as in the experiments' free chains, thesis §2.4). The free chain agrees
// on its wraps since session 18's flag (S > 0.25πR or T > 45°, compare/measures.hpp): the FE folds
// ring 1's lower half at B (T 75°, S 19.3 mm), Level 2 drapes it (T 68°, S 41.8 mm); on S alone
// the FE's rings 1 and 3 read 19.3 and 16.4 mm and the verdict failed.
TEST(Level2FeReference, Test30ChainsAgreeOnEveryVerdict) {
  const auto reference = load_reference();
  for (const char* name : {"test30_welded", "test30_plates", "test30_free"}) {
    const Level2Case hinge = run_scene(name);
    const Agreement a = assess_agreement(reference.at(name).fe, hinge.result);
    EXPECT_LT(hinge.energy_balance_error, 1e-3) << name;
    for (const char* key : {"wrap_rings", "alternation", "crush", "absorbed_energy"}) {
      const Verdict& v = verdict(a, key);
      EXPECT_TRUE(v.pass) << name << " " << key << ": " << v.value << " (" << v.detail << ")";
    }
  }
}

// The reference is converged where the models disagree: the three cases re-run at 72 × 2
// (data/reference/fe_explicit_72x2.csv: the thesis scene at 35 and 37.5 m/s, Test 30 free) keep
// the 48 × 2 crush per ring within 0.05 and its plastic work within 0.2 %, so the Level 2
// differences there (0.27 in ring 5's crush at 37.5 m/s) are the models', not the reference
// mesh's. The free chain keeps its wrap flags (1, 3, 5) though its folded rings 1 and 3 read a
// shorter inverted arc on the finer mesh (S 19.3 → 15.8 mm, 16.4 → 10.7 mm; T 75 → 79°, 53 →
// 52°); a flag within ~1 mm of the S threshold may cross it (35 m/s ring 5: S 19.0 → 20.1 mm).
TEST(Level2FeReference, ReferenceMeshIsConvergedWhereTheModelsDisagree) {
  const auto coarse = load_reference();
  const auto fine = load_reference("fe_explicit_72x2.csv");
  ASSERT_EQ(fine.size(), 3u);
  for (const auto& [name, row] : fine) {
    const auto& c = coarse.at(name).fe;
    for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(row.fe.crush_ratio[i], c.crush_ratio[i], 0.05) << name << " ring " << i + 1;
    EXPECT_NEAR(row.fe.plastic_j[0] / c.plastic_j[0], 1.0, 2e-3) << name;
  }
  EXPECT_EQ(fine.at("test30_free").fe.wrap_around, coarse.at("test30_free").fe.wrap_around);
}
