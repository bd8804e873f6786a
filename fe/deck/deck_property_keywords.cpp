// Property, contact and loading keywords: *SOLID SECTION, *MATERIAL (*ELASTIC, *PLASTIC,
// *DENSITY), *RIGID SURFACE, *INTERFACE (*FRICTION, *SURFACE CONTACT), *SLIDE LINE, *MPC,
// *BOUNDARY, *INITIAL CONDITIONS, *MASS. Values are checked for physical sense here (E > 0,
// 0 ≤ ν < 0.5, increasing hardening table...), each error naming the line.
#include <cmath>
#include <cstdio>

#include "fe/deck/deck_builder.hpp"
#include "fe/deck/deck_error.hpp"

namespace ringcrush::fe::deck {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

void require_positive(const Fields& f, double v, const char* what) {
  if (!(v > 0.0)) f.fail(std::string(what) + " must be positive, got " + num(v));
}

void one_record(const Card& card, const std::vector<Record>& recs) {
  if (recs.size() != 1) throw DeckError(recs[1].line, "*" + card.keyword + " takes one data line");
}

// ABAQUS symbolic boundary types as dof ranges: a symmetry plane x = const holds u1 and the
// rotations about y and z (dofs 1, 5, 6); ENCASTRE holds all six. Only 1, 2 and 6 exist in
// the plane decks; the others are kept as written.
struct SymbolicBoundary {
  const char* name;
  std::vector<std::pair<int, int>> dofs;
};
const std::vector<SymbolicBoundary>& symbolic_boundaries() {
  static const std::vector<SymbolicBoundary> table = {
      {"XSYMM", {{1, 1}, {5, 6}}}, {"YSYMM", {{2, 2}, {4, 4}, {6, 6}}}, {"ZSYMM", {{3, 5}}},
      {"XASYMM", {{2, 4}}},        {"YASYMM", {{1, 1}, {3, 3}, {5, 5}}}, {"ZASYMM", {{1, 2}, {6, 6}}},
      {"ENCASTRE", {{1, 6}}},      {"PINNED", {{1, 3}}},
  };
  return table;
}

}  // namespace

Step& DeckBuilder::open_step(const Card& card) {
  if (!in_step_) throw DeckError(card.line, "*" + card.keyword + " is only valid inside a *STEP");
  return m_.steps.back();
}

Material& DeckBuilder::current_material(const Card& card) {
  if (!material_) throw DeckError(card.line, "*" + card.keyword + " must follow *MATERIAL");
  return m_.materials.at(*material_);
}

Interface& DeckBuilder::current_interface(const Card& card) {
  if (!interface_) throw DeckError(card.line, "*" + card.keyword + " must follow *INTERFACE");
  return m_.interfaces.at(*interface_);
}

void DeckBuilder::solid_section(const Card& card) {
  allow_parameters(card, {"ELSET", "MATERIAL"});
  SolidSection s;
  s.elset = card.required("ELSET");
  s.material = card.required("MATERIAL");
  s.line = card.line;
  for (int e : elset_named(card, s.elset, card.line).labels)
    if (m_.elements.at(e).type != ElementType::Cps8)
      throw DeckError(card.line, "*SOLID SECTION: element " + std::to_string(e) + " of set " + s.elset +
                                     " is " + to_string(m_.elements.at(e).type) + ", not a solid element");
  const std::vector<Record> recs = records(card);
  if (!recs.empty()) {
    one_record(card, recs);
    const Fields f(card, recs[0]);
    s.thickness = f.real_or(0, 1.0, "thickness");
    require_positive(f, s.thickness, "thickness");
  }
  m_.sections.push_back(s);
}

void DeckBuilder::material(const Card& card) {
  allow_parameters(card, {"NAME"});
  forbid_data(card);
  const std::string name = card.required("NAME");
  const auto it = m_.materials.find(name);
  if (it != m_.materials.end())
    throw DeckError(card.line, "*MATERIAL " + name + " defined twice (first at line " +
                                   std::to_string(it->second.line) + ")");
  m_.materials[name].line = card.line;
  material_ = name;
}

