// ParaView output of the ring (DESIGN.md "Output"): one VTK XML unstructured grid per frame
// (quadratic quads, VTK cell type 23, whose node order is the CPS8 order) with point data
// `displacement` and `contact_pressure` and cell data `PEEQ` and `Mises`, and a `.pvd`
// collection indexed by the plate travel.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "fe/mesh/ring_mesh.hpp"
#include "fe/time/static_driver.hpp"

namespace ringcrush::fe {

void write_vtu(const std::filesystem::path& file, const RingMesh& mesh, const FieldFrame& frame);
// entries: (time or deflection, file name relative to the .pvd).
void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& entries);

}  // namespace ringcrush::fe
