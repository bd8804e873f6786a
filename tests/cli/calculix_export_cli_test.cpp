// `ringcrush export-calculix` (issue 5 item 3): the deck carries ringcrush's own mesh, material,
// contact and step exactly (checked without ccx), bad scenes exit 2 naming the feature, and —
// when CalculiX is installed — ccx run on the exported thesis static scene (coarse mesh) gives
// the load of ringcrush's own FE within 10 % at δ/d = 0.1 and 0.3.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "ccx_testing.hpp"
#include "command_run.hpp"
#include "compare/calculix_export.hpp"
#include "compare/fe_static.hpp"
#include "compare/scene.hpp"
#include "fe/mesh/ring_mesh.hpp"
#include "test_files.hpp"

namespace fs = std::filesystem;

namespace {

// The ringcrush executable (the helper's name would clash with namespace ringcrush here).
cli_testing::CommandRun run_cli(const std::string& args) { return cli_testing::ringcrush(args); }

fs::path scratch(const std::string& name) { return test_files::scratch_dir("ringcrush_calculix_test_", name); }

using test_files::read_text;

// The thesis static scene (22 CPS8 per half ring, the thesis's own coarse mesh) crushed to
// δ/d = 0.32, no fields or plots; `more` replaces further text (regex → value).
fs::path coarse_scene(const fs::path& dir, const test_files::Edits& more = {}) {
  test_files::Edits edits{{"crush_m = 0\\.046", "crush_m = 0.01575"},
                          {"fields = true", "fields = false"},
                          {"plots = true", "plots = false"},
                          {"initial_increment = 0\\.001", "initial_increment = 0.01"}};
  edits.insert(edits.end(), more.begin(), more.end());
  return test_files::edited_scene("data/scenes/thesis_static.toml", dir / "thesis_coarse.toml", edits);
}

using ccx_testing::deck_blocks;

using test_files::numbers;

// Linear interpolation of y(x) on an increasing x table.
double at(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i] >= xq) return y[i - 1] + (y[i] - y[i - 1]) * (xq - x[i - 1]) / (x[i] - x[i - 1]);
  return std::nan("");
}

}  // namespace

