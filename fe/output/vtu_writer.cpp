#include "fe/output/vtu_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace ringcrush::fe {

namespace {
void check_finite(double v, const char* what) {
  if (!std::isfinite(v)) throw std::runtime_error(fmt::format("vtu output: non-finite {}", what));
}

// What one frame of either model writes: reference nodes, CPS8 cells and the fields.
struct GridView {
  const std::vector<Eigen::Vector2d>& nodes;
  const std::vector<std::array<int, 8>>& elements;
  const Eigen::VectorXd& displacement;           // 2 per node
  const std::vector<double>& contact_pressure;   // per node (missing entries: 0)
  const std::vector<double>& peeq;               // per element
  const std::vector<double>& mises;              // per element
  const std::vector<int>* element_ring = nullptr;
  const std::vector<double>* stress = nullptr;   // per element xx, yy, xy (optional)
};

void write_grid(const std::filesystem::path& file, const GridView& g) {
  const std::size_t np = g.nodes.size(), nc = g.elements.size();
  if (static_cast<std::size_t>(g.displacement.size()) != 2 * np)
    throw std::invalid_argument(fmt::format("vtu output: {} displacement values for {} nodes",
                                            g.displacement.size(), np));
  if (g.peeq.size() != nc || g.mises.size() != nc)
    throw std::invalid_argument(fmt::format("vtu output: {} PEEQ and {} Mises values for {} elements",
                                            g.peeq.size(), g.mises.size(), nc));
  std::ofstream o(file);
  if (!o) throw std::runtime_error("cannot write " + file.string());
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<UnstructuredGrid>\n"
    << fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", np, nc);
  o << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < np; ++i) o << fmt::format("{:.9g} {:.9g} 0\n", g.nodes[i].x(), g.nodes[i].y());
  o << "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& e : g.elements)
    o << fmt::format("{} {} {} {} {} {} {} {}\n", e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]);
  o << "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nc; ++c) o << 8 * (c + 1) << '\n';
  o << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nc; ++c) o << "23\n";
  o << "</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\" Scalars=\"contact_pressure\">\n"
    << "<DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < np; ++i) {
    const auto k = static_cast<Eigen::Index>(2 * i);
    check_finite(g.displacement(k), "displacement");
    check_finite(g.displacement(k + 1), "displacement");
    o << fmt::format("{:.9g} {:.9g} 0\n", g.displacement(k), g.displacement(k + 1));
  }
  o << "</DataArray>\n<DataArray type=\"Float64\" Name=\"contact_pressure\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < np; ++i) {
    const double p = i < g.contact_pressure.size() ? g.contact_pressure[i] : 0.0;
    check_finite(p, "contact pressure");
    o << fmt::format("{:.6g}\n", p);
  }
  o << "</DataArray>\n</PointData>\n<CellData Scalars=\"PEEQ\">\n"
    << "<DataArray type=\"Float64\" Name=\"PEEQ\" format=\"ascii\">\n";
  for (double v : g.peeq) {
    check_finite(v, "PEEQ");
    o << fmt::format("{:.6g}\n", v);
  }
  o << "</DataArray>\n<DataArray type=\"Float64\" Name=\"Mises\" format=\"ascii\">\n";
  for (double v : g.mises) {
    check_finite(v, "Mises stress");
    o << fmt::format("{:.6g}\n", v);
  }
  o << "</DataArray>\n";
  if (g.element_ring) {
    o << "<DataArray type=\"Int32\" Name=\"ring\" format=\"ascii\">\n";
    for (int r : *g.element_ring) o << r + 1 << '\n';  // 1-based, as the rings are named
    o << "</DataArray>\n";
  }
  if (g.stress && g.stress->size() == 3 * nc) {
    o << "<DataArray type=\"Float64\" Name=\"stress\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (std::size_t c = 0; c < nc; ++c) {
      for (int k = 0; k < 3; ++k) check_finite((*g.stress)[3 * c + static_cast<std::size_t>(k)], "stress");
      o << fmt::format("{:.6g} {:.6g} {:.6g}\n", (*g.stress)[3 * c], (*g.stress)[3 * c + 1], (*g.stress)[3 * c + 2]);
    }
    o << "</DataArray>\n";
  }
  o << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  if (!o) throw std::runtime_error("error writing " + file.string());
}
}  // namespace

void write_vtu(const std::filesystem::path& file, const RingMesh& mesh, const FieldFrame& fr) {
  write_grid(file, {mesh.nodes, mesh.elements, fr.displacement, fr.contact_pressure_pa, fr.peeq, fr.mises_pa});
}

void write_vtu(const std::filesystem::path& file, const ChainMesh& mesh, const DynamicFrame& fr) {
  if (mesh.element_ring.size() != mesh.elements.size())
    throw std::invalid_argument("vtu output: the chain mesh has no ring for every element");
  write_grid(file, {mesh.nodes, mesh.elements, fr.displacement, fr.contact_pressure_pa, fr.peeq, fr.mises_pa,
                    &mesh.element_ring, &fr.stress_pa});
}

void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& entries) {
  std::ofstream o(file);
  if (!o) throw std::runtime_error("cannot write " + file.string());
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [t, name] : entries)
    o << fmt::format("<DataSet timestep=\"{:.9g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", t, name);
  o << "</Collection>\n</VTKFile>\n";
  if (!o) throw std::runtime_error("error writing " + file.string());
}

}  // namespace ringcrush::fe