void DeckBuilder::elastic(const Card& card) {
  allow_parameters(card, {"TYPE"});
  if (card.value("TYPE").value_or("ISO") != "ISO")
    throw DeckError(card.line, "*ELASTIC: only TYPE=ISO is supported");
  require_data(card);
  Material& m = current_material(card);
  if (m.youngs_modulus) throw DeckError(card.line, "*ELASTIC given twice for one material");
  const std::vector<Record> recs = records(card);
  one_record(card, recs);
  const Fields f(card, recs[0]);
  const double e = f.real(0, "Young's modulus"), nu = f.real_or(1, 0.0, "Poisson's ratio");
  require_positive(f, e, "Young's modulus");
  if (!(nu > -1.0 && nu < 0.5)) f.fail("Poisson's ratio " + num(nu) + " outside (-1, 0.5)");
  m.youngs_modulus = e;
  m.poisson_ratio = nu;
}

void DeckBuilder::plastic(const Card& card) {
  allow_parameters(card, {});
  require_data(card);
  Material& m = current_material(card);
  if (!m.plastic.empty()) throw DeckError(card.line, "*PLASTIC given twice for one material");
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    const HardeningPoint p{f.real(0, "yield stress"), f.real_or(1, 0.0, "plastic strain")};
    require_positive(f, p.yield_stress, "yield stress");
    if (m.plastic.empty() && p.plastic_strain != 0.0)
      f.fail("the first *PLASTIC point must be at plastic strain 0, got " + num(p.plastic_strain));
    if (!m.plastic.empty() && !(p.plastic_strain > m.plastic.back().plastic_strain))
      f.fail("plastic strains must increase, " + num(p.plastic_strain) + " after " + num(m.plastic.back().plastic_strain));
    m.plastic.push_back(p);
  }
}

void DeckBuilder::density(const Card& card) {
  allow_parameters(card, {});
  require_data(card);
  Material& m = current_material(card);
  const std::vector<Record> recs = records(card);
  one_record(card, recs);
  const Fields f(card, recs[0]);
  const double rho = f.real(0, "density");
  require_positive(f, rho, "density");
  m.density = rho;
}

void DeckBuilder::rigid_surface(const Card& card) {
  allow_parameters(card, {"TYPE", "ELSET"});
  require_data(card);
  const std::string type = card.required("TYPE");
  if (type != "SEGMENTS") throw DeckError(card.line, "*RIGID SURFACE: TYPE=" + type + " is not supported (SEGMENTS)");
  RigidSurface s;
  s.elset = card.required("ELSET");
  s.line = card.line;
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    RigidSegment seg;
    seg.kind = f.word(0, "segment type");
    if (s.segments.empty() != (seg.kind == "START"))
      f.fail(s.segments.empty() ? "the profile must begin with START" : "START may appear only once, first");
    if (seg.kind != "START" && seg.kind != "LINE" && seg.kind != "CIRCL")
      f.fail("segment type " + seg.kind + " unknown (START, LINE, CIRCL)");
    seg.x = f.real(1, "x");
    seg.y = f.real(2, "y");
    if (seg.kind == "CIRCL") {
      seg.xc = f.real(3, "centre x");
      seg.yc = f.real(4, "centre y");
    } else if (r.size() > 3) {
      f.fail(seg.kind + " takes two coordinates");
    }
    s.segments.push_back(seg);
  }
  if (s.segments.size() < 2) throw DeckError(card.line, "*RIGID SURFACE: the profile needs START and at least one segment");
  m_.rigid_surfaces.push_back(s);
}

