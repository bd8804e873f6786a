#include "compare/svg_charts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "compare/svg_plot.hpp"

namespace ringcrush::compare {
namespace {

const char* const colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd"};

std::string header(int width, int height, const std::string& title) {
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      "<text x=\"{2}\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">{3}</text>\n",
      width, height, width / 2, xml_escape(title));
}

}  // namespace

std::string render_bar_chart(const std::string& title, const std::string& y_label,
                             const std::vector<std::string>& categories, const std::vector<BarGroup>& groups,
                             int width, int height) {
  double hi = 0.0, lo = 0.0;
  for (const auto& g : groups) {
    if (g.values.size() != categories.size())
      throw std::invalid_argument("bar chart: group '" + g.label + "' has a different number of values");
    for (double v : g.values) {
      if (!std::isfinite(v)) throw std::invalid_argument("bar chart: non-finite value in group '" + g.label + "'");
      hi = std::max(hi, v);
      lo = std::min(lo, v);
    }
  }
  if (hi <= lo) hi = lo + 1.0;
  const auto ticks = nice_ticks(lo, hi);
  lo = std::min(lo, ticks.front());
  hi = std::max(hi, ticks.back());
  const double left = 70, right = 120, top = 40, bottom = 50;
  const double pw = width - left - right, ph = height - top - bottom;
  auto py = [&](double v) { return top + ph - (v - lo) / (hi - lo) * ph; };

  std::string svg = header(width, height, title);
  for (double v : ticks)
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
                       "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:g}</text>\n",
                       left, py(v), left + pw, left - 6, py(v) + 4, v);
  const double slot = pw / static_cast<double>(std::max<std::size_t>(1, categories.size()));
  const double bar = 0.8 * slot / static_cast<double>(std::max<std::size_t>(1, groups.size()));
  for (std::size_t c = 0; c < categories.size(); ++c) {
    const double x0 = left + slot * static_cast<double>(c) + 0.1 * slot;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      const double v = groups[g].values[c];
      const double y = py(std::max(v, 0.0)), h = std::abs(py(v) - py(0.0));
      svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\">"
                         "<title>{} {}: {:.4g}</title></rect>\n",
                         x0 + bar * static_cast<double>(g), y, bar, h, colours[g % std::size(colours)],
                         xml_escape(groups[g].label), xml_escape(categories[c]), v);
    }
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", x0 + 0.4 * slot,
                       top + ph + 16, xml_escape(categories[c]));
  }
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n", left,
                     top, pw, ph);
  svg += fmt::format("<text transform=\"translate(18,{}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     top + ph / 2, xml_escape(y_label));
  for (std::size_t g = 0; g < groups.size(); ++g)
    svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"14\" height=\"14\" fill=\"{}\"/><text x=\"{}\" y=\"{}\">{}</text>\n",
                       left + pw + 12, top + 6 + 20.0 * static_cast<double>(g), colours[g % std::size(colours)],
                       left + pw + 32, top + 18 + 20.0 * static_cast<double>(g), xml_escape(groups[g].label));
  return svg + "</svg>\n";
}

std::string render_outlines(const std::string& title, const std::vector<OutlineSet>& sets, int width, int height) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : sets)
    for (const auto& ring : s.rings)
      for (const auto& p : ring) {
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]))
          throw std::invalid_argument("outlines: non-finite point in '" + s.label + "'");
        const double xa = s.mirror ? -std::abs(p[0]) : p[0];
        x0 = std::min({x0, xa, p[0]});
        x1 = std::max({x1, p[0], s.mirror ? std::abs(p[0]) : p[0]});
        y0 = std::min(y0, p[1]);
        y1 = std::max(y1, p[1]);
      }
  if (!std::isfinite(x0)) { x0 = y0 = -1; x1 = y1 = 1; }
  const double top = 40, margin = 20, legend = 24.0 * static_cast<double>(sets.size());
  const double pw = width - 2 * margin, ph = height - top - margin - legend;
  const double span = std::max({x1 - x0, y1 - y0, 1e-9});
  const double scale = std::min(pw / (x1 - x0 + 1e-12 * span), ph / (y1 - y0 + 1e-12 * span));
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  auto px = [&](double x) { return margin + pw / 2 + (x - cx) * scale; };
  auto py = [&](double y) { return top + ph / 2 - (y - cy) * scale; };

  std::string svg = header(width, height, title);
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const auto& s = sets[k];
    const char* colour = colours[k % std::size(colours)];
    const char* dash = s.dashed ? " stroke-dasharray=\"5,3\"" : "";
    for (const auto& ring : s.rings)
      for (int side = 0; side < (s.mirror ? 2 : 1); ++side) {
        std::string pts;
        for (const auto& p : ring) pts += fmt::format("{:.2f},{:.2f} ", px(side ? -p[0] : p[0]), py(p[1]));
        svg += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"{} points=\"{}\"/>\n", colour,
                           dash, pts);
      }
    const double ly = top + ph + margin / 2 + 24.0 * static_cast<double>(k);
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"{3}\" stroke-width=\"2\"{4}/>"
                       "<text x=\"{5}\" y=\"{6}\">{7}</text>\n",
                       margin, ly, margin + 30, colour, dash, margin + 38, ly + 4, xml_escape(s.label));
  }
  // Scale bar: 10 mm.
  const double bar = 0.010 * scale;
  svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"black\" stroke-width=\"2\"/>"
                     "<text x=\"{3}\" y=\"{4}\" text-anchor=\"middle\">10 mm</text>\n",
                     width - margin - bar, top + 6, width - margin, width - margin - bar / 2, top + 20);
  return svg + "</svg>\n";
}

}  // namespace ringcrush::compare
