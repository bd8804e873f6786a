#include "compare/shape_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace ringcrush::compare {

namespace {

using Polyline = std::vector<std::array<double, 2>>;

std::ofstream open_file(const std::filesystem::path& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path.string());
  return f;
}

// Signed turning angle at each point of a closed polyline (2π/n on an undeformed n-gon;
// negative where the ring is inverted).
std::vector<double> turning_angles(const Polyline& p) {
  const std::size_t n = p.size();
  std::vector<double> t(n, 0.0);
  if (n < 3) return t;
  for (std::size_t k = 0; k < n; ++k) {
    const auto& a = p[(k + n - 1) % n];
    const auto& b = p[k];
    const auto& c = p[(k + 1) % n];
    const double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
    t[k] = std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
  }
  return t;
}

double half_width(const ShapeFrame& s) {
  double w = 0.0;
  for (const auto& ring : s.rings)
    for (const auto& p : ring) w = std::max(w, std::abs(p[0]));
  return w;
}

// One frame: every ring a closed polyline; body faces as lines across the chain width.
void write_vtp(const std::filesystem::path& path, const ShapeFrame& s) {
  const double hw = half_width(s);
  std::size_t points = 2 * s.body_faces.size();
  for (const auto& ring : s.rings) points += ring.size();
  const std::size_t lines = s.rings.size() + s.body_faces.size();
  auto f = open_file(path);
  f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<PolyData>\n"
    << fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
                   "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n", points, lines)
    << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& ring : s.rings)
    for (const auto& p : ring) f << fmt::format("{:.9g} {:.9g} 0\n", p[0], p[1]);
  for (double y : s.body_faces) f << fmt::format("{:.9g} {:.9g} 0\n{:.9g} {:.9g} 0\n", -hw, y, hw, y);
  f << "</DataArray>\n</Points>\n<PointData Scalars=\"turning_angle\">\n";
  auto point_array = [&](const char* name, auto&& value_of_ring) {
    f << "<DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
    for (std::size_t r = 0; r < s.rings.size(); ++r)
      for (double a : value_of_ring(r)) f << fmt::format("{:.6g}\n", a);
    for (std::size_t b = 0; b < 2 * s.body_faces.size(); ++b) f << "0\n";
    f << "</DataArray>\n";
  };
  point_array("turning_angle", [&](std::size_t r) { return turning_angles(s.rings[r]); });
  if (s.plastic_rotation.size() == s.rings.size())
    point_array("plastic_rotation", [&](std::size_t r) {
      auto a = s.plastic_rotation[r];
      a.resize(s.rings[r].size(), 0.0);
      return a;
    });
  f << "</PointData>\n<CellData>\n<DataArray type=\"Int32\" Name=\"ring\" format=\"ascii\">\n";
  for (std::size_t r = 0; r < s.rings.size(); ++r) f << r + 1 << "\n";
  for (std::size_t b = 0; b < s.body_faces.size(); ++b) f << "0\n";
  f << "</DataArray>\n</CellData>\n<Lines>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  std::size_t base = 0;
  for (const auto& ring : s.rings) {
    for (std::size_t k = 0; k < ring.size(); ++k) f << base + k << " ";
    f << base << "\n";  // closed
    base += ring.size();
  }
  for (std::size_t b = 0; b < s.body_faces.size(); ++b) f << base + 2 * b << " " << base + 2 * b + 1 << "\n";
  f << "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  std::size_t offset = 0;
  for (const auto& ring : s.rings) f << (offset += ring.size() + 1) << "\n";
  for (std::size_t b = 0; b < s.body_faces.size(); ++b) f << (offset += 2) << "\n";
  f << "</DataArray>\n</Lines>\n</Piece>\n</PolyData>\n</VTKFile>\n";
}

}  // namespace

std::vector<std::size_t> frame_samples(std::size_t samples, int frames) {
  std::vector<std::size_t> picks;
  if (frames <= 0 || samples == 0) return picks;
  if (samples == 1 || frames == 1) return {samples - 1};
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(frames), samples);
  for (std::size_t i = 0; i < count; ++i) picks.push_back(i * (samples - 1) / (count - 1));
  picks.erase(std::unique(picks.begin(), picks.end()), picks.end());
  return picks;
}

