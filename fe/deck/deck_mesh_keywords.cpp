// Mesh keywords: *NODE, *NGEN, *NCOPY, *ELEMENT, *ELGEN, *ELCOPY, *NSET, *ELSET.
// Generation follows ABAQUS 4.8: labels step by the given increments, generated labels must
// be new (a duplicate label is an error, never a silent redefinition), and every count is
// checked against max_entities before anything is allocated.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fe/deck/deck_builder.hpp"
#include "fe/deck/deck_error.hpp"
#include "fe/deck/deck_geometry.hpp"

namespace ringcrush::fe::deck {

namespace {

std::string str(long long v) { return std::to_string(v); }

ElementType element_type(const Card& card) {
  const std::string t = card.required("TYPE");
  if (t == "CPS8") return ElementType::Cps8;
  if (t == "IRS22") return ElementType::Irs22;
  if (t == "ISL22") return ElementType::Isl22;
  if (t == "MASS") return ElementType::Mass;
  throw DeckError(card.line, "*ELEMENT: element type " + t + " is not supported (CPS8, IRS22, ISL22, MASS)");
}

// The nodes of a generated copy: all shifted, except the rigid-surface reference node of an
// IRS22 element (its 4th node), which ABAQUS keeps: the surface is one rigid body.
std::vector<int> shifted_nodes(const Element& e, long long shift, const Fields& f) {
  std::vector<int> out = e.nodes;
  const std::size_t n = e.type == ElementType::Irs22 ? 3 : out.size();
  for (std::size_t k = 0; k < n; ++k) {
    const long long label = out[k] + shift;
    if (label < 1 || label > max_label) f.fail("generated node label " + str(label) + " is out of range");
    out[k] = static_cast<int>(label);
  }
  return out;
}

// Increments and label shifts are bounded by the label range, so that label arithmetic
// (count × increment ≤ 2·10^6 × 10^8) can never overflow.
long long checked_increment(const Fields& f, long long v, const char* what) {
  if (v < -max_label || v > max_label) f.fail(std::string(what) + " " + str(v) + " outside ±" + str(max_label));
  return v;
}

void check_count(const Fields& f, long long count, const char* what) {
  if (count < 1 || count > max_entities)
    f.fail(std::string(what) + " " + str(count) + " outside 1.." + str(max_entities));
}

}  // namespace

std::string to_string(ElementType t) {
  switch (t) {
    case ElementType::Cps8: return "CPS8";
    case ElementType::Irs22: return "IRS22";
    case ElementType::Isl22: return "ISL22";
    case ElementType::Mass: return "MASS";
  }
  return "?";
}

int node_count(ElementType t) {
  switch (t) {
    case ElementType::Cps8: return 8;
    case ElementType::Irs22: return 4;
    case ElementType::Isl22: return 3;
    case ElementType::Mass: return 1;
  }
  return 0;
}

void DeckBuilder::spend(long long items, int line) {
  generated_ += items;
  if (generated_ > max_generated)
    throw DeckError(line, "the deck generates more than " + str(max_generated) +
                              " nodes, elements, set members and constraints in all");
}

void DeckBuilder::add_node(int label, const Point& x, int line) {
  spend(1, line);
  const auto it = m_.nodes.find(label);
  if (it != m_.nodes.end())
    throw DeckError(line, "node " + std::to_string(label) + " defined twice (first at line " +
                              std::to_string(it->second.line) + ")");
  if (static_cast<long long>(m_.nodes.size()) >= max_entities)
    throw DeckError(line, "more than " + str(max_entities) + " nodes");
  for (double c : x)
    if (!std::isfinite(c)) throw DeckError(line, "node " + std::to_string(label) + " has a non-finite coordinate");
  m_.nodes.emplace(label, Node{x, line});
}

void DeckBuilder::add_element(int label, Element e) {
  spend(1, e.line);
  const auto it = m_.elements.find(label);
  if (it != m_.elements.end())
    throw DeckError(e.line, "element " + std::to_string(label) + " defined twice (first at line " +
                                std::to_string(it->second.line) + ")");
  if (static_cast<long long>(m_.elements.size()) >= max_entities)
    throw DeckError(e.line, "more than " + str(max_entities) + " elements");
  for (int n : e.nodes)
    if (!m_.nodes.contains(n))
      throw DeckError(e.line, "element " + std::to_string(label) + " uses node " + std::to_string(n) +
                                  ", which is not defined");
  m_.elements.emplace(label, std::move(e));
}

void DeckBuilder::add_to_set(std::map<std::string, LabelSet>& sets, const std::string& name, int label, int line) {
  spend(1, line);
  LabelSet& s = sets[name];
  if (s.line == 0) s.line = line;
  if (s.members.contains(label)) return;
  if (static_cast<long long>(s.labels.size()) >= max_entities)
    throw DeckError(line, "set " + name + " has more than " + str(max_entities) + " members");
  s.labels.push_back(label);
  s.members.insert(label);
}

const LabelSet& DeckBuilder::nset_named(const Card& card, const std::string& name, int line) const {
  const auto it = m_.nsets.find(name);
  if (it == m_.nsets.end()) throw DeckError(line, "*" + card.keyword + ": node set " + name + " is not defined");
  return it->second;
}

const LabelSet& DeckBuilder::elset_named(const Card& card, const std::string& name, int line) const {
  const auto it = m_.elsets.find(name);
  if (it == m_.elsets.end()) throw DeckError(line, "*" + card.keyword + ": element set " + name + " is not defined");
  return it->second;
}

std::vector<int> DeckBuilder::nodes_of(const Fields& f, std::size_t i, const char* what) const {
  const std::string w = f.word(i, what);
  if (is_integer_text(w)) {
    const int n = f.label(i, what);
    if (!m_.nodes.contains(n)) f.fail(std::string(what) + " " + w + " is not defined");
    return {n};
  }
  const auto it = m_.nsets.find(w);
  if (it == m_.nsets.end()) f.fail(std::string(what) + ": node set " + w + " is not defined");
  return it->second.labels;
}

void DeckBuilder::heading(const Card& card) {
  allow_parameters(card, {});
  for (const DataLine& d : card.data) m_.heading += (m_.heading.empty() ? "" : "\n") + d.text;
}

void DeckBuilder::node(const Card& card) {
  allow_parameters(card, {"NSET"});
  require_data(card);
  const auto set = card.value("NSET");
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    if (r.size() > 4) f.fail("a node line has at most 4 fields (label, x, y, z), found " + str(static_cast<long long>(r.size())));
    const int label = f.label(0, "node label");
    add_node(label, {f.real_or(1, 0.0, "x"), f.real_or(2, 0.0, "y"), f.real_or(3, 0.0, "z")}, r.line);
    if (set) add_to_set(m_.nsets, *set, label, card.line);
  }
}

