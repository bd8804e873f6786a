// compare/fe_dynamic: the scene → FE mapping (every value, and the refusals), and the
// DynamicResult → RunResult → results-directory path on a synthetic result built here (a real
// chain mesh from the ring mesher, deformed by hand), so the writers are tested without a
// solver: crush ratios and the wrap flag come out of compare/measures, every file is complete,
// the DESIGN.md columns and keys are present, and a NaN is refused, not written.
#include "compare/fe_dynamic.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>

#include "compare/deck_scene.hpp"
#include "compare/fe_static.hpp"
#include "compare/run_output.hpp"
#include "fe/mesh/ring_mesh.hpp"

namespace fs = std::filesystem;
using namespace ringcrush;
using namespace ringcrush::compare;

namespace {

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path scene_path(const std::string& name) {
  return fs::path(RINGCRUSH_SOURCE_DIR) / "data" / "scenes" / (name + ".toml");
}

// A scene file with some text replaced (regex → replacement).
Scene scene_variant(const std::string& name, const std::vector<std::pair<std::string, std::string>>& repl) {
  std::string text = read_text(scene_path(name));
  for (const auto& [pattern, value] : repl) text = std::regex_replace(text, std::regex(pattern), value);
  return parse_scene(text, name + ".toml");
}

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("ringcrush_fe_dynamic_test_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::vector<std::string> csv_header(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) out.push_back(c);
  return out;
}

std::size_t csv_rows(const fs::path& p) {
  std::ifstream in(p);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += !line.empty();
  return n - 1;
}

// The thesis chain cut to four rings on a coarse mesh.
Scene four_rings() {
  return scene_variant("thesis_dynamic", {{"count = 6", "count = 4"}, {"elements_around = 48", "elements_around = 8"},
                                          {"frames = 20", "frames = 2"}});
}

// A chain mesh assembled the way the ChainModel documents it (ring i centred at
// y = −i·pitch, outer nodes ordered by θ from the top apex), plus an impactor node; and a
// final displacement that squashes ring i along y by `crush[i]` about its centre. With
// `wrap_first`, ring 1's lower half is turned inside out instead (y − y_c → −½(y − y_c)):
// its lower arc then curves the wrong way over its whole length (a wrap), and its extent is
// R, so its crush ratio is exactly ½.
fe::DynamicResult synthetic_result(const Scene& s, const std::vector<double>& crush, bool wrap_first) {
  const double pi = std::numbers::pi;
  fe::RingInput ring;
  ring.outer_radius_m = 0.5 * s.rings.outer_diameter_m;
  ring.inner_radius_m = ring.outer_radius_m - s.rings.wall_thickness_m;
  ring.width_m = s.rings.width_m;
  fe::MeshInput mesh_in;
  mesh_in.elements_around = s.fe.elements_around;
  mesh_in.half_ring = true;
  const fe::RingMesh rm = fe::make_ring_mesh(ring, mesh_in);

  fe::DynamicResult r;
  auto& m = r.mesh;
  m.half_ring = true;
  std::vector<double> node_phi, node_centre;
  std::vector<int> node_ring;
  for (int i = 0; i < s.rings.count; ++i) {
    const int offset = static_cast<int>(m.nodes.size());
    const double yc = -i * s.rings.pitch_m;
    for (std::size_t k = 0; k < rm.nodes.size(); ++k) {
      m.nodes.emplace_back(rm.nodes[k].x(), rm.nodes[k].y() + yc);
      node_phi.push_back(rm.node_angle[k]);
      node_centre.push_back(yc);
      node_ring.push_back(i);
    }
    for (auto e : rm.elements) {
      for (int& n : e) n += offset;
      m.elements.push_back(e);
      m.element_ring.push_back(i);
    }
    std::vector<int> ids;
    std::vector<double> theta;
    for (auto it = rm.outer_nodes.rbegin(); it != rm.outer_nodes.rend(); ++it) {
      ids.push_back(*it + offset);
      theta.push_back(pi - rm.node_angle[static_cast<std::size_t>(*it)]);
    }
    m.ring_outer_nodes.push_back(ids);
    m.ring_outer_theta.push_back(theta);
    m.ring_centre_y.push_back(yc);
  }
  m.impactor_node = static_cast<int>(m.nodes.size());
  m.nodes.emplace_back(0.0, ring.outer_radius_m);

  const auto nn = static_cast<Eigen::Index>(m.nodes.size());
  r.final_displacement = Eigen::VectorXd::Zero(2 * nn);
  for (std::size_t k = 0; k < node_ring.size(); ++k) {
    const double dy = m.nodes[k].y() - node_centre[k];
    const auto dof = static_cast<Eigen::Index>(2 * k + 1);
    if (wrap_first && node_ring[k] == 0)
      r.final_displacement(dof) = node_phi[k] < 0.5 * pi ? -1.5 * dy : 0.0;
    else
      r.final_displacement(dof) = -crush[static_cast<std::size_t>(node_ring[k])] * dy;
  }

  // Five history rows: the impactor (KE0 = ½·0.256·30² = 115.2 J) slows and rebounds.
  const double ke0 = 0.5 * s.impactor->mass_kg * s.impactor->velocity_m_s * s.impactor->velocity_m_s;
  const std::vector<double> v{30.0, 20.0, 8.0, -0.5, -1.0};
  for (int k = 0; k < 5; ++k) {
    fe::DynamicRow row;
    row.time_s = 1e-4 * k;
    row.impactor_velocity_m_s = v[static_cast<std::size_t>(k)];
    row.impactor_displacement_m = 1e-3 * k;
    row.impactor_force_n = k == 2 ? 5000.0 : 1000.0 * k;
    for (int i = 0; i < s.rings.count; ++i)
      row.ring_crush_m.push_back(0.25 * k * crush[static_cast<std::size_t>(i)] * s.rings.outer_diameter_m);
    row.kinetic_j = 0.5 * s.impactor->mass_kg * row.impactor_velocity_m_s * row.impactor_velocity_m_s;
    row.plastic_j = 0.9 * (ke0 - row.kinetic_j);
    row.elastic_j = 0.05 * (ke0 - row.kinetic_j);
    row.contact_j = 0.01 * (ke0 - row.kinetic_j);
    row.numerical_j = ke0 - row.kinetic_j - row.plastic_j - row.elastic_j - row.contact_j;
    row.step_s = 1e-7;
    r.history.push_back(row);
  }
  for (int f = 0; f < 2; ++f) {
    fe::DynamicFrame fr;
    fr.time_s = 4e-4 * f;
    fr.displacement = f == 0 ? Eigen::VectorXd::Zero(2 * nn) : r.final_displacement;
    fr.mises_pa.assign(m.elements.size(), 1e8 * f);
    fr.peeq.assign(m.elements.size(), 0.01 * f);
    fr.stress_pa.assign(3 * m.elements.size(), -5e7 * f);
    fr.contact_pressure_pa.assign(m.nodes.size(), 0.0);
    r.frames.push_back(fr);
  }
  r.max_peeq_per_ring.assign(static_cast<std::size_t>(s.rings.count), 0.2);
  r.initial_kinetic_j = ke0;
  r.energy_balance_error = 0.0042;
  r.numerical_dissipation = 0.04;
  r.end_reason = "arrest";
  r.statistics.steps = 4000;
  r.statistics.wall_time_s = 2.0;
  r.statistics.contact_time_s = 0.5;
  r.statistics.step_limited_by = "element 3 (ring 1)";
  return r;
}

}  // namespace