void DeckBuilder::interface(const Card& card) {
  allow_parameters(card, {"ELSET"});
  Interface i;
  i.elset = card.required("ELSET");
  i.line = card.line;
  for (int e : elset_named(card, i.elset, card.line).labels) {
    const ElementType t = m_.elements.at(e).type;
    if (t != ElementType::Irs22 && t != ElementType::Isl22)
      throw DeckError(card.line, "*INTERFACE: element " + std::to_string(e) + " of set " + i.elset +
                                     " is not an interface element (IRS22, ISL22)");
  }
  const std::vector<Record> recs = records(card);
  if (!recs.empty()) {
    one_record(card, recs);
    const Fields f(card, recs[0]);
    i.thickness = f.real_or(0, 1.0, "thickness");
    require_positive(f, i.thickness, "thickness");
  }
  m_.interfaces.push_back(i);
  interface_ = m_.interfaces.size() - 1;
}

void DeckBuilder::friction(const Card& card) {
  allow_parameters(card, {});
  require_data(card);
  Interface& i = current_interface(card);
  const std::vector<Record> recs = records(card);
  one_record(card, recs);
  const Fields f(card, recs[0]);
  const double mu = f.real(0, "friction coefficient");
  if (mu < 0.0) f.fail("friction coefficient " + num(mu) + " is negative");
  i.friction = mu;
}

void DeckBuilder::surface_contact(const Card& card) {
  allow_parameters(card, {});
  require_data(card);
  Interface& i = current_interface(card);
  const std::vector<Record> recs = records(card);
  one_record(card, recs);
  const Fields f(card, recs[0]);
  i.softened_clearance = f.real(0, "clearance at zero pressure");
  i.softened_pressure = f.real(1, "pressure at zero clearance");
  require_positive(f, *i.softened_clearance, "clearance");
  require_positive(f, *i.softened_pressure, "pressure");
}

void DeckBuilder::slide_line(const Card& card) {
  allow_parameters(card, {"TYPE", "ELSET", "GENERATE", "SMOOTH"});
  require_data(card);
  SlideLine s;
  s.elset = card.required("ELSET");
  s.type = card.value("TYPE").value_or("LINEAR");
  s.line = card.line;
  if (s.type != "LINEAR" && s.type != "PARABOLIC")
    throw DeckError(card.line, "*SLIDE LINE: TYPE=" + s.type + " unknown (LINEAR, PARABOLIC)");
  s.smooth = real_parameter(card, "SMOOTH", 0.2);
  if (!(s.smooth > 0.0 && s.smooth <= 0.5))
    throw DeckError(card.line, "*SLIDE LINE: SMOOTH=" + num(s.smooth) + " outside (0, 0.5]");
  for (int e : elset_named(card, s.elset, card.line).labels)
    if (m_.elements.at(e).type != ElementType::Isl22)
      throw DeckError(card.line, "*SLIDE LINE: element " + std::to_string(e) + " of set " + s.elset + " is not ISL22");
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    if (card.has("GENERATE")) {
      const int a = f.label(0, "first node"), b = f.label(1, "last node");
      const long long inc = f.integer_or(2, 1, "increment");
      if (inc == 0 || (b - a) % inc != 0 || (b - a) / inc < 0)
        f.fail("nodes " + std::to_string(a) + " to " + std::to_string(b) + " are not reached in steps of " +
               std::to_string(inc));
      if ((b - a) / inc + 1 > max_entities) f.fail("too many slide-line nodes");
      spend((b - a) / inc + 1, r.line);
      for (long long n = a;; n += inc) {
        if (!m_.nodes.contains(static_cast<int>(n))) f.fail("node " + std::to_string(n) + " is not defined");
        s.nodes.push_back(static_cast<int>(n));
        if (n == b) break;
      }
      continue;
    }
    for (std::size_t k = 0; k < r.size(); ++k) {
      if (r.fields[k].empty()) continue;
      const int n = f.label(k, "slide-line node");
      if (!m_.nodes.contains(n)) f.fail("node " + std::to_string(n) + " is not defined");
      s.nodes.push_back(n);
    }
  }
  if (s.nodes.size() < 2) throw DeckError(card.line, "*SLIDE LINE needs at least two nodes");
  m_.slide_lines.push_back(std::move(s));
}

