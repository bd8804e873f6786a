// The Level 2 polygon chain on the explicit central-difference driver
// (hinge/polygon_central_difference.hpp): momentum in free flight, the energy balance of an
// impact, agreement with IDA at a tight tolerance, the wiring through a scene, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include <fstream>
#include <sstream>

#include "compare/hinge_run_1d.hpp"
#include "compare/hinge_run_2d.hpp"
#include "compare/scene.hpp"
#include "hinge/polygon_central_difference.hpp"
#include "hinge/polygon_simulation.hpp"
#include "two_ring_chain.hpp"

using namespace ringcrush::hinge;

namespace {

PolygonRunOutput run(const PolygonChainInput& in, PolygonIntegrator integ, double end) {
  PolygonRunOptions o;
  o.integrator = integ;
  o.relative_tolerance = 1e-6;
  o.absolute_scale = 1e-6;
  o.end_time_s = end;
  o.output_interval_s = 5e-5;
  return run_polygon_chain(in, o);
}

// Σ μ v over the nodes, x and y (the ring's momentum).
std::array<double, 2> ring_momentum(const PolygonChain& chain, const std::vector<double>& y) {
  std::array<double, 2> p{0.0, 0.0};
  for (int j = 0; j < chain.independent_nodes(); ++j) {
    const auto o = chain.node_offset(0, j);
    p[0] += chain.node_mass() * y[o + 2];
    p[1] += chain.node_mass() * y[o + 3];
  }
  return p;
}

}  // namespace

// One full ring (no symmetry plane), no target, the impactor left behind: a ring thrown
// sideways and downward, spinning and ringing in its ovalisation mode. Bars, hinges and their
// dampers act in equal and opposite pairs, so the leapfrog keeps the momentum to round-off
// while the ring deforms (0.3 ms, ~1500 steps).
TEST(PolygonCentralDifference, FreeFlightKeepsMomentum) {
  PolygonChainInput in = two_ring_chain::input(PolygonJoint::Free);
  in.rings = 1;
  in.half_symmetry = false;
  in.fixed_target = false;
  in.impactor_velocity_m_s = 0.0;
  PolygonChain chain(in);
  std::vector<double> y = chain.initial_state();
  const double R = chain.mean_radius();
  for (int j = 0; j < chain.independent_nodes(); ++j) {
    const auto o = chain.node_offset(0, j);
    const double x = y[o], yy = y[o + 1] - (y[chain.node_offset(0, 0) + 1] - R);  // from the centre
    const double a = 2.0 * std::numbers::pi * j / chain.nodes_per_ring();
    const double radial = 8.0 * std::cos(2.0 * a);  // m/s, ovalisation
    y[o + 2] = 3.0 - 400.0 * yy + radial * std::sin(a);
    y[o + 3] = -20.0 + 400.0 * x + radial * std::cos(a);  // away from the impactor above
  }
  const auto p0 = ring_momentum(chain, y);
  PolygonCentralDifference cd(chain, 0.0, y, {});
  cd.advance(3e-4);
  const auto p1 = ring_momentum(chain, cd.y());
  const double scale = std::hypot(p0[0], p0[1]);
  EXPECT_GT(cd.statistics().steps, 500);
  EXPECT_NEAR(p1[0], p0[0], 1e-10 * scale);
  EXPECT_NEAR(p1[1], p0[1], 1e-10 * scale);
  // The ring did deform: of the ovalisation mode's ~0.38 J, the bars and hinges took up or
  // their dampers dissipated a good part.
  const auto e = chain.energies(cd.time(), cd.y().data());
  EXPECT_GT(e.elastic + e.damping + e.plastic, 0.05) << e.elastic << " " << e.damping << " " << e.plastic;
}

// The first 1.5 ms of two welded Test 30 rings struck at 27.7 m/s (ring 1 well into its
// collapse, the ties and the contacts loaded): the energy balance, booked as for IDA and
// Odeint (polygon_simulation.cpp), closes to 1e-3 of the impact energy — with the
// Kelvin–Voigt dampers implicit (the default; their work booked in the driver) and explicit.
TEST(PolygonCentralDifference, EnergyBalanceOnAnImpact) {
  const auto in = two_ring_chain::input(PolygonJoint::Welded);
  for (bool implicit : {true, false}) {
    PolygonRunOptions o;
    o.integrator = PolygonIntegrator::CentralDifference;
    o.central_difference_implicit_dampers = implicit;
    o.end_time_s = 1.5e-3;
    o.output_interval_s = 5e-5;
    const auto out = run_polygon_chain(in, o);
    EXPECT_LT(out.energy_balance_error, 1e-3) << "implicit " << implicit;
    EXPECT_GT(out.history.plastic_j.back(), 0.1 * out.initial_energy_j);
    EXPECT_GT(out.history.damping_j.back(), 1e-4 * out.initial_energy_j) << "implicit " << implicit;
    EXPECT_GT(out.min_step_s, 0.0);
    EXPECT_LE(out.max_step_s, 1e-6);  // 2/ω of a bar is 0.63 µs; explicit dampers shorten it
  }
}

