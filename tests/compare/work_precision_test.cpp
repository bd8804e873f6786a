// The error measures of `ringcrush bench` (compare/work_precision.hpp) on crafted runs: a run
// against itself has no error, the crush error is the largest ring difference, the energy and
// peak-force errors are relative, a zero reference is handled, ring counts must match; the
// CSV writer refuses non-finite numbers and the diagram leaves references (error 0) out.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "compare/work_precision.hpp"

namespace {
using namespace ringcrush::compare;

RunResult crafted(std::vector<double> crush, double plastic_j, double force_n) {
  RunResult r;
  r.model = "fe";
  r.crush_ratio = std::move(crush);
  r.wrap_around.assign(r.crush_ratio.size(), false);
  r.time_s = {0.0, 1e-3};
  r.impactor_force_n = {force_n, force_n};  // constant: the windowed peak is the force
  r.plastic_j = {0.0, plastic_j};
  return r;
}

TEST(WorkPrecision, RunAgainstItselfHasNoError) {
  const auto r = crafted({0.6, 0.3, 0.7}, 12.0, 1500.0);
  const auto e = run_errors(r, r);
  EXPECT_EQ(e.crush, 0.0);
  EXPECT_EQ(e.energy, 0.0);
  EXPECT_EQ(e.peak_force, 0.0);
}

TEST(WorkPrecision, CrushErrorIsTheLargestRingDifferenceAndTheOthersRelative) {
  const auto ref = crafted({0.6, 0.3, 0.7}, 10.0, 1000.0);
  const auto run = crafted({0.62, 0.25, 0.71}, 11.0, 900.0);
  const auto e = run_errors(run, ref);
  EXPECT_NEAR(e.crush, 0.05, 1e-12);
  EXPECT_NEAR(e.energy, 0.1, 1e-12);
  EXPECT_NEAR(e.peak_force, 0.1, 1e-9);
}

TEST(WorkPrecision, ZeroReferenceGivesZeroOrOne) {
  const auto ref = crafted({0.0}, 0.0, 0.0);
  EXPECT_EQ(run_errors(crafted({0.0}, 0.0, 0.0), ref).energy, 0.0);
  EXPECT_EQ(run_errors(crafted({0.1}, 2.0, 5.0), ref).energy, 1.0);
  EXPECT_EQ(run_errors(crafted({0.1}, 2.0, 5.0), ref).peak_force, 1.0);
}

TEST(WorkPrecision, DifferentRingCountsAreRefused) {
  EXPECT_THROW(run_errors(crafted({0.1, 0.2}, 1, 1), crafted({0.1}, 1, 1)), std::invalid_argument);
}

TEST(WorkPrecision, CsvRefusesNonFiniteAndDiagramSkipsReferences) {
  BenchRow ok;
  ok.group = "work_precision";
  ok.model = "hinge";
  ok.level_or_mesh = "level 1";
  ok.integrator = "odeint";
  ok.control = "rtol";
  ok.tolerance = 1e-6;
  ok.cpu_s = ok.wall_s = 1e-3;
  ok.error.crush = 1e-5;
  ok.measures.crush_ratio = {0.5};
  BenchRow ref = ok;
  ref.reference = true;
  ref.error = {};
  const auto file = std::filesystem::temp_directory_path() / "ringcrush_work_precision_test.csv";
  write_bench_csv(file, {ok, ref});
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("error_vs_reference"), std::string::npos);
  const std::string svg = render_work_precision({ok, ref}, "t");
  EXPECT_NE(svg.find("hinge level 1 odeint"), std::string::npos);
  BenchRow bad = ok;
  bad.error.crush = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_bench_csv(file, {bad}), std::runtime_error);
  std::filesystem::remove(file);
}

}  // namespace
