// ParaView output of the rings (DESIGN.md "Output"): one VTK XML unstructured grid per frame
// (quadratic quads, VTK cell type 23, whose node order is the CPS8 order) with point data
// `displacement` and `contact_pressure` and cell data `PEEQ` and `Mises` (and `ring` for a
// chain), and a `.pvd` collection indexed by the plate travel or the time.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/dynamic_run.hpp"
#include "fe/mesh/ring_mesh.hpp"
#include "fe/time/static_driver.hpp"

namespace ringcrush::fe {

// One ring of the static crush.
void write_vtu(const std::filesystem::path& file, const RingMesh& mesh, const FieldFrame& frame);
// A chain of the dynamic impact: the rigid-body nodes (impactor, plates) are written as points
// without cells, so the point data stays indexed like the model's nodes.
void write_vtu(const std::filesystem::path& file, const ChainMesh& mesh, const DynamicFrame& frame);
// entries: (time or deflection, file name relative to the .pvd).
void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& entries);

}  // namespace ringcrush::fe