TEST(FeDynamicInput, ThesisSceneMapsEveryValue) {
  const Scene s = load_scene(scene_path("thesis_dynamic"));
  const fe::ChainInput c = fe_chain_input(s);
  EXPECT_EQ(c.rings, 6);
  EXPECT_DOUBLE_EQ(c.ring.outer_radius_m, 0.0254);
  EXPECT_NEAR(c.ring.inner_radius_m, 0.0254 - 0.0016, 1e-15);
  EXPECT_DOUBLE_EQ(c.ring.width_m, 0.0125);
  EXPECT_DOUBLE_EQ(c.material.youngs_modulus_pa, 202e9);
  EXPECT_DOUBLE_EQ(c.material.poisson_ratio, 0.3);
  ASSERT_EQ(c.material.hardening.size(), 2u);
  EXPECT_DOUBLE_EQ(c.material.hardening[1].yield_stress_pa, 320e6);
  EXPECT_DOUBLE_EQ(c.material.hardening[1].plastic_strain, 0.02113);
  EXPECT_DOUBLE_EQ(c.density_kg_m3, 8410.0);
  EXPECT_EQ(c.mesh.elements_around, 48);
  EXPECT_EQ(c.mesh.elements_through, 1);
  EXPECT_TRUE(c.mesh.half_ring);
  EXPECT_EQ(c.integration, fe::Integration::Selective);
  EXPECT_DOUBLE_EQ(c.contact.smoothing, 0.25);
  EXPECT_DOUBLE_EQ(c.contact.penalty_scale, 1.0);
  EXPECT_DOUBLE_EQ(c.pitch_m, 0.0508);
  EXPECT_EQ(c.joints, fe::JointKind::Welded);
  EXPECT_DOUBLE_EQ(c.impactor_mass_kg, 0.256);  // the FULL mass: the model halves it
  EXPECT_DOUBLE_EQ(c.impactor_velocity_m_s, 30.0);
  EXPECT_TRUE(c.fixed_target);

  const fe::DynamicSolverInput d = fe_dynamic_solver_input(s);
  EXPECT_EQ(d.scheme, fe::DynamicScheme::Hht);
  EXPECT_DOUBLE_EQ(d.alpha, -0.105);
  EXPECT_DOUBLE_EQ(d.initial_step_s, 5e-7);
  EXPECT_DOUBLE_EQ(d.haftol_n, 1e4);
  EXPECT_DOUBLE_EQ(d.ptol_n, 3.0);
  EXPECT_DOUBLE_EQ(d.end_time_s, 0.05);
  EXPECT_TRUE(d.stop_at_rest);
  EXPECT_EQ(d.frames, 20);
  EXPECT_DOUBLE_EQ(d.energy_error_limit, 0.05);
  EXPECT_DOUBLE_EQ(d.safety, 0.8);
  EXPECT_DOUBLE_EQ(c.bulk_viscosity, 0.06);  // ABAQUS/Explicit's default b1
  EXPECT_EQ(c.step_bound, fe::StepBound::Assembled);  // the estimate by default (session 12; test below)
  EXPECT_GE(d.max_step_s, d.initial_step_s);
  EXPECT_LT(d.min_step_s, d.initial_step_s);
}

