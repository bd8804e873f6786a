#include "fe/deck/deck_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <numeric>
#include <set>
#include <stdexcept>

namespace ringcrush::fe::deck {

namespace {

[[noreturn]] void fail(const std::string& reason) {
  throw std::invalid_argument("deck does not describe a ringcrush ring chain: " + reason);
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

struct Xy {
  double x, y;
};
Xy xy(const Point& p) { return {p[0], p[1]}; }
double cross(Xy a, Xy b) { return a.x * b.y - a.y * b.x; }
Xy minus(Xy a, Xy b) { return {a.x - b.x, a.y - b.y}; }
double length(Xy a) { return std::hypot(a.x, a.y); }

// Union-find over element indices: elements sharing a node belong to one mesh part.
struct Parts {
  std::vector<std::size_t> parent;
  explicit Parts(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::size_t root(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) { parent[root(a)] = root(b); }
};

// A CPS8 element of a ring has two straight (radial) opposite edges — their mid-side nodes
// lie on the chord — and two curved ones. The radial edges' lines meet at the ring centre.
// Returns false when the element has no such pair (not a ring element).
bool element_centre(const DeckModel& m, const Element& e, Xy& centre, Xy& radial_a, Xy& radial_b) {
  Xy p[8];
  for (int k = 0; k < 8; ++k) p[k] = xy(m.nodes.at(e.nodes[static_cast<std::size_t>(k)]).x);
  auto straight = [&](int a, int mid, int b) {
    const Xy ab = minus(p[b], p[a]);
    const double l2 = ab.x * ab.x + ab.y * ab.y;
    return l2 > 0 && std::abs(cross(ab, minus(p[mid], p[a]))) <= 1e-6 * l2;
  };
  int a0, a1, b0, b1;  // radial lines a0→a1 and b0→b1
  if (straight(1, 5, 2) && straight(3, 7, 0)) {
    a0 = 1, a1 = 2, b0 = 0, b1 = 3;
  } else if (straight(0, 4, 1) && straight(2, 6, 3)) {
    a0 = 0, a1 = 1, b0 = 3, b1 = 2;
  } else {
    return false;
  }
  const Xy d = minus(p[a1], p[a0]), f = minus(p[b1], p[b0]);
  const double det = cross(d, f);
  if (std::abs(det) <= 1e-12 * length(d) * length(f)) return false;  // parallel: no centre
  const double s = cross(minus(p[b0], p[a0]), f) / det;
  centre = {p[a0].x + s * d.x, p[a0].y + s * d.y};
  if (!std::isfinite(centre.x) || !std::isfinite(centre.y)) return false;  // coordinates overflow
  radial_a = d;
  radial_b = f;
  return true;
}

double angle_between(Xy a, Xy b) { return std::abs(std::atan2(cross(a, b), a.x * b.x + a.y * b.y)); }

bool close(double a, double b, double rel) { return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)); }

struct RingAnalysis {
  std::vector<DeckRing> rings;
  std::map<int, std::size_t> ring_of_node;
  std::vector<double> spans;  // ring 1 element angles
};

RingAnalysis find_rings(const DeckModel& m) {
  std::vector<int> labels;
  for (const auto& [label, e] : m.elements)
    if (e.type == ElementType::Cps8) labels.push_back(label);
  if (labels.empty()) fail("no CPS8 elements");
  Parts parts(labels.size());
  std::map<int, std::size_t> first_user;
  for (std::size_t i = 0; i < labels.size(); ++i)
    for (int n : m.elements.at(labels[i]).nodes) {
      const auto [it, fresh] = first_user.emplace(n, i);
      if (!fresh) parts.join(i, it->second);
    }
  // Centre of each mesh part: the mean of its elements' radial-line intersections.
  struct Part {
    Xy sum{0, 0};
    int count = 0;
    std::vector<int> elements;
  };
  std::map<std::size_t, Part> by_root;
  std::map<int, double> span_of;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    Part& p = by_root[parts.root(i)];
    p.elements.push_back(labels[i]);
    Xy c{}, ra{}, rb{};
    if (element_centre(m, m.elements.at(labels[i]), c, ra, rb)) {
      p.sum.x += c.x, p.sum.y += c.y, ++p.count;
      span_of[labels[i]] = angle_between(ra, rb);
    }
  }
  // Parts around one centre form one ring (the static deck's two quarters are separate
  // parts, tied by *MPC).
  RingAnalysis out;
  for (auto& [root, part] : by_root) {
    if (part.count == 0) fail("CPS8 elements around element " + std::to_string(part.elements.front()) +
                              " have no radial edges: not a ring");
    const Xy c{part.sum.x / part.count, part.sum.y / part.count};
    double r_max = 0;
    for (int e : part.elements)
      for (int n : m.elements.at(e).nodes) r_max = std::max(r_max, length(minus(xy(m.nodes.at(n).x), c)));
    DeckRing* ring = nullptr;
    for (DeckRing& r : out.rings)
      if (length(minus(xy(r.centre), c)) <= 1e-6 * r_max) ring = &r;
    if (ring == nullptr) {
      out.rings.push_back(DeckRing{{c.x, c.y, 0.0}, 0, 0, {}, {}});
      ring = &out.rings.back();
    }
    ring->elements.insert(ring->elements.end(), part.elements.begin(), part.elements.end());
  }
  std::sort(out.rings.begin(), out.rings.end(),
            [](const DeckRing& a, const DeckRing& b) { return a.centre[1] > b.centre[1]; });
  for (std::size_t k = 0; k < out.rings.size(); ++k) {
    DeckRing& r = out.rings[k];
    std::sort(r.elements.begin(), r.elements.end());
    std::set<int> nodes;
    for (int e : r.elements) nodes.insert(m.elements.at(e).nodes.begin(), m.elements.at(e).nodes.end());
    r.nodes.assign(nodes.begin(), nodes.end());
    r.inner_radius = 1e300;
    for (int n : r.nodes) {
      const double rad = length(minus(xy(m.nodes.at(n).x), xy(r.centre)));
      r.inner_radius = std::min(r.inner_radius, rad);
      r.outer_radius = std::max(r.outer_radius, rad);
      out.ring_of_node[n] = k;
    }
    if (!(r.inner_radius > 0.0 && r.outer_radius > r.inner_radius && std::isfinite(r.outer_radius)))
      fail("ring " + std::to_string(k + 1) + " has no wall (inner radius " + num(r.inner_radius) + ")");
  }
  for (int e : out.rings.front().elements)
    if (span_of.contains(e)) out.spans.push_back(span_of.at(e));
  return out;
}

// Corner-node radii of one ring, clustered: n distinct radii = n − 1 elements through.
int layers_through(const DeckModel& m, const DeckRing& r) {
  std::vector<double> radii;
  for (int e : r.elements)
    for (std::size_t k = 0; k < 4; ++k)
      radii.push_back(length(minus(xy(m.nodes.at(m.elements.at(e).nodes[k]).x), xy(r.centre))));
  std::sort(radii.begin(), radii.end());
  int distinct = 1;
  for (std::size_t i = 1; i < radii.size(); ++i)
    if (radii[i] - radii[i - 1] > 1e-6 * r.outer_radius) ++distinct;
  return distinct - 1;
}

const SolidSection& ring_section(const DeckModel& m, const RingAnalysis& rings) {
  const SolidSection* found = nullptr;
  for (const DeckRing& r : rings.rings)
    for (int e : r.elements) {
      const SolidSection* s = nullptr;
      for (const SolidSection& sec : m.sections)
        if (m.elsets.at(sec.elset).members.contains(e)) s = &sec;
      if (s == nullptr) fail("CPS8 element " + std::to_string(e) + " has no *SOLID SECTION");
      if (found != nullptr && (s->material != found->material || s->thickness != found->thickness))
        fail("rings with different sections (" + found->material + " and " + s->material + ")");
      found = s;
    }
  return *found;
}

int reference_node(const DeckModel& m, const RigidSurface& s) {
  std::set<int> refs;
  for (int e : m.elsets.at(s.elset).labels) refs.insert(m.elements.at(e).nodes.back());
  if (refs.size() != 1) fail("rigid surface " + s.elset + " has " + std::to_string(refs.size()) + " reference nodes");
  return *refs.begin();
}

}  // namespace

