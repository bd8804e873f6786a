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
}  // namespace

void write_vtu(const std::filesystem::path& file, const RingMesh& mesh, const FieldFrame& fr) {
  std::ofstream o(file);
  if (!o) throw std::runtime_error("cannot write " + file.string());
  const std::size_t np = mesh.nodes.size(), nc = mesh.elements.size();
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<UnstructuredGrid>\n"
    << fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", np, nc);
  o << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < np; ++i) o << fmt::format("{:.9g} {:.9g} 0\n", mesh.nodes[i].x(), mesh.nodes[i].y());
  o << "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& e : mesh.elements)
    o << fmt::format("{} {} {} {} {} {} {} {}\n", e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]);
  o << "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nc; ++c) o << 8 * (c + 1) << '\n';
  o << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nc; ++c) o << "23\n";
  o << "</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\" Scalars=\"contact_pressure\">\n"
    << "<DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < np; ++i) {
    check_finite(fr.displacement(2 * i), "displacement");
    check_finite(fr.displacement(2 * i + 1), "displacement");
    o << fmt::format("{:.9g} {:.9g} 0\n", fr.displacement(2 * i), fr.displacement(2 * i + 1));
  }
  o << "</DataArray>\n<DataArray type=\"Float64\" Name=\"contact_pressure\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < np; ++i) {
    const double p = i < fr.contact_pressure_pa.size() ? fr.contact_pressure_pa[i] : 0.0;
    check_finite(p, "contact pressure");
    o << fmt::format("{:.6g}\n", p);
  }
  o << "</DataArray>\n</PointData>\n<CellData Scalars=\"PEEQ\">\n"
    << "<DataArray type=\"Float64\" Name=\"PEEQ\" format=\"ascii\">\n";
  for (double v : fr.peeq) {
    check_finite(v, "PEEQ");
    o << fmt::format("{:.6g}\n", v);
  }
  o << "</DataArray>\n<DataArray type=\"Float64\" Name=\"Mises\" format=\"ascii\">\n";
  for (double v : fr.mises_pa) {
    check_finite(v, "Mises stress");
    o << fmt::format("{:.6g}\n", v);
  }
  o << "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  if (!o) throw std::runtime_error("error writing " + file.string());
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