// The shipped explicit step defaults, decided in session 12 on the stability matrix's hard
// cells (README "FE dynamics": the assembled estimate lost no case the element bound brings to
// rest and takes 7–21 % fewer steps; safety 0.9 lost one, so 0.8 stays): a scene or a deck
// without the keys runs the assembled estimate at 0.8, and the keys set to the old defaults
// still give the element bound (the route to every earlier measurement).
TEST(FeDynamicInput, ShippedExplicitStepDefaults) {
  for (const char* name : {"thesis_dynamic", "test30_welded", "test30_free", "test30_plates"}) {
    const std::string text = read_text(scene_path(name));
    ASSERT_EQ(text.find("step_bound"), std::string::npos) << name;  // the defaults, not the file, decide
    ASSERT_EQ(text.find("explicit_safety"), std::string::npos) << name;
    const Scene s = scene_variant(name, {{"solver = \"hht\"", "solver = \"explicit\""}});
    EXPECT_EQ(s.fe.step_bound, ExplicitStepBound::Assembled) << name;
    EXPECT_EQ(s.fe.explicit_safety, 0.8) << name;
    EXPECT_EQ(fe_chain_input(s).step_bound, fe::StepBound::Assembled) << name;
    EXPECT_EQ(fe_dynamic_solver_input(s).safety, 0.8) << name;
  }
  const Scene deck = scene_from_deck(fs::path(RINGCRUSH_SOURCE_DIR) / "data" / "thesis" / "thesis_dynamic.inp");
  EXPECT_EQ(deck.fe.step_bound, ExplicitStepBound::Assembled);
  EXPECT_EQ(deck.fe.explicit_safety, 0.8);
  const Scene old = scene_variant("thesis_dynamic", {{"solver = \"hht\"", "solver = \"explicit\""},
                                                     {"\\[fe\\]", "[fe]\nstep_bound = \"element\"\nexplicit_safety = 0.8"}});
  EXPECT_EQ(fe_chain_input(old).step_bound, fe::StepBound::Element);
  EXPECT_EQ(fe_dynamic_solver_input(old).safety, 0.8);
}