void DeckBuilder::ngen(const Card& card) {
  allow_parameters(card, {"NSET", "LINE"});
  require_data(card);
  const auto set = card.value("NSET");
  const std::string line_type = card.value("LINE").value_or("L");
  if (line_type != "L" && line_type != "C")
    throw DeckError(card.line, "*NGEN: LINE=" + line_type + " is not supported (L straight, C circular)");
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    const int first = f.label(0, "first end node");
    const int last = f.label(1, "second end node");
    const long long inc = f.integer_or(2, 1, "increment");
    if (inc == 0) f.fail("increment 0");
    const long long span = static_cast<long long>(last) - first;
    if (span == 0 || span % inc != 0 || span / inc < 1)
      f.fail("nodes " + str(first) + " to " + str(last) + " are not reached in steps of " + str(inc));
    const long long intervals = span / inc;
    check_count(f, intervals, "number of generated intervals");
    for (int end : {first, last})
      if (!m_.nodes.contains(end)) f.fail("end node " + str(end) + " is not defined");
    const Point a = m_.nodes.at(first).x, b = m_.nodes.at(last).x;
    Point centre{0, 0, 0}, normal{0, 0, 1};
    if (line_type == "C") {
      if (!r.empty_at(3)) {
        const int c = f.label(3, "centre node");
        if (!m_.nodes.contains(c)) f.fail("centre node " + str(c) + " is not defined");
        centre = m_.nodes.at(c).x;
      } else {
        centre = {f.real_or(4, 0.0, "centre x"), f.real_or(5, 0.0, "centre y"), f.real_or(6, 0.0, "centre z")};
      }
      if (!r.empty_at(7) || !r.empty_at(8) || !r.empty_at(9))
        normal = {f.real_or(7, 0.0, "normal x"), f.real_or(8, 0.0, "normal y"), f.real_or(9, 0.0, "normal z")};
    } else if (r.size() > 3) {
      f.fail("a straight *NGEN line has 3 fields (first, last, increment)");
    }
    if (set) add_to_set(m_.nsets, *set, first, card.line);
    for (long long k = 1; k < intervals; ++k) {
      const double t = static_cast<double>(k) / static_cast<double>(intervals);
      Point p{};
      try {
        p = line_type == "C" ? arc_point(a, b, centre, normal, t) : straight_point(a, b, t);
      } catch (const std::invalid_argument& e) {
        f.fail(e.what());
      }
      const int label = static_cast<int>(first + k * inc);
      add_node(label, p, r.line);
      if (set) add_to_set(m_.nsets, *set, label, card.line);
    }
    if (set) add_to_set(m_.nsets, *set, last, card.line);
  }
}

