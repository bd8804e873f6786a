// `ringcrush export-calculix` on dynamic scenes (issue 5 item 3): the chain deck carries
// ringcrush's own chain mesh as one layer of 20-node bricks, the masses scaled to the slab, the
// impactor's rigid body, mass and velocity, the contact gaps and the step (checked without
// ccx), and — when CalculiX is installed — ccx run on one coarse ring for 50 µs moves the
// impactor as ringcrush's own FE does (compare/calculix_export.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "ccx_testing.hpp"
#include "command_run.hpp"
#include "compare/calculix_deck_parts.hpp"
#include "compare/calculix_export.hpp"
#include "compare/fe_dynamic.hpp"
#include "compare/scene.hpp"
#include "fe/chain/chain_mesh.hpp"
#include "test_files.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) { return test_files::scratch_dir("ringcrush_calculix_dyn_test_", name); }

// The thesis dynamic chain cut to `rings` rings of 12 CPS8 per half ring, ending at end_time.
fs::path coarse_chain(const fs::path& dir, const std::string& rings, const std::string& end_time,
                      const test_files::Edits& more = {}) {
  test_files::Edits edits{{"count = 6", "count = " + rings},
                          {"elements_around = 48", "elements_around = 12"},
                          {"end_time_s = 0\\.05", "end_time_s = " + end_time},
                          {"fields = true", "fields = false"},
                          {"plots = true", "plots = false"},
                          {"frames = 20", "frames = 0"}};
  edits.insert(edits.end(), more.begin(), more.end());
  return test_files::edited_scene("data/scenes/thesis_dynamic.toml", dir / "chain.toml", edits);
}

using ccx_testing::deck_blocks;

using test_files::numbers;

const std::vector<std::string>& block(const std::multimap<std::string, std::vector<std::string>>& b,
                                      const std::string& key) {
  const auto it = b.find(key);
  if (it == b.end()) throw std::runtime_error("deck has no " + key);
  return it->second;
}

}  // namespace