DeckParameters deck_parameters(const DeckModel& m) {
  DeckParameters p;
  p.heading = m.heading;
  RingAnalysis a = find_rings(m);
  p.rings = a.rings;
  const DeckRing& first = p.rings.front();
  p.inner_radius_m = first.inner_radius;
  p.outer_radius_m = first.outer_radius;

  // Every ring the same, on one vertical line, evenly spaced.
  p.elements_through = layers_through(m, first);
  if (p.elements_through < 1) fail("the corner nodes of ring 1 all lie at one radius: no wall");
  for (std::size_t k = 0; k < p.rings.size(); ++k) {
    const DeckRing& r = p.rings[k];
    const std::string which = "ring " + std::to_string(k + 1);
    if (!close(r.inner_radius, p.inner_radius_m, 1e-6) || !close(r.outer_radius, p.outer_radius_m, 1e-6))
      fail(which + " radii " + num(r.inner_radius) + ", " + num(r.outer_radius) + " differ from ring 1's");
    if (r.elements.size() != first.elements.size())
      fail(which + " has " + std::to_string(r.elements.size()) + " elements, ring 1 " +
           std::to_string(first.elements.size()));
    if (std::abs(r.centre[0] - first.centre[0]) > 1e-6 * p.outer_radius_m)
      fail(which + " centre is not below ring 1's (chains run along y)");
  }
  if (first.elements.size() % static_cast<std::size_t>(p.elements_through) != 0)
    fail("ring elements do not form whole layers through the wall");
  p.elements_around = static_cast<int>(first.elements.size()) / p.elements_through;
  const auto [smallest, largest] = std::minmax_element(a.spans.begin(), a.spans.end());
  if (a.spans.empty() || !(*smallest > 0.0)) fail("cannot measure the element angles of ring 1");
  p.grading = *largest / *smallest;
  {
    // Corner nodes on the outer circle of ring 1, as angles from the bottom point.
    std::vector<double> phi;
    for (int e : first.elements)
      for (std::size_t k = 0; k < 4; ++k) {
        const Xy r = minus(xy(m.nodes.at(m.elements.at(e).nodes[k]).x), xy(first.centre));
        if (length(r) < first.outer_radius * (1.0 - 1e-6)) continue;
        double angle = std::atan2(r.y, r.x) + std::numbers::pi / 2;  // 0 at −y
        if (angle < 0) angle += 2 * std::numbers::pi;
        phi.push_back(angle);
      }
    std::sort(phi.begin(), phi.end());
    for (double angle : phi)
      if (p.boundary_angles.empty() || angle - p.boundary_angles.back() > 1e-9) p.boundary_angles.push_back(angle);
  }
  p.pitch_m = 2.0 * p.outer_radius_m;
  if (p.rings.size() > 1) {
    p.pitch_m = p.rings[0].centre[1] - p.rings[1].centre[1];
    for (std::size_t k = 1; k < p.rings.size(); ++k)
      if (!close(p.rings[k - 1].centre[1] - p.rings[k].centre[1], p.pitch_m, 1e-6))
        fail("rings are not evenly spaced (ring " + std::to_string(k + 1) + ")");
  }
  p.half_model = true;
  for (const DeckRing& r : p.rings)
    for (int n : r.nodes)
      if (m.nodes.at(n).x[0] < r.centre[0] - 1e-9 * p.outer_radius_m) p.half_model = false;

  // Ties: the thesis's *MPC join coincident nodes — the quarters of the static ring, the
  // touching points of neighbouring rings in the welded chain.
  for (const Mpc& c : m.mpcs) {
    if (c.nodes.size() != 2) fail("*MPC at line " + std::to_string(c.line) + " does not tie two nodes");
    const auto ra = a.ring_of_node.find(c.nodes[0]), rb = a.ring_of_node.find(c.nodes[1]);
    if (ra == a.ring_of_node.end() || rb == a.ring_of_node.end())
      fail("*MPC at line " + std::to_string(c.line) + " ties a node outside the rings");
    const Point& x0 = m.nodes.at(c.nodes[0]).x;
    const Point& x1 = m.nodes.at(c.nodes[1]).x;
    if (std::hypot(x0[0] - x1[0], x0[1] - x1[1]) > 1e-9 * p.outer_radius_m)
      fail("*MPC at line " + std::to_string(c.line) + " ties nodes that are not coincident");
    if (ra->second == rb->second) {
      ++p.internal_ties;
    } else if (ra->second + 1 == rb->second || rb->second + 1 == ra->second) {
      ++p.ring_ties;
    } else {
      fail("*MPC at line " + std::to_string(c.line) + " ties rings that are not neighbours");
    }
  }
  p.welded = p.ring_ties > 0;
  if (p.welded && p.ring_ties != static_cast<int>(p.rings.size()) - 1)
    fail(std::to_string(p.ring_ties) + " ring-to-ring ties for " + std::to_string(p.rings.size()) + " rings");

  // Section and material.
  const SolidSection& section = ring_section(m, a);
  p.width_m = section.thickness;
  const Material& mat = m.materials.at(section.material);
  p.youngs_modulus_pa = *mat.youngs_modulus;
  p.poisson_ratio = mat.poisson_ratio.value_or(0.0);
  p.density_kg_m3 = mat.density;
  p.hardening = mat.plastic;

  // Contact.
  p.slide_lines = static_cast<int>(m.slide_lines.size());
  for (const SlideLine& s : m.slide_lines) {
    if (p.contact_smoothing && *p.contact_smoothing != s.smooth)
      fail("slide lines with different SMOOTH (" + num(*p.contact_smoothing) + ", " + num(s.smooth) + ")");
    p.contact_smoothing = s.smooth;
  }
  std::optional<double> mu;
  for (const Interface& i : m.interfaces) {
    const double f = i.friction.value_or(0.0);
    if (mu && *mu != f) fail("interfaces with different friction coefficients");
    mu = f;
    if (i.softened_clearance) {
      if (p.softened_clearance_m && (*p.softened_clearance_m != *i.softened_clearance ||
                                     *p.softened_pressure_pa != *i.softened_pressure))
        fail("interfaces with different *SURFACE CONTACT");
      p.softened_clearance_m = i.softened_clearance;
      p.softened_pressure_pa = i.softened_pressure;
    }
  }
  p.friction_coefficient = mu.value_or(0.0);

  // The one step.
  if (m.steps.size() != 1) fail("ringcrush runs one step, the deck has " + std::to_string(m.steps.size()));
  const Step& step = m.steps.front();
  p.dynamic = step.procedure == Procedure::Dynamic;
  p.ptol_n = step.ptol;
  p.haftol_n = step.haftol;
  p.hht_alpha = step.alpha;
  p.period = step.period.value_or(1.0);
  p.max_iterations = step.max_iterations;
  p.max_increments = step.max_increments;
  // Static increments are fractions of the step (the thesis's period is 1.0); dynamic ones
  // are seconds.
  const double unit = p.dynamic ? 1.0 : p.period;
  p.initial_increment = step.initial_increment.value_or(0.0) / unit;
  if (step.min_increment) p.min_increment = *step.min_increment / unit;
  if (step.max_increment) p.max_increment = *step.max_increment / unit;

  // Rigid surfaces: impactor, target, driven plate.
  p.rigid_surfaces = static_cast<int>(m.rigid_surfaces.size());
  const double top = first.centre[1] + p.outer_radius_m;
  const double bottom = p.rings.back().centre[1] - p.outer_radius_m;
  for (const RigidSurface& s : m.rigid_surfaces) {
    const int ref = reference_node(m, s);
    double y_sum = 0;
    for (const RigidSegment& seg : s.segments) y_sum += seg.y;
    const double y = y_sum / static_cast<double>(s.segments.size());
    const bool above = y >= top - 1e-6 * p.outer_radius_m;
    const bool below = y <= bottom + 1e-6 * p.outer_radius_m;
    if (!above && !below) fail("rigid surface " + s.elset + " is neither above ring 1 nor below the last ring");
    bool encastre = false;
    for (const Constraint& c : m.boundaries)
      if (c.node == ref && c.first_dof <= 2 && c.last_dof >= 2) encastre = encastre || (c.first_dof == 1 && c.last_dof == 6);
    double mass = 0;
    for (const PointMass& pm : m.masses)
      for (int e : m.elsets.at(pm.elset).labels)
        if (m.elements.at(e).nodes.front() == ref) mass += pm.mass;
    std::optional<double> vy;
    for (const InitialVelocity& v : m.initial_velocities)
      if (v.node == ref) {
        if (v.dof != 2 && v.value != 0.0) fail("rigid surface " + s.elset + " has a velocity across the chain axis");
        if (v.dof == 2) vy = v.value;
      }
    std::optional<double> drive;
    for (const Constraint& c : step.boundaries)
      if (c.node == ref && c.first_dof <= 2 && c.last_dof >= 2 && c.value != 0.0) drive = c.value;
    if (below) {
      if (!encastre) fail("rigid surface " + s.elset + " under the chain is not ENCASTRE (a fixed target)");
      p.fixed_target = true;
    } else if (p.dynamic) {
      if (!(mass > 0.0) || !vy) fail("rigid surface " + s.elset + " above ring 1 needs a MASS and a velocity");
      if (!(*vy < 0.0)) fail("impactor " + s.elset + " velocity " + num(*vy) + " does not point toward the chain (-y)");
      p.impactor_mass_kg = mass * (p.half_model ? 2.0 : 1.0);  // the deck carries half of it
      p.impactor_velocity_m_s = -*vy;
    } else {
      if (!drive || !(*drive < 0.0)) fail("static plate " + s.elset + " is not driven toward the chain in the step");
      p.crush_m = -*drive;
    }
  }
  if (p.dynamic && !p.impactor_mass_kg) fail("dynamic step without an impactor (rigid surface with MASS)");
  if (!p.dynamic && !(p.crush_m > 0.0)) fail("static step without a driven plate");
  return p;
}

}  // namespace ringcrush::fe::deck