void DeckBuilder::ncopy(const Card& card) {
  allow_parameters(card, {"CHANGE NUMBER", "OLD SET", "NEW SET", "SHIFT", "REFLECT", "MULTIPLE"});
  require_data(card);
  const long long change = integer_parameter(card, "CHANGE NUMBER", 0);
  if (!card.has("CHANGE NUMBER") || change == 0 || change < -max_label || change > max_label)
    throw DeckError(card.line, "*NCOPY: CHANGE NUMBER must be given, non-zero and within ±" + str(max_label));
  if (integer_parameter(card, "MULTIPLE", 1) != 1)
    throw DeckError(card.line, "*NCOPY: MULTIPLE other than 1 is not supported");
  const LabelSet& old_set = nset_named(card, card.required("OLD SET"), card.line);
  const auto new_set = card.value("NEW SET");
  const bool shift = card.has("SHIFT");
  const auto reflect = card.find("REFLECT") ? std::optional<std::string>(card.find("REFLECT")->value) : std::nullopt;
  if (shift == reflect.has_value())
    throw DeckError(card.line, "*NCOPY: give exactly one of SHIFT and REFLECT=LINE");
  if (reflect && *reflect != "LINE")
    throw DeckError(card.line, "*NCOPY: REFLECT=" + (reflect->empty() ? std::string("(none)") : *reflect) +
                                   " is not supported (REFLECT=LINE)");
  const std::vector<Record> recs = records(card);
  if (recs.size() > 2) throw DeckError(recs[2].line, "*NCOPY: at most two data lines");
  const Fields f0(card, recs[0]);
  Point translation{}, axis_a{}, axis_b{0, 0, 1}, la{}, lb{};
  double angle = 0;
  if (shift) {
    translation = {f0.real_or(0, 0, "x shift"), f0.real_or(1, 0, "y shift"), f0.real_or(2, 0, "z shift")};
    if (recs.size() == 2) {
      const Fields f1(card, recs[1]);
      axis_a = {f1.real_or(0, 0, "axis point a x"), f1.real_or(1, 0, "axis point a y"), f1.real_or(2, 0, "axis point a z")};
      axis_b = {f1.real_or(3, 0, "axis point b x"), f1.real_or(4, 0, "axis point b y"), f1.real_or(5, 0, "axis point b z")};
      angle = f1.real_or(6, 0, "rotation angle");
    }
  } else {
    if (recs.size() != 1) throw DeckError(recs[1].line, "*NCOPY, REFLECT=LINE takes one data line");
    la = {f0.real(0, "line point a x"), f0.real(1, "line point a y"), f0.real_or(2, 0, "line point a z")};
    lb = {f0.real(3, "line point b x"), f0.real(4, "line point b y"), f0.real_or(5, 0, "line point b z")};
  }
  const std::vector<int> labels = old_set.labels;  // copy: NEW SET may alias
  for (int old_label : labels) {
    const long long label = old_label + change;
    if (label < 1 || label > max_label)
      f0.fail("copied node label " + str(label) + " (node " + str(old_label) + " + " + str(change) + ") out of range");
    Point p{};
    try {
      p = shift ? shift_rotate(m_.nodes.at(old_label).x, translation, axis_a, axis_b, angle)
                : reflect_line(m_.nodes.at(old_label).x, la, lb);
    } catch (const std::invalid_argument& e) {
      f0.fail(e.what());
    }
    add_node(static_cast<int>(label), p, card.line);
    if (new_set) add_to_set(m_.nsets, *new_set, static_cast<int>(label), card.line);
  }
}

