#include "svg_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace ringcrush::compare {
namespace {
const char* const palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                               "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

}  // namespace

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::vector<double> nice_ticks(double lo, double hi, int target_count) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double raw = (hi - lo) / std::max(1, target_count);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * magnitude >= raw) { step = m * magnitude; break; }
  // A range at the rounding level of its values (a series flat but for the last bits) gives a
  // step that adding to v no longer changes: the ends are the only honest ticks.
  if (!(step > 0) || lo + step == lo || hi - step == hi) return {lo, hi};
  std::vector<double> ticks;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step)
    ticks.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  return ticks;
}

SvgPlot::SvgPlot(std::string title, std::string x_label, std::string y_label)
    : title_(std::move(title)), x_label_(std::move(x_label)), y_label_(std::move(y_label)) {}

void SvgPlot::add(Series series) {
  if (series.x.size() != series.y.size()) throw std::logic_error("SvgPlot: x and y differ in length");
  series_.push_back(std::move(series));
}

void SvgPlot::set_log_axes(bool log_x, bool log_y) { log_x_ = log_x; log_y_ = log_y; }

std::string SvgPlot::render(int width, int height) const {
  const double left = 80, right = 190, top = 40, bottom = 60;
  const double pw = width - left - right, ph = height - top - bottom;
  auto tx = [&](double v) { return log_x_ ? std::log10(v) : v; };
  auto ty = [&](double v) { return log_y_ ? std::log10(v) : v; };

  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : series_)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if ((log_x_ && s.x[i] <= 0) || (log_y_ && s.y[i] <= 0)) continue;
      x0 = std::min(x0, tx(s.x[i])); x1 = std::max(x1, tx(s.x[i]));
      y0 = std::min(y0, ty(s.y[i])); y1 = std::max(y1, ty(s.y[i]));
    }
  if (!std::isfinite(x0)) { x0 = 0; x1 = 1; y0 = 0; y1 = 1; }
  // A flat series (or one flat to the last few bits): open the axis around its value.
  auto open_flat = [](double& lo, double& hi) {
    if (hi - lo > 1e-9 * std::max(std::abs(lo), std::abs(hi))) return;
    const double mid = 0.5 * (lo + hi), half = mid != 0.0 ? 0.05 * std::abs(mid) : 0.5;
    lo = mid - half;
    hi = mid + half;
  };
  open_flat(x0, x1);
  open_flat(y0, y1);
  if (!log_y_ && y0 > 0 && y0 < 0.3 * y1) y0 = 0;  // start force/energy axes at zero
  const auto xt = nice_ticks(x0, x1), yt = nice_ticks(y0, y1);
  x0 = std::min(x0, xt.front()); x1 = std::max(x1, xt.back());
  y0 = std::min(y0, yt.front()); y1 = std::max(y1, yt.back());
  auto px = [&](double v) { return left + (tx(v) - x0) / (x1 - x0) * pw; };
  auto py = [&](double v) { return top + ph - (ty(v) - y0) / (y1 - y0) * ph; };
  auto label = [](double v, bool log) { return log ? fmt::format("1e{:g}", v) : fmt::format("{:g}", v); };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      width, height);
  svg += fmt::format("<text x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">{}</text>\n",
                     left + pw / 2, xml_escape(title_));
  for (double v : xt) {
    const double x = left + (v - x0) / (x1 - x0) * pw;
    svg += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
                       "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
                       x, top, top + ph, top + ph + 16, label(v, log_x_));
  }
  for (double v : yt) {
    const double y = top + ph - (v - y0) / (y1 - y0) * ph;
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
                       "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
                       left, y, left + pw, left - 6, y + 4, label(v, log_y_));
  }
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n",
                     left, top, pw, ph);
  svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", left + pw / 2,
                     height - 18, xml_escape(x_label_));
  svg += fmt::format("<text transform=\"translate(20,{}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     top + ph / 2, xml_escape(y_label_));

  for (std::size_t k = 0; k < series_.size(); ++k) {
    const auto& s = series_[k];
    const char* colour = palette[k % std::size(palette)];
    std::string points;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if ((log_x_ && s.x[i] <= 0) || (log_y_ && s.y[i] <= 0)) continue;
      if (s.markers)
        svg += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3\" fill=\"{}\"/>\n", px(s.x[i]), py(s.y[i]), colour);
      else
        points += fmt::format("{:.2f},{:.2f} ", px(s.x[i]), py(s.y[i]));
    }
    if (!s.markers)
      svg += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.8\"{} points=\"{}\"/>\n",
                         colour, s.dashed ? " stroke-dasharray=\"6,4\"" : "", points);
    const double ly = top + 14 + 18.0 * static_cast<double>(k);
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"{3}\" stroke-width=\"2\"{4}/>"
                       "<text x=\"{5}\" y=\"{6}\">{7}</text>\n",
                       left + pw + 10, ly, left + pw + 34, colour,
                       s.dashed ? " stroke-dasharray=\"6,4\"" : "", left + pw + 40, ly + 4, xml_escape(s.label));
  }
  svg += "</svg>\n";
  return svg;
}

void SvgPlot::write(const std::filesystem::path& file) const {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  out << render();
}

}  // namespace ringcrush::compare
