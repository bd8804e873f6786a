// Two chart kinds the line plot (svg_plot.hpp) cannot draw, for reports: grouped bars (one
// group per ring, one bar per model) and ring outlines drawn to scale (equal axes).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace ringcrush::compare {

struct BarGroup {
  std::string label;           // legend entry, e.g. "FE"
  std::vector<double> values;  // one per category
};

// Grouped bar chart; values must be finite (std::invalid_argument otherwise).
std::string render_bar_chart(const std::string& title, const std::string& y_label,
                             const std::vector<std::string>& categories, const std::vector<BarGroup>& groups,
                             int width = 720, int height = 400);

struct OutlineSet {
  std::string label;
  std::vector<std::vector<std::array<double, 2>>> rings;  // polylines (m)
  bool mirror = false;  // half-model outlines: also draw the x → −x mirror image
  bool dashed = false;
};

// Outlines to scale in millimetres, every set in its own colour.
std::string render_outlines(const std::string& title, const std::vector<OutlineSet>& sets, int width = 720,
                            int height = 720);

}  // namespace ringcrush::compare