void DeckBuilder::element(const Card& card) {
  allow_parameters(card, {"TYPE", "ELSET"});
  require_data(card);
  const ElementType type = element_type(card);
  const auto set = card.value("ELSET");
  const auto n = static_cast<std::size_t>(node_count(type));
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    const int label = f.label(0, "element label");
    if (r.size() != n + 1)
      f.fail("element " + str(label) + " has " + str(static_cast<long long>(r.size()) - 1) + " nodes, " +
             to_string(type) + " needs " + str(static_cast<long long>(n)));
    Element e{type, {}, r.line};
    for (std::size_t k = 1; k <= n; ++k) e.nodes.push_back(f.label(k, "element node"));
    add_element(label, std::move(e));
    if (set) add_to_set(m_.elsets, *set, label, card.line);
  }
}

void DeckBuilder::elgen(const Card& card) {
  allow_parameters(card, {"ELSET"});
  require_data(card);
  const auto set = card.value("ELSET");
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    if (r.size() > 7) f.fail("an *ELGEN line has at most 7 fields (master, two rows of count/node/element increments)");
    const int master = f.label(0, "master element");
    const auto it = m_.elements.find(master);
    if (it == m_.elements.end()) f.fail("master element " + str(master) + " is not defined");
    const Element base = it->second;
    const long long n1 = f.integer_or(1, 1, "number of elements");
    const long long dn1 = checked_increment(f, f.integer_or(2, 1, "node increment"), "node increment");
    const long long de1 = checked_increment(f, f.integer_or(3, 1, "element increment"), "element increment");
    const long long n2 = f.integer_or(4, 1, "number of rows");
    const long long dn2 = checked_increment(f, f.integer_or(5, 1, "row node increment"), "row node increment");
    const long long de2 = checked_increment(f, f.integer_or(6, 1, "row element increment"), "row element increment");
    check_count(f, n1, "number of elements");
    check_count(f, n2, "number of rows");
    check_count(f, n1 * n2, "number of generated elements");
    for (long long j = 0; j < n2; ++j)
      for (long long i = 0; i < n1; ++i) {
        const long long label = master + i * de1 + j * de2;
        if (label < 1 || label > max_label) f.fail("generated element label " + str(label) + " out of range");
        if (i != 0 || j != 0) {
          Element e{base.type, shifted_nodes(base, i * dn1 + j * dn2, f), r.line};
          add_element(static_cast<int>(label), std::move(e));
        }
        if (set) add_to_set(m_.elsets, *set, static_cast<int>(label), card.line);
      }
  }
}