TEST(CalculixExport, DeckCarriesTheMeshMaterialContactAndStep) {
  using namespace ringcrush;
  const fs::path dir = scratch("content");
  const compare::Scene s = compare::load_scene(coarse_scene(dir));
  const compare::CalculixDeck deck = compare::calculix_deck(s);
  const fe::FeInput in = compare::fe_static_input(s);
  const fe::RingMesh mesh = fe::make_ring_mesh(in.ring, in.mesh);
  const auto blocks = deck_blocks(deck.deck);

  for (const char* k : {"*HEADING", "*NODE, NSET=NALL", "*MATERIAL, NAME=RING_MATERIAL", "*ELASTIC", "*PLASTIC",
                        "*SOLID SECTION, ELSET=RING, MATERIAL=RING_MATERIAL",
                        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
                        "*CONTACT PAIR, INTERACTION=RING_PLATE, TYPE=SURFACE TO SURFACE", "*STATIC", "*END STEP",
                        "*NODE PRINT, NSET=PLATE_TOP_NODES, TOTALS=ONLY"})
    EXPECT_EQ(blocks.count(k), k == std::string("*CONTACT PAIR, INTERACTION=RING_PLATE, TYPE=SURFACE TO SURFACE") ? 3u
                               : k == std::string("*ELASTIC")                                                ? 2u
                                                                                                             : 1u)
        << k;
  EXPECT_NE(deck.deck.find("*STEP, NLGEOM"), std::string::npos);

  // Nodes: the ring mesh first, with its coordinates.
  const auto& node_lines = blocks.find("*NODE, NSET=NALL")->second;
  ASSERT_EQ(static_cast<int>(node_lines.size()), deck.nodes);
  ASSERT_EQ(deck.ring_nodes, static_cast<int>(mesh.nodes.size()));
  std::vector<std::array<double, 2>> xy(node_lines.size() + 1);
  for (std::size_t i = 0; i < node_lines.size(); ++i) {
    const auto v = numbers(node_lines[i]);
    ASSERT_EQ(v.size(), 3u);
    ASSERT_EQ(static_cast<std::size_t>(v[0]), i + 1);
    xy[i + 1] = {v[1], v[2]};
    if (i < mesh.nodes.size()) {
      // ccx reads 20 characters a field: the shortest exact decimal, or 15–16 digits.
      EXPECT_NEAR(v[1], mesh.nodes[i].x(), 1e-15 * in.ring.outer_radius_m) << "node " << i + 1;
      EXPECT_NEAR(v[2], mesh.nodes[i].y(), 1e-15 * in.ring.outer_radius_m) << "node " << i + 1;
    }
  }
  // Elements: the ring's connectivity, and every element (ring and plates) counter-clockwise
  // with its corner-quad area positive (ccx rejects inverted elements).
  const auto& ring_lines = blocks.find("*ELEMENT, TYPE=CPS8, ELSET=RING")->second;
  ASSERT_EQ(ring_lines.size(), mesh.elements.size());
  int element_count = 0;
  for (const auto& [key, lines] : blocks) {
    if (key.rfind("*ELEMENT", 0) != 0) continue;
    for (const auto& line : lines) {
      const auto v = numbers(line);
      ASSERT_EQ(v.size(), 9u) << line;
      ++element_count;
      double area2 = 0;
      for (int a = 0; a < 4; ++a) {
        const auto& p = xy.at(static_cast<std::size_t>(v[1 + a]));
        const auto& q = xy.at(static_cast<std::size_t>(v[1 + (a + 1) % 4]));
        area2 += p[0] * q[1] - q[0] * p[1];
      }
      EXPECT_GT(area2, 0) << key << ": " << line;
    }
  }
  EXPECT_EQ(element_count, deck.elements);
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const auto v = numbers(ring_lines[e]);
    for (int a = 0; a < 8; ++a) EXPECT_EQ(static_cast<int>(v[1 + a]), mesh.elements[e][a] + 1);
  }
  // Inner wall (lock-up): faces near the bottom and near the top, the same count by symmetry.
  const auto& inner_bottom = blocks.find("*SURFACE, NAME=RING_INNER_BOTTOM, TYPE=ELEMENT")->second;
  EXPECT_GT(inner_bottom.size(), 0u);
  EXPECT_EQ(inner_bottom.size(), blocks.find("*SURFACE, NAME=RING_INNER_TOP, TYPE=ELEMENT")->second.size());
  // Outer surface: one face per element around the ring.
  EXPECT_EQ(blocks.find("*SURFACE, NAME=RING_OUTER, TYPE=ELEMENT")->second.size(),
            static_cast<std::size_t>(2 * in.mesh.elements_around / (in.mesh.half_ring ? 2 : 1)));

  // Material and section: exact values of the scene.
  const auto& mat = s.rings.material;
  const auto elastic = numbers(blocks.find("*ELASTIC")->second.at(0));
  EXPECT_EQ(elastic.at(0), mat.youngs_modulus_pa);
  EXPECT_EQ(elastic.at(1), mat.poisson_ratio);
  const auto& plastic = blocks.find("*PLASTIC")->second;
  ASSERT_EQ(plastic.size(), mat.hardening.size());
  for (std::size_t i = 0; i < plastic.size(); ++i) {
    EXPECT_EQ(numbers(plastic[i]).at(0), mat.hardening[i].yield_stress_pa);
    EXPECT_EQ(numbers(plastic[i]).at(1), mat.hardening[i].plastic_strain);
  }
  // Plane stress as a thin slab (t/10); the load factor carries the width and the symmetry.
  const double slab = numbers(blocks.find("*SOLID SECTION, ELSET=RING, MATERIAL=RING_MATERIAL")->second.at(0)).at(0);
  EXPECT_NEAR(slab, 0.1 * s.rings.wall_thickness_m, 1e-15);
  EXPECT_NEAR(deck.load_factor, 2.0 * s.rings.width_m / slab, 1e-12 * deck.load_factor);
  const auto wide = compare::calculix_deck(s, compare::CalculixSection::FullWidth);
  EXPECT_NE(wide.deck.find("MATERIAL=RING_MATERIAL\n0.0125\n"), std::string::npos);
  EXPECT_EQ(wide.load_factor, 2.0);
  // Penalty per unit area = scale · E / h (ringcrush's per-node stiffness over its area).
  const double slope = numbers(blocks.find("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR")->second.at(0)).at(0);
  EXPECT_NEAR(slope, s.fe.contact_penalty_scale * mat.youngs_modulus_pa / mesh.element_depth, 1e-9 * slope);
  // Step: the scene's increments and the crush on the driven plate.
  const auto stat = numbers(blocks.find("*STATIC")->second.at(0));
  EXPECT_EQ(stat.at(0), s.fe.initial_increment);
  EXPECT_EQ(stat.at(1), 1.0);
  EXPECT_EQ(stat.at(2), s.fe.min_increment);
  EXPECT_EQ(stat.at(3), s.fe.max_increment);
  EXPECT_NE(deck.deck.find("PLATE_TOP_NODES, 2, 2, -0.01575\n"), std::string::npos);
  // Half model: the x = 0 symmetry nodes (both loading-axis columns of the ring) are held in x.
  const auto& fixed = blocks.find("*NSET, NSET=RING_FIXED_X")->second;
  std::size_t fixed_count = 0;
  for (const auto& l : fixed) fixed_count += numbers(l).size();
  EXPECT_EQ(fixed_count, mesh.fixed_x.size());
  EXPECT_EQ(deck.symmetry_factor, 2.0);
  EXPECT_NE(deck.readme.find("selective"), std::string::npos);  // the approximation is listed
}