void DeckBuilder::mpc(const Card& card) {
  allow_parameters(card, {});
  require_data(card);
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    Mpc c;
    c.type = f.word(0, "MPC type");
    c.line = r.line;
    // A number is a user MPC type of ABAQUS 4.8 (the thesis's "5" ties coincident nodes,
    // see data/thesis/README.md); named types are the built-in ones.
    if (!is_integer_text(c.type) && c.type != "TIE" && c.type != "PIN" && c.type != "BEAM" && c.type != "LINK")
      f.fail("MPC type " + c.type + " unknown (a number, TIE, PIN, BEAM, LINK)");
    for (std::size_t k = 1; k < r.size(); ++k) {
      const int n = f.label(k, "MPC node");
      if (!m_.nodes.contains(n)) f.fail("node " + std::to_string(n) + " is not defined");
      c.nodes.push_back(n);
    }
    if (c.nodes.size() < 2) f.fail("an MPC needs at least two nodes");
    m_.mpcs.push_back(std::move(c));
  }
}

void DeckBuilder::boundary(const Card& card) {
  allow_parameters(card, {});
  require_data(card);
  std::vector<Constraint>& out = in_step_ ? open_step(card).boundaries : m_.boundaries;
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    const std::vector<int> nodes = nodes_of(f, 0, "node");
    const std::string what = f.word(1, "degree of freedom or boundary type");
    std::vector<std::pair<int, int>> ranges;
    std::string written;
    double value = 0.0;
    if (is_integer_text(what)) {
      const long long first = f.integer(1, "first dof"), last = f.integer_or(2, first, "last dof");
      if (first < 1 || first > 6 || last < first || last > 6)
        f.fail("dofs " + std::to_string(first) + ".." + std::to_string(last) + " outside 1..6");
      ranges.emplace_back(static_cast<int>(first), static_cast<int>(last));
      value = f.real_or(3, 0.0, "magnitude");
    } else {
      for (const auto& b : symbolic_boundaries())
        if (what == b.name) ranges = b.dofs;
      if (ranges.empty())
        f.fail("unknown boundary type '" + what +
               "' (a dof number or XSYMM, YSYMM, ZSYMM, XASYMM, YASYMM, ZASYMM, ENCASTRE, PINNED)");
      if (r.size() > 2) f.fail("a symbolic boundary type takes no further fields");
      written = what;
    }
    spend(static_cast<long long>(nodes.size() * ranges.size()), r.line);
    for (int n : nodes)
      for (const auto& [a, b] : ranges) out.push_back(Constraint{n, a, b, value, written, r.line});
  }
}

void DeckBuilder::initial_conditions(const Card& card) {
  allow_parameters(card, {"TYPE"});
  require_data(card);
  const std::string type = card.required("TYPE");
  if (type != "VELOCITY")
    throw DeckError(card.line, "*INITIAL CONDITIONS: TYPE=" + type + " is not supported (VELOCITY)");
  for (const Record& r : records(card)) {
    const Fields f(card, r);
    const std::vector<int> nodes = nodes_of(f, 0, "node");
    const long long dof = f.integer(1, "dof");
    if (dof < 1 || dof > 6) f.fail("dof " + std::to_string(dof) + " outside 1..6");
    const double v = f.real(2, "velocity");
    spend(static_cast<long long>(nodes.size()), r.line);
    for (int n : nodes) m_.initial_velocities.push_back(InitialVelocity{n, static_cast<int>(dof), v, r.line});
  }
}

void DeckBuilder::mass(const Card& card) {
  allow_parameters(card, {"ELSET"});
  require_data(card);
  PointMass p;
  p.elset = card.required("ELSET");
  p.line = card.line;
  for (int e : elset_named(card, p.elset, card.line).labels)
    if (m_.elements.at(e).type != ElementType::Mass)
      throw DeckError(card.line, "*MASS: element " + std::to_string(e) + " of set " + p.elset + " is not a MASS element");
  const std::vector<Record> recs = records(card);
  one_record(card, recs);
  const Fields f(card, recs[0]);
  p.mass = f.real(0, "mass");
  require_positive(f, p.mass, "mass");
  m_.masses.push_back(p);
}

}  // namespace ringcrush::fe::deck