TEST(FeDynamicInput, PlatesFreeEndAndSolverKeys) {
  const Scene s = scene_variant("test30_plates", {{"type = \"fixed\"", "type = \"free\""},
                                                  {"integration = \"reduced\"", "integration = \"full\""},
                                                  {"\\[fe\\]", "[fe]\nexplicit_safety = 0.6\nenergy_error_limit = 0.02\nbulk_viscosity = 0.1\n"
                                                               "step_bound = \"element\"\ncontact_smoothing = 0.1\ncontact_penalty_scale = 3.0"},
                                                  {"fields = true", "fields = false"},
                                                  {"stop_at_rest = true", "stop_at_rest = false"}});
  const fe::ChainInput c = fe_chain_input(s);
  EXPECT_EQ(c.joints, fe::JointKind::Plates);
  EXPECT_DOUBLE_EQ(c.plate_mass_kg, 0.010);
  EXPECT_DOUBLE_EQ(c.plate_thickness_m, 0.002);
  EXPECT_DOUBLE_EQ(c.pitch_m, 0.0528);
  EXPECT_DOUBLE_EQ(c.density_kg_m3, 7850.0);
  EXPECT_DOUBLE_EQ(c.impactor_mass_kg, 0.257);
  EXPECT_DOUBLE_EQ(c.impactor_velocity_m_s, 27.7);
  EXPECT_FALSE(c.fixed_target);
  EXPECT_EQ(c.integration, fe::Integration::Full);
  EXPECT_DOUBLE_EQ(c.contact.smoothing, 0.1);
  EXPECT_DOUBLE_EQ(c.contact.penalty_scale, 3.0);
  const fe::DynamicSolverInput d = fe_dynamic_solver_input(s);
  EXPECT_EQ(d.scheme, fe::DynamicScheme::Explicit);
  EXPECT_DOUBLE_EQ(d.safety, 0.6);
  EXPECT_DOUBLE_EQ(d.energy_error_limit, 0.02);
  EXPECT_DOUBLE_EQ(c.bulk_viscosity, 0.1);
  EXPECT_EQ(c.step_bound, fe::StepBound::Element);  // the key against the default (assembled)
  EXPECT_FALSE(d.stop_at_rest);
  EXPECT_EQ(d.frames, 0);  // outputs.fields = false
  const Scene free = load_scene(scene_path("test28_free"));
  EXPECT_EQ(fe_chain_input(free).joints, fe::JointKind::Free);
  EXPECT_DOUBLE_EQ(fe_chain_input(free).impactor_velocity_m_s, 54.1);
}

TEST(FeDynamicInput, ContactArrivalDepthKey) {
  // Default half the reach (fe/contact/contact_arrival.hpp); the scene key reaches the chain;
  // a value outside (0, 1] is refused by name.
  EXPECT_DOUBLE_EQ(fe_chain_input(load_scene(scene_path("thesis_dynamic"))).contact.arrival_depth, 0.5);
  const Scene s = scene_variant("thesis_dynamic", {{"\\[fe\\]", "[fe]\ncontact_arrival_depth = 0.8"}});
  EXPECT_DOUBLE_EQ(fe_chain_input(s).contact.arrival_depth, 0.8);
  for (const char* bad : {"0", "-0.2", "1.5"}) {
    try {
      scene_variant("thesis_dynamic", {{"\\[fe\\]", std::string("[fe]\ncontact_arrival_depth = ") + bad}});
      ADD_FAILURE() << bad << " accepted";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("contact_arrival_depth"), std::string::npos) << e.what();
    }
  }
}

TEST(FeDynamicInput, RefusesWhatTheDynamicFeDoesNotCover) {
  const Scene stat = load_scene(scene_path("thesis_static"));
  EXPECT_THROW(fe_chain_input(stat), std::invalid_argument);
  EXPECT_THROW(fe_dynamic_solver_input(stat), std::invalid_argument);
  const Scene friction = scene_variant("thesis_dynamic", {{"\\[fe\\]", "[fe]\nfriction_coefficient = 0.2"}});
  try {
    fe_chain_input(friction);
    FAIL() << "friction accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("friction"), std::string::npos) << e.what();
  }
  // Bulk viscosity b1 outside [0, 1): a named scene error.
  for (const char* b1 : {"-0.06", "1.0", "nan"}) {
    try {
      scene_variant("thesis_dynamic", {{"\\[fe\\]", std::string("[fe]\nbulk_viscosity = ") + b1}});
      ADD_FAILURE() << "bulk_viscosity = " << b1 << " accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("bulk_viscosity"), std::string::npos) << e.what();
    }
  }
  // A step bound that is not one of the two: a named scene error listing them.
  try {
    scene_variant("thesis_dynamic", {{"\\[fe\\]", "[fe]\nstep_bound = \"exact\""}});
    ADD_FAILURE() << "step_bound = \"exact\" accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("step_bound"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("assembled"), std::string::npos) << e.what();
  }
  const Scene strain = scene_variant("thesis_dynamic", {{"plane_stress", "plane_strain"}});
  EXPECT_THROW(fe_chain_input(strain), std::invalid_argument);
  EXPECT_THROW(fe_dynamic_solver_input(strain), std::invalid_argument);
}