// A full ring: no symmetry factor, plates on both sides of the axis, two x restraints.
TEST(CalculixExport, FullRingDeck) {
  using namespace ringcrush;
  const fs::path dir = scratch("full");
  const compare::Scene s = compare::load_scene(coarse_scene(dir, {{"symmetry = \"half\"", "symmetry = \"full\""}}));
  const compare::CalculixDeck deck = compare::calculix_deck(s);
  EXPECT_EQ(deck.symmetry_factor, 1.0);
  EXPECT_NEAR(deck.load_factor, s.rings.width_m / deck.section_thickness_m, 1e-12 * deck.load_factor);
  EXPECT_EQ(deck.ring_elements, 2 * s.fe.elements_around);
  const auto blocks = deck_blocks(deck.deck);
  EXPECT_EQ(numbers(blocks.find("*NSET, NSET=RING_FIXED_X")->second.at(0)).size(), 2u);
  double x_min = 0;
  for (const auto& line : blocks.find("*NODE, NSET=NALL")->second) x_min = std::min(x_min, numbers(line).at(1));
  EXPECT_NEAR(x_min, -s.rings.outer_diameter_m, 1e-12);  // plates reach one diameter to each side
}

// --rigid-plates: the deck in 20-node bricks (ccx 2.20 reads no reaction at a rigid body of
// CPS8), each plate a *RIGID BODY whose reference node is held / driven and carries the load.
TEST(CalculixExport, RigidBodyPlatesDeck) {
  using namespace ringcrush;
  const fs::path dir = scratch("rigid");
  const compare::Scene s = compare::load_scene(coarse_scene(dir));
  const auto strips = compare::calculix_deck(s);
  const auto deck =
      compare::calculix_deck(s, compare::CalculixSection::PlaneStressSlab, compare::CalculixPlates::RigidBodies);
  const auto blocks = deck_blocks(deck.deck);
  EXPECT_EQ(deck.elements, strips.elements);  // one brick per CPS8
  EXPECT_EQ(deck.ring_element_type, "C3D20");
  EXPECT_EQ(blocks.find("*ELEMENT, TYPE=C3D20, ELSET=RING")->second.size(), 2u * static_cast<std::size_t>(deck.ring_elements));
  EXPECT_EQ(static_cast<int>(blocks.find("*NODE, NSET=NALL")->second.size()), deck.nodes);
  EXPECT_EQ(deck.reaction_set, "PLATE_TOP_REF");
  EXPECT_EQ(deck.load_factor, strips.load_factor);
  const std::string top_ref = std::to_string(deck.driven_reference_node);
  EXPECT_NE(deck.deck.find("*RIGID BODY, NSET=PLATE_TOP_NODES, REF NODE=" + top_ref), std::string::npos);
  EXPECT_NE(deck.deck.find("*RIGID BODY, NSET=PLATE_BOTTOM_NODES, REF NODE="), std::string::npos);
  EXPECT_NE(deck.deck.find("*BOUNDARY\n" + top_ref + ", 2, 2, -0.01575\n"), std::string::npos);
  EXPECT_NE(deck.deck.find("*NODE PRINT, NSET=PLATE_TOP_REF, TOTALS=ONLY\nRF\n"), std::string::npos);
  EXPECT_NE(deck.deck.find("RING_FRONT, 3, 3"), std::string::npos);
  // the brick faces of the CPS8 faces: outer S1 → S3, inner S3 → S5
  EXPECT_EQ(blocks.find("*SURFACE, NAME=RING_OUTER, TYPE=ELEMENT")->second.at(0), "1, S3");
  EXPECT_EQ(blocks.find("*SURFACE, NAME=RING_INNER_TOP, TYPE=ELEMENT")->second.at(0).substr(
                blocks.find("*SURFACE, NAME=RING_INNER_TOP, TYPE=ELEMENT")->second.at(0).find(',')),
            ", S5");
  // the ring's symmetry nodes through the slab: 2 or 3 brick nodes per 2-D node
  std::size_t fixed = 0;
  for (const auto& l : blocks.find("*NSET, NSET=RING_FIXED_X")->second) fixed += numbers(l).size();
  std::size_t fixed_2d = 0;
  const auto strip_blocks = deck_blocks(strips.deck);
  for (const auto& l : strip_blocks.find("*NSET, NSET=RING_FIXED_X")->second) fixed_2d += numbers(l).size();
  EXPECT_GT(fixed, 2 * fixed_2d);
  EXPECT_LT(fixed, 3 * fixed_2d + 1);
}

