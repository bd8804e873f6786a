// Results directories are complete or absent; CSV and JSON writers refuse NaN; SVG renders.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "compare/results_dir.hpp"
#include "compare/svg_plot.hpp"
#include "compare/table_output.hpp"

using namespace ringcrush::compare;
namespace fs = std::filesystem;

namespace {
fs::path fresh_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("ringcrush_output_test_" + name);
  fs::remove_all(p);
  return p;
}
int entries(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}
}  // namespace

TEST(ResultsDir, CommitMovesEverythingIntoPlace) {
  const fs::path parent = fresh_dir("commit");
  const fs::path target = parent / "run";
  {
    ResultsDir out(target);
    std::ofstream(out.file("a.txt")) << "a";
    std::ofstream(out.file("frames/f0.vtu")) << "f";
    EXPECT_FALSE(fs::exists(target));  // nothing visible before commit
    out.commit();
  }
  EXPECT_TRUE(fs::exists(target / "a.txt"));
  EXPECT_TRUE(fs::exists(target / "frames" / "f0.vtu"));
  EXPECT_EQ(entries(parent), 1);  // no staging left behind
}

TEST(ResultsDir, FailedRunLeavesNothing) {
  const fs::path parent = fresh_dir("fail");
  try {
    ResultsDir out(parent / "run");
    std::ofstream(out.file("summary.json")) << "{}";
    throw std::runtime_error("solver diverged");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(parent / "run"));
  EXPECT_EQ(entries(parent), 0);
}

TEST(ResultsDir, ReplacesAnOlderResultOnlyOnSuccess) {
  const fs::path parent = fresh_dir("replace");
  const fs::path target = parent / "run";
  {
    ResultsDir out(target);
    std::ofstream(out.file("old.txt")) << "old";
    out.commit();
  }
  {
    ResultsDir out(target);
    std::ofstream(out.file("new.txt")) << "new";
    // not committed: the old result stays as it was
  }
  EXPECT_TRUE(fs::exists(target / "old.txt"));
  {
    ResultsDir out(target);
    std::ofstream(out.file("new.txt")) << "new";
    out.commit();
  }
  EXPECT_TRUE(fs::exists(target / "new.txt"));
  EXPECT_FALSE(fs::exists(target / "old.txt"));
  EXPECT_EQ(entries(parent), 1);
}

TEST(CsvTable, WritesHeaderAndRowsAndRefusesNaN) {
  CsvTable t;
  t.columns = {"deflection_m", "force_N"};
  t.add_row({0.0, 0.0});
  t.add_row({0.001, 355.5});
  EXPECT_THROW(t.add_row({0.002, std::numeric_limits<double>::quiet_NaN()}), std::runtime_error);
  EXPECT_THROW(t.add_row({0.002}), std::logic_error);
  EXPECT_EQ(t.column("force_N")[1], 355.5);
  const fs::path f = fresh_dir("csv");
  fs::create_directories(f);
  t.write(f / "h.csv");
  std::ifstream in(f / "h.csv");
  std::string header, row0, row1;
  std::getline(in, header);
  std::getline(in, row0);
  std::getline(in, row1);
  EXPECT_EQ(header, "deflection_m,force_N");
  EXPECT_EQ(row1, "0.001,355.5");
}

TEST(Json, RefusesNonFiniteNumbersAnywhere) {
  nlohmann::json ok = {{"a", 1.0}, {"b", {1.0, 2.0}}};
  EXPECT_NO_THROW(require_finite(ok));
  nlohmann::json bad = {{"a", 1.0}, {"b", {{"c", {1.0, std::numeric_limits<double>::infinity()}}}}};
  try {
    require_finite(bad);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/b/c/1"), std::string::npos) << e.what();
  }
}

TEST(SvgPlot, TicksAreNiceAndCoverTheRange) {
  const auto t = nice_ticks(0.0, 47.6);
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
  EXPECT_GE(t.back(), 40.0);
  EXPECT_NEAR(t[1] - t[0], 10.0, 1e-12);
  const auto s = nice_ticks(-0.013, 0.021);
  EXPECT_LE(s.front(), -0.01 + 1e-12);
  EXPECT_GE(s.back(), 0.02 - 1e-12);
}

// A series flat but for its last bits (a Level 3 plated chain at 40 m/s plotted a force whose
// range was below the rounding of its values): the ticks end, and the plot has finite
// coordinates instead of hanging in the tick loop.
TEST(SvgPlot, NearlyFlatSeriesEndsWithFiniteCoordinates) {
  const double v = 1234.5678;
  const auto t = nice_ticks(v, std::nextafter(std::nextafter(v, 2 * v), 2 * v));
  ASSERT_FALSE(t.empty());
  EXPECT_LE(t.size(), 2u);
  SvgPlot p("flat", "t (ms)", "F (N)");
  p.add({"F", {0, 1, 2}, {v, std::nextafter(v, 2 * v), v}});
  const std::string svg = p.render();
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
  EXPECT_NE(svg.find(">1200<"), std::string::npos);  // the axis opened ±5 % around the value
}

TEST(SvgPlot, RendersSeriesLabelsAndEscapes) {
  SvgPlot p("P <vs> δ", "δ (mm)", "P (N)");
  p.add({"DeRuntz–Hodge", {0, 1, 2}, {355, 356, 360}});
  p.add({"Redwood & α=2", {0, 1, 2}, {355, 370, 390}, true});
  const std::string svg = p.render();
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("P &lt;vs&gt; δ"), std::string::npos);
  EXPECT_NE(svg.find("Redwood &amp; α=2"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  std::size_t polylines = 0;
  for (auto pos = svg.find("<polyline"); pos != std::string::npos; pos = svg.find("<polyline", pos + 1)) ++polylines;
  EXPECT_EQ(polylines, 2u);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}