TEST(FeDynamicResult, MeasuresComeFromTheFinalOuterSurfaces) {
  const Scene s = four_rings();
  const std::vector<double> crush{0.6, 0.1, 0.55, 0.05};
  const RunResult run = fe_dynamic_run_result(s, synthetic_result(s, crush, false));
  ASSERT_EQ(run.crush_ratio.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(run.crush_ratio[i], crush[i], 1e-12) << "ring " << i + 1;
    EXPECT_FALSE(run.wrap_around[i]) << "an ellipse has no inverted arc, ring " << i + 1;
    EXPECT_NEAR(run.inverted_arc_m[i], 0.0, 1e-12);
  }
  EXPECT_EQ(run.mode, (std::vector<std::string>{"flattened", "crushed", "flattened", "intact"}));
  EXPECT_EQ(run.time_s.size(), 5u);
  EXPECT_EQ(run.ring_crush_m.size(), 4u);
  EXPECT_DOUBLE_EQ(run.ring_crush_m[0].back(), 0.6 * 0.0508);
  // Alternation of c = (0.6, 0.1, 0.55, 0.05) is strong, and flagged as such.
  EXPECT_GT(alternation(run.crush_ratio).index, alternation_threshold);
  EXPECT_TRUE(run.extra["alternates"].get<bool>());
  EXPECT_DOUBLE_EQ(run.extra["energy_balance_error"].get<double>(), 0.0042);
  EXPECT_NEAR(run.extra["contact_share"].get<double>(), 0.25, 1e-15);
  EXPECT_NEAR(run.extra["time_per_element_step_s"].get<double>(), 2.0 / (4000.0 * 32.0), 1e-18);
  EXPECT_EQ(run.extra["end_reason"].get<std::string>(), "arrest");
}

TEST(FeDynamicResult, AnInvertedLowerArcIsAWrap) {
  const Scene s = four_rings();
  const RunResult run = fe_dynamic_run_result(s, synthetic_result(s, {0.0, 0.1, 0.1, 0.1}, true));
  EXPECT_NEAR(run.crush_ratio[0], 0.5, 1e-12);
  EXPECT_TRUE(run.wrap_around[0]);
  EXPECT_EQ(run.mode[0], "wrapped");
  // The inverted arc is the whole lower half: two quarter arcs of the ellipse with semi-axes
  // R, R/2 (≈ 1.211 R each), less the half elements next to the side and the axis.
  const double r_out = 0.0254;
  EXPECT_GT(run.inverted_arc_m[0], 1.5 * r_out);
  EXPECT_LT(run.inverted_arc_m[0], 2.5 * r_out);
  EXPECT_FALSE(run.wrap_around[1]);
}

TEST(FeDynamicResult, NonFiniteValuesAreRefused) {
  const Scene s = four_rings();
  auto r = synthetic_result(s, {0.2, 0.2, 0.2, 0.2}, false);
  r.history[2].impactor_force_n = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(fe_dynamic_run_result(s, r), std::runtime_error);
  r = synthetic_result(s, {0.2, 0.2, 0.2, 0.2}, false);
  r.final_displacement(7) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(fe_dynamic_run_result(s, r), std::runtime_error);
  r = synthetic_result(s, {0.2, 0.2, 0.2, 0.2}, false);
  r.history[1].ring_crush_m.pop_back();
  EXPECT_THROW(fe_dynamic_run_result(s, r), std::runtime_error);
}