TEST(CalculixDynamicExport, WeldedChainDeckCarriesMeshMassesVelocityAndContact) {
  using namespace ringcrush;
  const fs::path dir = scratch("welded");
  const compare::Scene s = compare::load_scene(coarse_chain(dir, "2", "0.0001"));
  const compare::CalculixDeck deck = compare::calculix_deck(s);  // dispatches on the analysis type
  ASSERT_TRUE(deck.dynamic);
  const fe::ChainInput in = compare::fe_chain_input(s);
  const fe::ChainTopology topo = fe::make_chain_topology(in);
  const auto& mesh = topo.mesh;
  const auto b = deck_blocks(deck.deck);

  // Elements: ringcrush's CPS8 as C3D20 (selective → full integration), 2 lines each (ccx
  // reads 16 entries a line); the 4 front corners are the CPS8 corners, the back ones + N.
  const auto& rings = block(b, "*ELEMENT, TYPE=C3D20, ELSET=RINGS");
  ASSERT_EQ(rings.size(), 2 * mesh.elements.size());
  EXPECT_EQ(deck.ring_elements, static_cast<int>(mesh.elements.size()));
  EXPECT_EQ(deck.ring_element_type, "C3D20");
  // Welded: the shared node is one node, so the chain has 2 × ring nodes − 1 plane nodes.
  const int plane = mesh.impactor_node;
  EXPECT_EQ(plane, 2 * static_cast<int>(topo.ring.nodes.size()) - 1);
  int corners = 0;
  {
    std::vector<bool> c(static_cast<std::size_t>(plane), false);
    for (const auto& e : mesh.elements)
      for (int a = 0; a < 4; ++a) c[static_cast<std::size_t>(e[static_cast<std::size_t>(a)])] = true;
    for (bool x : c) corners += x ? 1 : 0;
  }
  EXPECT_EQ(deck.ring_nodes, 2 * plane + corners);
  const auto& node_lines = block(b, "*NODE, NSET=NALL");
  EXPECT_EQ(static_cast<int>(node_lines.size()), deck.nodes);
  std::map<int, std::vector<double>> xyz;
  for (const auto& l : node_lines) {
    const auto v = numbers(l);
    ASSERT_EQ(v.size(), 4u) << l;
    xyz[static_cast<int>(v[0])] = {v[1], v[2], v[3]};
  }
  for (int n = 1; n <= plane; ++n) {
    // ccx reads 20 characters a field: the shortest exact decimal, or 15–16 digits.
    EXPECT_NEAR(xyz.at(n)[0], mesh.nodes[static_cast<std::size_t>(n - 1)].x(), 1e-15 * s.rings.outer_diameter_m) << n;
    EXPECT_NEAR(xyz.at(n)[1], mesh.nodes[static_cast<std::size_t>(n - 1)].y(), 1e-15 * s.rings.outer_diameter_m) << n;
    EXPECT_EQ(xyz.at(n)[2], 0.0);
  }
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const auto v = numbers(rings[2 * e]);
    ASSERT_EQ(v.size(), 16u);
    for (int a = 0; a < 4; ++a) EXPECT_EQ(static_cast<int>(v[1 + static_cast<std::size_t>(a)]), mesh.elements[e][static_cast<std::size_t>(a)] + 1);
    // back corner a + 4 lies over front corner a, one slab thickness behind
    for (int a = 0; a < 4; ++a) {
      const auto& f = xyz.at(static_cast<int>(v[1 + static_cast<std::size_t>(a)]));
      const auto& k = xyz.at(static_cast<int>(v[5 + static_cast<std::size_t>(a)]));
      EXPECT_EQ(f[0], k[0]);  // the same text
      EXPECT_EQ(f[1], k[1]);
      EXPECT_NEAR(k[2] - f[2], deck.section_thickness_m, 1e-18);
    }
  }

  // Masses: the ring's *DENSITY is the scene's (the slab carries s/L of the mass by its
  // volume); the impactor's *MASS is its physical mass / (2 L / s) of the half model's slab.
  EXPECT_NEAR(deck.section_thickness_m, 0.1 * s.rings.wall_thickness_m, 1e-15);
  EXPECT_NEAR(deck.load_factor, 2 * s.rings.width_m / deck.section_thickness_m, 1e-9);
  EXPECT_EQ(numbers(block(b, "*DENSITY").at(0)).at(0), s.rings.material.density_kg_m3);
  const double m = numbers(block(b, "*MASS, ELSET=IMPACTOR_MASS").at(0)).at(0);
  EXPECT_NEAR(m, s.impactor->mass_kg / deck.load_factor, 1e-12 * m);
  EXPECT_NEAR(deck.impactor_mass_kg, m, 1e-15);
  EXPECT_NE(deck.deck.find("*RIGID BODY, NSET=IMPACTOR_NODES, REF NODE=" + std::to_string(deck.driven_reference_node)),
            std::string::npos);
  // Initial velocity: every node of the impactor and its reference node, −v along y.
  const auto& ic = block(b, "*INITIAL CONDITIONS, TYPE=VELOCITY");
  ASSERT_EQ(ic.size(), 2u);
  for (const auto& l : ic) {
    const auto v = numbers(l.substr(l.find(',') + 1));
    EXPECT_EQ(v.at(0), 2.0);
    EXPECT_EQ(v.at(1), -s.impactor->velocity_m_s);
  }
  // Contact: the impactor's gaps sum to ringcrush's penalty over the facing half ring's nodes
  // (scale · E / h × Σ w × s), the apex gap is closed, all gaps have clearance ≥ 0.
  double k_impactor = 0, closed = 0;
  int gap_count = 0;
  const std::string ref = std::to_string(deck.driven_reference_node);
  std::map<int, int> gap_other;  // gap element id → second node
  for (const auto& [key, lines] : b)
    if (key.rfind("*ELEMENT, TYPE=GAPUNI", 0) == 0) {
      const auto v = numbers(lines.at(0));
      gap_other[static_cast<int>(v.at(0))] = static_cast<int>(v.at(2));
      ++gap_count;
    }
  EXPECT_EQ(gap_count, deck.gap_elements);
  for (const auto& [key, lines] : b)
    if (key.rfind("*GAP, ELSET=GAP", 0) == 0) {
      const int id = std::stoi(key.substr(std::string("*GAP, ELSET=GAP").size()));
      const auto v = numbers(lines.at(0));
      ASSERT_EQ(v.size(), 6u) << lines.at(0);
      EXPECT_GE(v[0], 0.0);
      if (gap_other.at(id) == deck.driven_reference_node) {
        EXPECT_EQ(v[2], 1.0);  // the impactor lies above ring 1
        k_impactor += v[5];
        if (v[0] == 0.0) closed += 1;
      }
    }
  double w_top = 0;
  for (std::size_t j = 0; j < topo.ring.outer_nodes.size(); ++j)
    if (topo.ring.nodes[static_cast<std::size_t>(topo.ring.outer_nodes[j])].y() >= 0) w_top += topo.ring.outer_weight[j];
  const double slope = s.fe.contact_penalty_scale * s.rings.material.youngs_modulus_pa / topo.ring.element_depth;
  EXPECT_NEAR(k_impactor, slope * w_top * deck.section_thickness_m, 1e-9 * k_impactor);
  EXPECT_EQ(closed, 3.0);  // the apex: front, middle and back node of a corner
  EXPECT_GT(deck.ring_ring_gaps, 0);
  EXPECT_GT(deck.inner_wall_gaps, 0);
  // Step: HHT α and the scene's step and end time.
  const auto& dyn = block(b, "*DYNAMIC, ALPHA=-0.105");
  const auto d = numbers(dyn.at(0));
  EXPECT_EQ(d.at(0), s.fe.initial_step_s);
  EXPECT_EQ(d.at(1), s.analysis.end_time_s);
  EXPECT_NE(deck.readme.find("GAPUNI"), std::string::npos);
}

