#include "compare/hinge_shapes_output.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/os.h>
#include <fstream>
#include <stdexcept>

namespace ringcrush::compare {

namespace {

std::ofstream open_file(const std::filesystem::path& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path.string());
  return f;
}

// One frame: every ring a closed polyline; plates (impactor face, interleaved plates,
// target face) as lines across the chain width.
void write_vtp(const std::filesystem::path& path, const hinge::PolygonShape& s, double half_width) {
  std::size_t points = 0, lines = 0;
  for (const auto& ring : s.nodes) points += ring.size();
  points += 2 * s.body_faces.size();
  lines = s.nodes.size() + s.body_faces.size();
  auto f = open_file(path);
  f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<PolyData>\n"
    << fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
                   "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n", points, lines)
    << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& ring : s.nodes)
    for (const auto& p : ring) f << fmt::format("{:.9g} {:.9g} 0\n", p[0], p[1]);
  for (double y : s.body_faces) f << fmt::format("{:.9g} {:.9g} 0\n{:.9g} {:.9g} 0\n", -half_width, y, half_width, y);
  f << "</DataArray>\n</Points>\n<PointData Scalars=\"plastic_rotation\">\n"
    << "<DataArray type=\"Float64\" Name=\"plastic_rotation\" format=\"ascii\">\n";
  for (const auto& ring : s.plastic_rotation)
    for (double a : ring) f << fmt::format("{:.6g}\n", a);
  for (std::size_t b = 0; b < 2 * s.body_faces.size(); ++b) f << "0\n";
  f << "</DataArray>\n<DataArray type=\"Float64\" Name=\"turning_angle\" format=\"ascii\">\n";
  for (const auto& ring : s.turning)
    for (double a : ring) f << fmt::format("{:.6g}\n", a);
  for (std::size_t b = 0; b < 2 * s.body_faces.size(); ++b) f << "0\n";
  f << "</DataArray>\n</PointData>\n<CellData>\n<DataArray type=\"Int32\" Name=\"ring\" format=\"ascii\">\n";
  for (std::size_t r = 0; r < s.nodes.size(); ++r) f << r + 1 << "\n";
  for (std::size_t b = 0; b < s.body_faces.size(); ++b) f << "0\n";
  f << "</DataArray>\n</CellData>\n<Lines>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  std::size_t base = 0;
  for (const auto& ring : s.nodes) {
    for (std::size_t k = 0; k < ring.size(); ++k) f << base + k << " ";
    f << base << "\n";  // closed
    base += ring.size();
  }
  for (std::size_t b = 0; b < s.body_faces.size(); ++b) f << base + 2 * b << " " << base + 2 * b + 1 << "\n";
  f << "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  std::size_t offset = 0;
  for (const auto& ring : s.nodes) f << (offset += ring.size() + 1) << "\n";
  for (std::size_t b = 0; b < s.body_faces.size(); ++b) f << (offset += 2) << "\n";
  f << "</DataArray>\n</Lines>\n</Piece>\n</PolyData>\n</VTKFile>\n";
}

}  // namespace

void write_level2_shape_frames(const Level2Run& run, const Scene& scene, ResultsDir& out, int frames) {
  const auto& h = run.raw.history;
  if (h.shapes.empty()) return;
  const std::size_t n = h.shapes.size();
  const std::size_t count = std::clamp<std::size_t>(static_cast<std::size_t>(std::max(frames, 2)), 2, n);
  std::vector<std::size_t> picks;
  for (std::size_t i = 0; i < count; ++i) picks.push_back(i * (n - 1) / (count - 1));
  picks.erase(std::unique(picks.begin(), picks.end()), picks.end());
  auto pvd = open_file(out.file("shapes.pvd"));
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (std::size_t f = 0; f < picks.size(); ++f) {
    const std::string name = fmt::format("frames/shape_{:04d}.vtp", f);
    write_vtp(out.file(name), h.shapes[picks[f]], scene.rings.outer_diameter_m);
    pvd << fmt::format("<DataSet timestep=\"{:.9g}\" file=\"{}\"/>\n", h.time_s[picks[f]], name);
  }
  pvd << "</Collection>\n</VTKFile>\n";
}

void write_level2_final_svg(const Level2Run& run, const Scene& scene, ResultsDir& out) {
  const auto& h = run.raw.history;
  if (h.shapes.empty()) return;
  const auto& first = h.shapes.front();
  const auto& last = h.shapes.back();
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const auto* s : {&first, &last})
    for (const auto& ring : s->nodes)
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
  auto polyline = [&](const std::vector<std::array<double, 2>>& ring, const char* colour, double stroke) {
    f << "<polygon fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"" << stroke << "\" points=\"";
    for (const auto& p : ring) f << fmt::format("{:.1f},{:.1f} ", X(p[0]), Y(p[1]));
    f << "\"/>\n";
  };
  for (const auto& ring : first.nodes) polyline(ring, "#cccccc", 1.0);
  const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  for (std::size_t r = 0; r < last.nodes.size(); ++r) {
    polyline(last.nodes[r], colours[r % 6], std::max(1.0, t * scale));
    double cy = 0;
    for (const auto& p : last.nodes[r]) cy += p[1];
    cy /= static_cast<double>(last.nodes[r].size());
    const bool wrap = r < run.result.wrap_around.size() && run.result.wrap_around[r];
    f << fmt::format("<text x=\"{:.0f}\" y=\"{:.0f}\">ring {}: c = {:.2f}{}</text>\n", X(xmax) - 230,
                     Y(cy), r + 1, r < run.result.crush_ratio.size() ? run.result.crush_ratio[r] : 0.0,
                     wrap ? ", wrap" : "");
  }
  for (double y : last.body_faces)
    f << fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"black\" "
                     "stroke-width=\"2\"/>\n", X(-0.5 * D), Y(y), X(0.5 * D), Y(y));
  f << fmt::format("<text x=\"10\" y=\"{:.0f}\">{}: Level 2 final shapes (grey: undeformed), t = {:.2f} ms</text>\n",
                   height + 22, scene.name, h.time_s.back() * 1e3);
  f << "</svg>\n";
}

}  // namespace ringcrush::compare