void write_shape_frames(const RunResult& r, ResultsDir& out) {
  if (r.shape_frames.empty()) return;
  auto pvd = open_file(out.file("shapes.pvd"));
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (std::size_t f = 0; f < r.shape_frames.size(); ++f) {
    const std::string name = fmt::format("frames/shape_{:04d}.vtp", f);
    write_vtp(out.file(name), r.shape_frames[f]);
    pvd << fmt::format("<DataSet timestep=\"{:.9g}\" file=\"{}\"/>\n", r.shape_frames[f].time_s, name);
  }
  pvd << "</Collection>\n</VTKFile>\n";
}

void write_final_shapes_svg(const RunResult& r, const Scene& scene, ResultsDir& out) {
  if (r.shape_frames.empty()) return;
  const auto& first = r.shape_frames.front();
  const auto& last = r.shape_frames.back();
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const auto* s : {&first, &last})
    for (const auto& ring : s->rings)
      for (const auto& p : ring) {
        xmin = std::min(xmin, p[0]);
        xmax = std::max(xmax, p[0]);
        ymin = std::min(ymin, p[1]);
        ymax = std::max(ymax, p[1]);
      }
  const double D = scene.rings.outer_diameter_m, t = scene.rings.wall_thickness_m;
  xmin -= 0.6 * D;
  xmax += 0.6 * D;
  ymin -= 0.1 * D;
  ymax += 0.1 * D;
  const double scale = 8000.0;  // px per m: a 50.8 mm ring is ~400 px
  const double width = (xmax - xmin) * scale, height = (ymax - ymin) * scale;
  auto X = [&](double x) { return (x - xmin) * scale; };
  auto Y = [&](double y) { return (ymax - y) * scale; };
  auto f = open_file(out.file("shapes_final.svg"));
  f << fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" "
                   "viewBox=\"0 0 {:.0f} {:.0f}\" font-family=\"sans-serif\" font-size=\"14\">\n",
                   width, height + 30, width, height + 30);
  f << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  auto polygon = [&](const Polyline& ring, const char* colour, double stroke) {
    f << "<polygon fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"" << stroke << "\" points=\"";
    for (const auto& p : ring) f << fmt::format("{:.1f},{:.1f} ", X(p[0]), Y(p[1]));
    f << "\"/>\n";
  };
  for (const auto& ring : first.rings) polygon(ring, "#cccccc", 1.0);
  const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  for (std::size_t k = 0; k < last.rings.size(); ++k) {
    if (last.rings[k].empty()) continue;
    polygon(last.rings[k], colours[k % 6], std::max(1.0, t * scale));
    double cy = 0;
    for (const auto& p : last.rings[k]) cy += p[1];
    cy /= static_cast<double>(last.rings[k].size());
    const bool wrap = k < r.wrap_around.size() && r.wrap_around[k];
    f << fmt::format("<text x=\"{:.0f}\" y=\"{:.0f}\">ring {}: c = {:.2f}{}</text>\n", X(xmax) - 230, Y(cy), k + 1,
                     k < r.crush_ratio.size() ? r.crush_ratio[k] : 0.0, wrap ? ", wrap" : "");
  }
  for (double y : last.body_faces)
    f << fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"black\" "
                     "stroke-width=\"2\"/>\n", X(-0.5 * D), Y(y), X(0.5 * D), Y(y));
  const std::string level = r.extra.contains("level") && r.extra["level"].is_string()
                                ? " Level " + r.extra["level"].get<std::string>()
                                : "";
  f << fmt::format("<text x=\"10\" y=\"{:.0f}\">{}: {}{} final shapes (grey: first frame), t = {:.2f} ms</text>\n",
                   height + 22, r.scene, r.model, level, last.time_s * 1e3);
  f << "</svg>\n";
}

}  // namespace ringcrush::compare
