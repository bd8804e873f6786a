// Pieces of a CalculiX deck (compare/calculix_export.hpp): numbers ccx reads back, id lists,
// element blocks, rigid plate strips.
#pragma once

#include <Eigen/Core>
#include <array>
#include <sstream>
#include <string>
#include <vector>

#include "compare/scene.hpp"

namespace ringcrush::compare::calculix_parts {

// The shortest decimal that reads back as the same double, shortened further only if it
// exceeds the 20 characters ccx reads per field (its Fortran A20 reads: a longer field is a
// fatal "*ERROR reading *NODE"); then the most significant digits that fit.
std::string num(double v);

// Id lists 8 to a line (ccx reads at most 16 entries per data line).
void write_ids(std::ostringstream& o, const std::vector<int>& ids);

// ids first, first + 1, ..., first + count − 1.
std::vector<int> id_range(int first, std::size_t count);

// A rigid plate as a strip of CPS8 elements along x, one element thick, whose face at y =
// face_y is the contact face; `up` = the strip lies above that face. Node order makes face 1
// (nodes 1-5-2, ccx label S1) the face at face_y and face 3 (S3) the back face, and keeps
// every element counter-clockwise (positive area), as ccx requires.
struct PlateStrip {
  std::vector<Eigen::Vector2d> nodes;
  std::vector<std::array<int, 8>> elements;  // local 0-based ids
  int reference = -1;                        // local id of the face node at x = 0
};
PlateStrip make_plate_strip(double x_lo, double x_hi, int count, double face_y, double thickness, bool up);

// ccx has CPS8 (3×3) and CPS8R (2×2); ringcrush's selective scheme (volumetric strain at the
// 2×2 points, thesis §3.6.1.4) has no ccx counterpart: full integration is the closest in
// plane stress, where the volumetric constraint that the scheme relieves is weak.
std::string element_type(Integration integration);

// "*ELEMENT, TYPE=…, ELSET=…" and one line per element, ids from first_element, node ids
// offset by node_offset (local 0-based → deck 1-based ids).
void write_elements(std::ostringstream& o, const std::string& elset, const std::string& type,
                    const std::vector<std::array<int, 8>>& elements, int first_element, int node_offset);

}  // namespace ringcrush::compare::calculix_parts
