// Line and bar charts as standalone SVG, for results directories and reports.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace ringcrush::compare {

struct Series {
  std::string label;
  std::vector<double> x, y;
  bool dashed = false;
  bool markers = false;   // draw points, not a line
};

class SvgPlot {
 public:
  SvgPlot(std::string title, std::string x_label, std::string y_label);
  void add(Series series);
  void set_log_axes(bool log_x, bool log_y);
  std::string render(int width = 720, int height = 460) const;
  void write(const std::filesystem::path& file) const;

 private:
  std::string title_, x_label_, y_label_;
  std::vector<Series> series_;
  bool log_x_ = false, log_y_ = false;
};

// Text for XML/HTML content and attribute values (< > & ").
std::string xml_escape(const std::string& s);

// "Nice" tick positions covering [lo, hi] (1, 2, 5 × 10^k steps).
std::vector<double> nice_ticks(double lo, double hi, int target_count = 6);

}  // namespace ringcrush::compare