// Against IDA at rtol 1e-6 on the same two rings (free and welded), 1.5 ms: crush per ring
// within 5e-3 D. The explicit step's error is O(Δt²) with Δt ≈ 0.2 µs, far below that; what
// differs is the treatment of the stiff parts (the flow by backward Euler, the dampers from
// the half-step velocity), each first order in Δt/τ on a few-µs transient.
TEST(PolygonCentralDifference, AgreesWithIdaOnTwoRings) {
  for (auto joint : {PolygonJoint::Free, PolygonJoint::Welded}) {
    const auto in = two_ring_chain::input(joint);
    const auto cd = run(in, PolygonIntegrator::CentralDifference, 1.5e-3);
    const auto ida = run(in, PolygonIntegrator::Ida, 1.5e-3);
    for (int r = 0; r < 2; ++r) {
      const double c_cd = two_ring_chain::crush(cd.history.shapes.back(), r, in) / in.outer_diameter_m;
      const double c_ida = two_ring_chain::crush(ida.history.shapes.back(), r, in) / in.outer_diameter_m;
      EXPECT_NEAR(c_cd, c_ida, 5e-3) << "joint " << static_cast<int>(joint) << " ring " << r + 1;
    }
    EXPECT_GT(two_ring_chain::crush(ida.history.shapes.back(), 0, in), 0.1 * in.outer_diameter_m);
  }
}

// A whole impact through the scene runner (compare/hinge_run_2d): Test 30's welded chain cut
// to three rings with half the impactor mass, run to rest on both integrators (IDA at
// rtol 1e-4): the same final crush ratio per ring to 5e-3, the same wrap flags, and the
// energy balance within 1e-3 on both.
TEST(PolygonCentralDifference, SameFlagsAsIdaOnAShortChain) {
  using namespace ringcrush::compare;
  Scene scene = load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/test30_welded.toml");
  scene.rings.count = 3;
  scene.impactor->mass_kg *= 0.5;
  HingeRunOptions o;
  o.level = "2";
  o.relative_tolerance = 1e-4;
  o.integrator = HingeIntegrator::Ida;
  const auto ida = run_level2(scene, o);
  o.integrator = HingeIntegrator::CentralDifference;
  const auto cd = run_level2(scene, o);
  ASSERT_EQ(cd.result.crush_ratio.size(), 3u);
  for (std::size_t r = 0; r < 3; ++r) {
    EXPECT_NEAR(cd.result.crush_ratio[r], ida.result.crush_ratio[r], 5e-3) << "ring " << r + 1;
    EXPECT_EQ(cd.result.wrap_around[r], ida.result.wrap_around[r]) << "ring " << r + 1;
  }
  EXPECT_GT(ida.result.crush_ratio[0], 0.3);
  EXPECT_LT(cd.raw.energy_balance_error, 1e-3);
  EXPECT_LT(ida.raw.energy_balance_error, 1e-3);
  EXPECT_EQ(cd.result.extra["integrator"], "central_difference");
}

TEST(PolygonCentralDifference, RejectsBadSafety) {
  PolygonChain chain(two_ring_chain::input(PolygonJoint::Free));
  for (double s : {0.0, -0.5, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    CentralDifferenceOptions o;
    o.safety = s;
    try {
      PolygonCentralDifference cd(chain, 0.0, chain.initial_state(), o);
      ADD_FAILURE() << "safety " << s << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("safety"), std::string::npos) << e.what();
    }
  }
}

// `[hinge] integrator = "central_difference"` is Level 2 only: another level is an error in
// the scene, and a runner of another level refuses it.
TEST(PolygonCentralDifference, SceneWiring) {
  using namespace ringcrush::compare;
  const std::string path = std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/test30_welded.toml";
  Scene scene = load_scene(path);
  EXPECT_EQ(scene.hinge.integrator, HingeIntegrator::Ida);
  std::ifstream file(path);
  std::stringstream buffer;
  buffer << file.rdbuf();
  std::string text = buffer.str();
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("level = 2 ", "level = 1 ");
  replace("integrator = \"ida\"", "integrator = \"central_difference\"");
  try {
    parse_scene(text, "inline.toml");
    ADD_FAILURE() << "level 1 with central_difference accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("central_difference"), std::string::npos) << e.what();
  }
  HingeRunOptions o;
  o.level = "1";
  o.integrator = HingeIntegrator::CentralDifference;
  EXPECT_THROW(run_hinge_level1(scene, o), std::invalid_argument);
}