// Plates: each joint plate a rigid body with its mass, gaps to both its rings; free joints:
// two distinct touching nodes joined by a closed gap.
TEST(CalculixDynamicExport, PlatesAndFreeJoints) {
  using namespace ringcrush;
  const fs::path dir = scratch("joints");
  const compare::Scene plates = compare::load_scene(test_files::edited_scene(
      "data/scenes/test30_plates.toml", dir / "plates.toml",
      {{"count = 6", "count = 3"}, {"elements_around = 48", "elements_around = 12"}}));
  const auto dp = compare::calculix_deck(plates);
  const auto bp = deck_blocks(dp.deck);
  for (const char* p : {"PLATE1", "PLATE2"}) {
    const double m = numbers(block(bp, std::string("*MASS, ELSET=") + p + "_MASS").at(0)).at(0);
    EXPECT_NEAR(m, plates.joints.plate_mass_kg / dp.load_factor, 1e-12 * m) << p;
    EXPECT_NE(dp.deck.find(std::string("*RIGID BODY, NSET=") + p + "_NODES"), std::string::npos) << p;
  }
  EXPECT_EQ(dp.ring_ring_gaps, 0);

  const compare::Scene free = compare::load_scene(test_files::edited_scene(
      "data/scenes/test30_free.toml", dir / "free.toml",
      {{"count = 6", "count = 2"}, {"elements_around = 48", "elements_around = 12"}}));
  const auto df = compare::calculix_deck(free);
  // Free: the touching nodes are distinct, so one more mirror pair than welded (the joint's own).
  const compare::Scene welded = compare::load_scene(test_files::edited_scene(
      "data/scenes/test30_welded.toml", dir / "welded.toml",
      {{"count = 6", "count = 2"}, {"elements_around = 48", "elements_around = 12"}}));
  const auto dw = compare::calculix_deck(welded);
  EXPECT_EQ(df.ring_ring_gaps, dw.ring_ring_gaps + 3);  // the joint node's front, middle and back
  // An explicit scene is integrated by ccx's implicit alpha method (ccx's explicit step crawls).
  EXPECT_NE(df.deck.find("*DYNAMIC, ALPHA=" + compare::calculix_parts::num(free.fe.hht_alpha)), std::string::npos);
}