TEST(CalculixExport, CommandWritesTheDeckAndReadme) {
  const fs::path dir = scratch("cli");
  const auto r = run_cli("export-calculix " + coarse_scene(dir).string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "thesis_coarse.inp"));
  EXPECT_TRUE(fs::exists(dir / "out" / "README.txt"));
  EXPECT_NE(r.output.find("nodes"), std::string::npos) << r.output;
}

TEST(CalculixExport, BadInputExitsTwoNamingTheProblem) {
  const fs::path dir = scratch("bad");
  auto r = run_cli("export-calculix " + (dir / "missing.toml").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("missing.toml"), std::string::npos) << r.output;

  // (Dynamic scenes are exported: tests/cli/calculix_dynamic_export_test.cpp.)

  // A static chain: the static FE (and so the deck) crushes one ring.
  const fs::path chain =
      coarse_scene(dir, {{"count = 1", "count = 2"}, {"\\[far_end\\]", "[joints]\ntype = \"welded\"\n\n[far_end]"}});
  r = run_cli("export-calculix " + chain.string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("one ring"), std::string::npos) << r.output;

  r = run_cli("export-calculix " + coarse_scene(dir, {{"plane_stress", "plane_strain"}}).string() + " -o " +
                (dir / "out").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("plane_stress"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out")) << "a refused export leaves no directory";
}

TEST(CalculixExport, ParsesCcxTotalForces) {
  const std::string dat =
      "\n forces (fx,fy,fz) for set PLATE_TOP_NODES and time  0.1000000E+00\n\n"
      " total force (fx,fy,fz) for set PLATE_TOP_NODES and time  0.1000000E+00\n\n"
      "        1.000000E-03  2.500000E+02  0.000000E+00\n"
      " total force (fx,fy,fz) for set OTHER and time  0.1000000E+00\n\n        1 2 3\n"
      " total force (fx,fy,fz) for set PLATE_TOP_NODES and time  0.2000000E+00\n\n"
      "        0.000000E+00  3.000000E+02  0.000000E+00\n";
  const auto f = ringcrush::compare::parse_ccx_total_forces(dat, "plate_top_nodes");
  ASSERT_EQ(f.size(), 2u);
  EXPECT_DOUBLE_EQ(f[0].time, 0.1);
  EXPECT_DOUBLE_EQ(f[0].fy, 250.0);
  EXPECT_DOUBLE_EQ(f[1].time, 0.2);
  EXPECT_DOUBLE_EQ(f[1].fy, 300.0);
  EXPECT_THROW(ringcrush::compare::parse_ccx_total_forces(
                   " total force (fx,fy,fz) for set A and time 0.1\n\n  x y\n", "A"),
               std::runtime_error);
}

// The cross-check itself: ccx on the exported deck against ringcrush's FE on the same mesh.
TEST(CalculixExport, CcxLoadAgreesWithRingcrushWithinTenPercent) {
  if (!ccx_testing::ccx_on_path()) GTEST_SKIP() << ccx_testing::kMissing;
  const fs::path dir = scratch("ccx");
  const fs::path scene = coarse_scene(dir);
  auto r = run_cli("export-calculix " + scene.string() + " -o " + (dir / "ccx").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(ccx_testing::run_ccx(dir / "ccx", "thesis_coarse")) << read_text(dir / "ccx" / "ccx.log");
  const double ccx_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto forces = ringcrush::compare::parse_ccx_total_forces(read_text(dir / "ccx" / "thesis_coarse.dat"),
                                                                 "PLATE_TOP_NODES");
  ASSERT_GT(forces.size(), 5u);

  r = run_cli("fe " + scene.string() + " -q -o " + (dir / "fe").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::vector<double> fe_delta, fe_force;
  for (const auto& v : test_files::csv_rows(dir / "fe" / "history.csv")) {  // deflection_m, force_N, ...
    fe_delta.push_back(v.at(0));
    fe_force.push_back(v.at(1));
  }
  const ringcrush::compare::Scene s = ringcrush::compare::load_scene(scene);
  const ringcrush::compare::CalculixDeck deck = ringcrush::compare::calculix_deck(s);
  const double crush = s.analysis.crush_m;
  const double d = s.rings.outer_diameter_m - s.rings.wall_thickness_m;  // mean diameter
  std::vector<double> ccx_delta{0.0}, ccx_force{0.0};
  for (const auto& f : forces) {
    ccx_delta.push_back(f.time * crush);
    ccx_force.push_back(deck.load_factor * std::abs(f.fy));  // half model, thin slab → whole ring
  }
  for (double ratio : {0.1, 0.3}) {
    const double p_ccx = at(ccx_delta, ccx_force, ratio * d);
    const double p_fe = at(fe_delta, fe_force, ratio * d);
    RecordProperty("load_ccx_N_at_" + std::to_string(ratio), std::to_string(p_ccx));
    RecordProperty("load_ringcrush_N_at_" + std::to_string(ratio), std::to_string(p_fe));
    std::printf("delta/d = %.2f: ccx %.2f N, ringcrush %.2f N (%.2f %%); ccx wall %.2f s\n", ratio, p_ccx, p_fe,
                100 * (p_ccx - p_fe) / p_fe, ccx_s);
    ASSERT_TRUE(std::isfinite(p_ccx)) << "ccx stopped before delta/d = " << ratio;
    EXPECT_NEAR(p_ccx, p_fe, 0.10 * p_fe) << "delta/d = " << ratio;
  }
}