void DeckBuilder::elcopy(const Card& card) {
  allow_parameters(card, {"ELEMENT SHIFT", "OLD SET", "SHIFT NODES", "NEW SET", "REFLECT"});
  forbid_data(card);
  const long long shift = integer_parameter(card, "ELEMENT SHIFT", 0);
  if (!card.has("ELEMENT SHIFT") || shift == 0 || shift < -max_label || shift > max_label)
    throw DeckError(card.line, "*ELCOPY: ELEMENT SHIFT must be given, non-zero and within ±" + str(max_label));
  const long long node_shift = integer_parameter(card, "SHIFT NODES", 0);
  if (node_shift < -max_label || node_shift > max_label)
    throw DeckError(card.line, "*ELCOPY: SHIFT NODES outside ±" + str(max_label));
  const std::vector<int> labels = elset_named(card, card.required("OLD SET"), card.line).labels;
  const auto new_set = card.value("NEW SET");
  const bool reflect = card.has("REFLECT");
  const Record here{card.line, {}};
  const Fields f(card, here);
  for (int old_label : labels) {
    const Element& old = m_.elements.at(old_label);
    Element e{old.type, shifted_nodes(old, node_shift, f), card.line};
    // REFLECT: the copy of a mirrored node set would be numbered clockwise (inside out);
    // reverse the connectivity so the element keeps a positive area: corners 1,4,3,2 and
    // mid-sides 8,7,6,5 for CPS8, the segment ends swapped for the 3-node interfaces.
    if (reflect && e.type == ElementType::Cps8) {
      const std::vector<int> c = e.nodes;
      e.nodes = {c[0], c[3], c[2], c[1], c[7], c[6], c[5], c[4]};
    } else if (reflect && (e.type == ElementType::Isl22 || e.type == ElementType::Irs22)) {
      std::swap(e.nodes[0], e.nodes[2]);
    }
    const long long label = old_label + shift;
    if (label < 1 || label > max_label) f.fail("copied element label " + str(label) + " out of range");
    add_element(static_cast<int>(label), std::move(e));
    if (new_set) add_to_set(m_.elsets, *new_set, static_cast<int>(label), card.line);
  }
}

void DeckBuilder::nset(const Card& card) {
  allow_parameters(card, {"NSET", "GENERATE"});
  require_data(card);
  const std::string name = card.required("NSET");
  const bool generate = card.has("GENERATE");
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    if (generate) {
      const int a = f.label(0, "first node"), b = f.label(1, "last node");
      const long long inc = f.integer_or(2, 1, "increment");
      if (inc == 0 || (b - a) % inc != 0 || (b - a) / inc < 0)
        f.fail("nodes " + str(a) + " to " + str(b) + " are not reached in steps of " + str(inc));
      check_count(f, (b - a) / inc + 1, "number of generated members");
      for (long long n = a;; n += inc) {
        if (!m_.nodes.contains(static_cast<int>(n))) f.fail("node " + str(n) + " is not defined");
        add_to_set(m_.nsets, name, static_cast<int>(n), card.line);
        if (n == b) break;
      }
      continue;
    }
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (r.fields[i].empty()) continue;
      for (int n : nodes_of(f, i, "node")) add_to_set(m_.nsets, name, n, card.line);
    }
  }
}

void DeckBuilder::elset(const Card& card) {
  allow_parameters(card, {"ELSET", "GENERATE"});
  require_data(card);
  const std::string name = card.required("ELSET");
  const bool generate = card.has("GENERATE");
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    if (generate) {
      const int a = f.label(0, "first element"), b = f.label(1, "last element");
      const long long inc = f.integer_or(2, 1, "increment");
      if (inc == 0 || (b - a) % inc != 0 || (b - a) / inc < 0)
        f.fail("elements " + str(a) + " to " + str(b) + " are not reached in steps of " + str(inc));
      check_count(f, (b - a) / inc + 1, "number of generated members");
      for (long long e = a;; e += inc) {
        if (!m_.elements.contains(static_cast<int>(e))) f.fail("element " + str(e) + " is not defined");
        add_to_set(m_.elsets, name, static_cast<int>(e), card.line);
        if (e == b) break;
      }
      continue;
    }
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (r.fields[i].empty()) continue;
      const std::string w = f.word(i, "element");
      if (is_integer_text(w)) {
        const int e = f.label(i, "element");
        if (!m_.elements.contains(e)) f.fail("element " + w + " is not defined");
        add_to_set(m_.elsets, name, e, card.line);
      } else {
        const std::vector<int> members = elset_named(card, w, r.line).labels;
        for (int e : members) add_to_set(m_.elsets, name, e, card.line);
      }
    }
  }
}

}  // namespace ringcrush::fe::deck