TEST(FeDynamicOutputs, ResultsDirectoryIsComplete) {
  const Scene s = four_rings();
  const auto r = synthetic_result(s, {0.6, 0.1, 0.5, 0.05}, false);
  const RunResult run = fe_dynamic_run_result(s, r);
  const fs::path dir = scratch("outputs") / "out";
  {
    ResultsDir out(dir);
    write_fe_dynamic_outputs(s, r, run, out);
    out.commit();
  }
  for (const char* f : {"summary.json", "history.csv", "rings.csv", "crush_per_ring.svg", "crush_final.svg",
                        "impactor.svg", "force.svg", "energy.svg", "series.pvd", "frames/frame_0000.vtu",
                        "frames/frame_0001.vtu"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;

  const auto summary = nlohmann::json::parse(read_text(dir / "summary.json"));
  for (const char* k : {"model", "scene", "analysis", "wall_time_s", "steps", "crush_ratio", "wrap_around",
                        "wrapped_angle_deg", "alternation_index", "energy_balance_error", "arrest_time_s",
                        "peak_force_N", "impactor_final_velocity_m_s", "numerical_dissipation", "end_reason",
                        "max_peeq_per_ring", "step_limited_by", "contact_share", "time_per_element_step_s"})
    EXPECT_TRUE(summary.contains(k)) << k;
  EXPECT_EQ(summary["analysis"], "dynamic");
  EXPECT_EQ(summary["crush_ratio"].size(), 4u);
  // The driver's balance, not run_output's remainder sum (zero by construction here).
  EXPECT_DOUBLE_EQ(summary["energy_balance_error"].get<double>(), 0.0042);
  EXPECT_DOUBLE_EQ(summary["peak_force_N"].get<double>(), 5000.0);
  EXPECT_DOUBLE_EQ(summary["impactor_final_velocity_m_s"].get<double>(), -1.0);
  // v crosses zero between 2e-4 s (8 m/s) and 3e-4 s (−0.5 m/s).
  EXPECT_NEAR(summary["arrest_time_s"].get<double>(), 2e-4 + 1e-4 * 8.0 / 8.5, 1e-12);
  EXPECT_NEAR(summary["alternation_index"].get<double>(), alternation(run.crush_ratio).index, 1e-15);

  const auto history = csv_header(dir / "history.csv");
  for (const char* c : {"time_s", "impactor_displacement_m", "impactor_velocity_m_s", "impactor_force_N",
                        "crush_ring_1_m", "crush_ring_4_m", "kinetic_J", "elastic_J", "plastic_J", "contact_J",
                        "numerical_J", "external_work_J"})
    EXPECT_NE(std::find(history.begin(), history.end(), c), history.end()) << c;
  EXPECT_EQ(csv_rows(dir / "history.csv"), 5u);
  EXPECT_EQ(csv_header(dir / "rings.csv"),
            (std::vector<std::string>{"ring", "crush_ratio", "crush_m", "wrapped_angle_deg", "inverted_arc_m",
                                      "wrap_around", "top_height_ratio", "bottom_height_ratio", "max_peeq", "inverted_turning_deg"}));
  EXPECT_EQ(csv_rows(dir / "rings.csv"), 4u);

  const std::string vtu = read_text(dir / "frames/frame_0001.vtu");
  EXPECT_NE(vtu.find("NumberOfCells=\"32\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"ring\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"stress\" NumberOfComponents=\"3\""), std::string::npos);  // xx, yy, xy per element
  EXPECT_NE(vtu.find("</VTKFile>"), std::string::npos);
  EXPECT_NE(read_text(dir / "series.pvd").find("frame_0001.vtu"), std::string::npos);
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string text = read_text(e.path());
    EXPECT_FALSE(std::regex_search(text, std::regex("\\b(nan|inf|infinity)\\b", std::regex::icase))) << e.path();
  }
}

TEST(FeDynamicOutputs, NanInAFrameLeavesNoResultsDirectory) {
  const Scene s = four_rings();
  auto r = synthetic_result(s, {0.2, 0.2, 0.2, 0.2}, false);
  const RunResult run = fe_dynamic_run_result(s, r);
  r.frames[1].peeq[5] = std::numeric_limits<double>::quiet_NaN();
  const fs::path dir = scratch("nan") / "out";
  {
    ResultsDir out(dir);
    EXPECT_THROW(write_fe_dynamic_outputs(s, r, run, out), std::runtime_error);
  }
  EXPECT_FALSE(fs::exists(dir));
}

// Mass scaling (fe/dynamics/mass_scaling.hpp): the [fe] keys reach the chain input with the
// scene's safety; off by default; bad values are scene errors naming the key; with HHT or a
// static scene it is refused by name, not ignored; the summary carries the added mass.
TEST(FeDynamicInput, MassScalingKeys) {
  const fe::ChainInput off = fe_chain_input(scene_variant("thesis_dynamic", {{"solver = \"hht\"", "solver = \"explicit\""}}));
  EXPECT_FALSE(off.mass_scaling.active());
  const Scene s = scene_variant("thesis_dynamic", {{"solver = \"hht\"", "solver = \"explicit\""},
                                                   {"\\[fe\\]", "[fe]\nmass_scaling_dt = 1.5e-7\nmass_scaling_factor = 2.0\nexplicit_safety = 0.7"}});
  const fe::ChainInput c = fe_chain_input(s);
  EXPECT_DOUBLE_EQ(c.mass_scaling.target_step_s, 1.5e-7);
  EXPECT_DOUBLE_EQ(c.mass_scaling.factor, 2.0);
  EXPECT_DOUBLE_EQ(c.mass_scaling.safety, 0.7);
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"mass_scaling_dt", "-1e-7"}, {"mass_scaling_dt", "nan"}, {"mass_scaling_factor", "0.5"},
           {"mass_scaling_factor", "inf"}}) {
    try {
      scene_variant("thesis_dynamic", {{"\\[fe\\]", "[fe]\n" + key + " = " + value}});
      ADD_FAILURE() << key << " = " << value << " accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
  // The thesis scene's own solver is HHT: refused by name.
  const Scene hht = scene_variant("thesis_dynamic", {{"\\[fe\\]", "[fe]\nmass_scaling_dt = 1e-7"}});
  try {
    fe_chain_input(hht);
    ADD_FAILURE() << "mass scaling with HHT accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("explicit solver only"), std::string::npos) << e.what();
  }
  const Scene stat = scene_variant("thesis_static", {{"\\[fe\\]", "[fe]\nmass_scaling_factor = 2.0"}});
  try {
    fe_static_input(stat);
    ADD_FAILURE() << "mass scaling with a static scene accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mass_scaling_factor"), std::string::npos) << e.what();
  }
  // The summary reports the added mass next to the rings' and the impactor's.
  const Scene four = four_rings();
  auto r = synthetic_result(four, {0.2, 0.2, 0.2, 0.2}, false);
  r.mass_scaling.active = true;
  r.mass_scaling.target_step_s = 1e-7;
  r.mass_scaling.element_mass_kg = 0.1;
  r.mass_scaling.added_mass_kg = 0.05;
  r.mass_scaling.scaled_elements = 7;
  const RunResult run = fe_dynamic_run_result(four, r);
  const auto j = fe_dynamic_summary(four, run);
  ASSERT_TRUE(j.contains("mass_scaling"));
  EXPECT_DOUBLE_EQ(j["mass_scaling"]["added_mass_percent_of_rings"].get<double>(), 50.0);
  EXPECT_DOUBLE_EQ(j["mass_scaling"]["added_mass_over_impactor_mass"].get<double>(), 0.05 / four.impactor->mass_kg);
  EXPECT_EQ(j["mass_scaling"]["elements_scaled"].get<int>(), 7);
  EXPECT_FALSE(fe_dynamic_summary(four, fe_dynamic_run_result(four, synthetic_result(four, {0.2, 0.2, 0.2, 0.2}, false)))
                   .contains("mass_scaling"));
}

TEST(FeDynamicInput, ContactPenaltyStepFractionKey) {
  EXPECT_EQ(fe_chain_input(scene_variant("thesis_dynamic", {})).contact_penalty_step_fraction, 0.0);
  const Scene s = scene_variant("thesis_dynamic", {{"\\[fe\\]", "[fe]\ncontact_penalty_step_fraction = 0.05"}});
  EXPECT_DOUBLE_EQ(fe_chain_input(s).contact_penalty_step_fraction, 0.05);
  for (const std::string value : {"-0.1", "0.6", "nan"}) {
    try {
      scene_variant("thesis_dynamic", {{"\\[fe\\]", "[fe]\ncontact_penalty_step_fraction = " + value}});
      ADD_FAILURE() << value << " accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("contact_penalty_step_fraction"), std::string::npos) << e.what();
    }
  }
}