TEST(CalculixDynamicExport, CommandSaysWhatTheDeckHolds) {
  const fs::path dir = scratch("cli");
  const auto r = cli_testing::ringcrush("export-calculix " + coarse_chain(dir, "2", "0.0001").string() + " -o " +
                                        (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "chain.inp"));
  EXPECT_NE(r.output.find("*DYNAMIC deck"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("GAPUNI"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("*RIGID BODY"), std::string::npos) << r.output;
}

TEST(CalculixDynamicExport, ParsesCcxNodeVectors) {
  const std::string dat =
      " displacements (vx,vy,vz) for set IMPACTOR_REF and time  0.5000000E-04\n\n"
      "       448  0.000000E+00 -1.482861E-03  0.000000E+00\n\n"
      " velocities (vx,vy,vz) for set IMPACTOR_REF and time  0.5000000E-04\n\n"
      "       448  0.000000E+00 -2.945388E+01  0.000000E+00\n";
  const auto u = ringcrush::compare::parse_ccx_node_vectors(dat, "displacements", "impactor_ref");
  ASSERT_EQ(u.size(), 1u);
  EXPECT_DOUBLE_EQ(u[0].time, 5e-5);
  EXPECT_DOUBLE_EQ(u[0].y, -1.482861e-3);
  const auto v = ringcrush::compare::parse_ccx_node_vectors(dat, "velocities", "IMPACTOR_REF");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_DOUBLE_EQ(v[0].y, -29.45388);
  EXPECT_THROW(ringcrush::compare::parse_ccx_node_vectors(" velocities (vx,vy,vz) for set A and time 1\n\n x\n",
                                                          "velocities", "A"),
               std::runtime_error);
}

// The cross-check: ccx on one coarse ring for 50 µs against ringcrush's FE on the same mesh.
// In 50 µs the impactor (0.256 kg at 30 m/s) loses ~0.5 m/s, so its displacement is within
// 1.2 % of free flight whatever the ring does; the test therefore compares what the ring does
// to it: the velocity lost and the displacement short of free flight, within 15 %. The two
// models differ by the element (C3D20 through a thin slab, consistent mass, against CPS8 plane
// stress with the selective scheme and HRZ lumped mass) and by the step control; measured:
// Δv 0.546 m/s (ccx) against 0.516 m/s (ringcrush), 6 %.
TEST(CalculixDynamicExport, CcxImpactorMotionAgreesWithRingcrush) {
  if (!ccx_testing::ccx_on_path()) GTEST_SKIP() << ccx_testing::kMissing;
  const fs::path dir = scratch("ccx");
  const double end = 5e-5;
  const fs::path scene = coarse_chain(dir, "1", "0.00005");
  auto r = cli_testing::ringcrush("export-calculix " + scene.string() + " -o " + (dir / "ccx").string());
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(ccx_testing::run_ccx(dir / "ccx", "chain")) << test_files::read_text(dir / "ccx" / "ccx.log");
  const std::string dat = test_files::read_text(dir / "ccx" / "chain.dat");
  const auto u = ringcrush::compare::parse_ccx_node_vectors(dat, "displacements", "IMPACTOR_REF");
  const auto v = ringcrush::compare::parse_ccx_node_vectors(dat, "velocities", "IMPACTOR_REF");
  ASSERT_FALSE(u.empty());
  ASSERT_FALSE(v.empty());
  ASSERT_NEAR(u.back().time, end, 1e-12) << "ccx stopped before the end";

  r = cli_testing::ringcrush("fe " + scene.string() + " -q -o " + (dir / "fe").string());
  ASSERT_EQ(r.status, 0) << r.output;
  // history.csv: time_s, impactor_displacement_m, impactor_velocity_m_s, ... ; interpolate at end
  const auto rows = test_files::csv_rows(dir / "fe" / "history.csv");
  ASSERT_GE(rows.size(), 2u);
  double fe_u = std::nan(""), fe_v = std::nan("");
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (rows[i][0] >= end - 1e-12) {
      const double f = (end - rows[i - 1][0]) / (rows[i][0] - rows[i - 1][0]);
      fe_u = rows[i - 1][1] + f * (rows[i][1] - rows[i - 1][1]);
      fe_v = rows[i - 1][2] + f * (rows[i][2] - rows[i - 1][2]);
      break;
    }
  ASSERT_TRUE(std::isfinite(fe_u)) << "ringcrush stopped before " << end << " s";
  const double v0 = ringcrush::compare::load_scene(scene).impactor->velocity_m_s;
  const double ccx_u = -u.back().y, ccx_v = -v.back().y;
  const double ccx_dv = v0 - ccx_v, fe_dv = v0 - fe_v;
  const double ccx_short = v0 * end - ccx_u, fe_short = v0 * end - fe_u;
  std::printf("t = %g s: impactor u ccx %.6g m, ringcrush %.6g m; v ccx %.6g, ringcrush %.6g m/s; "
              "dv ccx %.4g, ringcrush %.4g m/s; short of free flight ccx %.4g, ringcrush %.4g m\n",
              end, ccx_u, fe_u, ccx_v, fe_v, ccx_dv, fe_dv, ccx_short, fe_short);
  RecordProperty("dv_ccx", std::to_string(ccx_dv));
  RecordProperty("dv_ringcrush", std::to_string(fe_dv));
  EXPECT_GT(fe_dv, 0.1);  // the ring does slow the impactor
  EXPECT_NEAR(ccx_u, fe_u, 0.002 * fe_u);
  EXPECT_NEAR(ccx_dv, fe_dv, 0.15 * fe_dv);
  EXPECT_NEAR(ccx_short, fe_short, 0.15 * fe_short);
}
