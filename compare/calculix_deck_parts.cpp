#include "compare/calculix_deck_parts.hpp"

#include <fmt/format.h>

#include <cmath>

namespace ringcrush::compare::calculix_parts {

std::string num(double v) {
  std::string s = fmt::format("{}", v);
  for (int digits = 16; s.size() > 20 && digits > 1; --digits) s = fmt::format("{:.{}g}", v, digits);
  return s;
}

void write_ids(std::ostringstream& o, const std::vector<int>& ids) {
  for (std::size_t i = 0; i < ids.size(); ++i) {
    o << ids[i];
    o << ((i + 1) % 8 == 0 || i + 1 == ids.size() ? "\n" : ", ");
  }
}

PlateStrip make_plate_strip(double x_lo, double x_hi, int count, double face_y, double thickness, bool up) {
  PlateStrip p;
  const int columns = 2 * count + 1;
  const double back_y = up ? face_y + thickness : face_y - thickness;
  std::vector<std::array<int, 3>> id(columns, {-1, -1, -1});  // rows: face, middle, back
  for (int c = 0; c < columns; ++c)
    for (int r = 0; r < 3; ++r) {
      if (c % 2 == 1 && r == 1) continue;
      const double x = x_lo + (x_hi - x_lo) * c / (2.0 * count);
      const double y = face_y + (back_y - face_y) * r / 2.0;
      id[c][r] = static_cast<int>(p.nodes.size());
      p.nodes.emplace_back(std::abs(x) < 1e-12 * (x_hi - x_lo) ? 0.0 : x, y);
      if (r == 0 && std::abs(x) < 1e-12 * (x_hi - x_lo)) p.reference = id[c][r];
    }
  for (int i = 0; i < count; ++i) {
    const int a = 2 * i, b = 2 * i + 2, m = 2 * i + 1;
    if (up)  // face below the strip: along +x on the face, then up
      p.elements.push_back({id[a][0], id[b][0], id[b][2], id[a][2], id[m][0], id[b][1], id[m][2], id[a][1]});
    else     // face on top of the strip: along −x on the face, then down
      p.elements.push_back({id[b][0], id[a][0], id[a][2], id[b][2], id[m][0], id[a][1], id[m][2], id[b][1]});
  }
  return p;
}

std::string element_type(Integration i) {
  return i == Integration::Reduced ? "CPS8R" : "CPS8";
}

std::vector<int> id_range(int first, std::size_t count) {
  std::vector<int> v(count);
  for (std::size_t i = 0; i < count; ++i) v[i] = first + static_cast<int>(i);
  return v;
}

void write_elements(std::ostringstream& o, const std::string& elset, const std::string& type,
                    const std::vector<std::array<int, 8>>& elements, int first_element, int node_offset) {
  o << "*ELEMENT, TYPE=" << type << ", ELSET=" << elset << "\n";
  int e = first_element;
  for (const auto& c : elements) {
    o << e++;
    for (int n : c) o << ", " << n + node_offset;
    o << "\n";
  }
}

}  // namespace ringcrush::compare::calculix_parts
