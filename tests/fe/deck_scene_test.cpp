// The thesis decks turned into ringcrush parameters and scenes (issue 5 item 2) agree with
// the hand-written TOML equivalents data/scenes/thesis_static.toml and thesis_dynamic.toml:
// radii, element counts, material, impactor mass and velocity, solver controls.
#include <gtest/gtest.h>

#include <numbers>

#include "compare/deck_scene.hpp"
#include "compare/scene.hpp"
#include "fe/deck/deck_parameters.hpp"
#include "fe/deck/deck_reader.hpp"

namespace fd = ringcrush::fe::deck;
namespace rc = ringcrush::compare;

namespace {
const std::string root = RINGCRUSH_SOURCE_DIR;

void expect_same_rings(const rc::Scene& deck, const rc::Scene& toml) {
  EXPECT_EQ(deck.rings.count, toml.rings.count);
  EXPECT_NEAR(deck.rings.outer_diameter_m, toml.rings.outer_diameter_m, 1e-12);
  EXPECT_NEAR(deck.rings.wall_thickness_m, toml.rings.wall_thickness_m, 1e-12);
  EXPECT_EQ(deck.rings.width_m, toml.rings.width_m);
  EXPECT_NEAR(deck.rings.pitch_m, toml.rings.pitch_m, 1e-12);
  EXPECT_EQ(deck.rings.material.youngs_modulus_pa, toml.rings.material.youngs_modulus_pa);
  EXPECT_EQ(deck.rings.material.poisson_ratio, toml.rings.material.poisson_ratio);
  ASSERT_EQ(deck.rings.material.hardening.size(), toml.rings.material.hardening.size());
  for (std::size_t k = 0; k < deck.rings.material.hardening.size(); ++k) {
    EXPECT_EQ(deck.rings.material.hardening[k].yield_stress_pa, toml.rings.material.hardening[k].yield_stress_pa);
    EXPECT_EQ(deck.rings.material.hardening[k].plastic_strain, toml.rings.material.hardening[k].plastic_strain);
  }
  EXPECT_EQ(deck.analysis.type, toml.analysis.type);
  EXPECT_EQ(deck.analysis.symmetry, toml.analysis.symmetry);
  EXPECT_EQ(deck.far_end, toml.far_end);
  EXPECT_EQ(deck.fe.elements_around, toml.fe.elements_around);
  EXPECT_EQ(deck.fe.elements_through, toml.fe.elements_through);
  EXPECT_NEAR(deck.fe.grading, toml.fe.grading, 1e-9);
  EXPECT_EQ(deck.fe.solver, toml.fe.solver);
  EXPECT_EQ(deck.fe.ptol_n, toml.fe.ptol_n);
}
}  // namespace

TEST(DeckParameters, StaticDeckReadsOffTheRing) {
  const fd::DeckParameters p = fd::deck_parameters(fd::load_deck(root + "/data/thesis/thesis_static.inp"));
  ASSERT_EQ(p.rings.size(), 1u);  // two quarters around one centre, tied by 3 MPCs
  EXPECT_NEAR(p.rings[0].centre[0], 0.0, 1e-15);
  EXPECT_NEAR(p.rings[0].centre[1], 0.0, 1e-15);
  EXPECT_NEAR(p.inner_radius_m, 23.8e-3, 1e-9 * 23.8e-3);
  EXPECT_NEAR(p.outer_radius_m, 25.4e-3, 1e-9 * 25.4e-3);
  EXPECT_TRUE(p.half_model);
  EXPECT_EQ(p.internal_ties, 3);
  EXPECT_EQ(p.ring_ties, 0);
  EXPECT_NEAR(p.grading, 2.0, 1e-9);  // 11.25° elements mid-quarter, 5.625° at the ends
  EXPECT_EQ(p.crush_m, 46e-3);
  EXPECT_TRUE(p.fixed_target);
  EXPECT_EQ(*p.contact_smoothing, 0.25);
  EXPECT_EQ(p.initial_increment, 0.001);
  // The deck's block grading per quarter: 3 × 5.625°, 5 × 11.25°, 3 × 5.625°, twice.
  ASSERT_EQ(p.boundary_angles.size(), 23u);
  const double deg = std::numbers::pi / 180;
  const double steps[11] = {5.625, 5.625, 5.625, 11.25, 11.25, 11.25, 11.25, 11.25, 5.625, 5.625, 5.625};
  double phi = 0;
  for (int k = 0; k < 22; ++k) {
    EXPECT_NEAR(p.boundary_angles[static_cast<std::size_t>(k)], phi * deg, 1e-12) << k;
    phi += steps[k % 11];
  }
  EXPECT_NEAR(p.boundary_angles.back(), std::numbers::pi, 1e-12);
}

TEST(DeckParameters, DynamicDeckReadsOffTheChain) {
  const fd::DeckParameters p = fd::deck_parameters(fd::load_deck(root + "/data/thesis/thesis_dynamic.inp"));
  ASSERT_EQ(p.rings.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(p.rings[k].centre[1], -50.8e-3 * static_cast<double>(k), 1e-12);
  EXPECT_NEAR(p.pitch_m, 50.8e-3, 1e-12);
  EXPECT_TRUE(p.welded);
  EXPECT_EQ(p.ring_ties, 5);
  EXPECT_EQ(*p.impactor_mass_kg, 0.256);  // 2 × 0.128 kg of the half model
  EXPECT_EQ(*p.impactor_velocity_m_s, 30.0);
  EXPECT_EQ(*p.hht_alpha, -0.105);
  EXPECT_EQ(*p.softened_clearance_m, 5e-6);
  EXPECT_EQ(*p.contact_smoothing, 0.24);
  EXPECT_NEAR(p.grading, 1.0, 1e-9);
}

TEST(DeckScene, StaticDeckMatchesTheTomlScene) {
  const rc::Scene deck = rc::scene_from_deck(root + "/data/thesis/thesis_static.inp");
  const rc::Scene toml = rc::load_scene(root + "/data/scenes/thesis_static.toml");
  expect_same_rings(deck, toml);
  EXPECT_EQ(deck.analysis.crush_m, toml.analysis.crush_m);
  EXPECT_EQ(deck.fe.initial_increment, toml.fe.initial_increment);
  EXPECT_EQ(deck.fe.min_increment, toml.fe.min_increment);
  EXPECT_EQ(deck.fe.max_increment, toml.fe.max_increment);
  EXPECT_EQ(deck.fe.max_iterations, toml.fe.max_iterations);
  EXPECT_EQ(deck.fe.contact_smoothing, toml.fe.contact_smoothing);
}

TEST(DeckScene, DynamicDeckMatchesTheTomlScene) {
  const rc::Scene deck = rc::scene_from_deck(root + "/data/thesis/thesis_dynamic.inp");
  const rc::Scene toml = rc::load_scene(root + "/data/scenes/thesis_dynamic.toml");
  expect_same_rings(deck, toml);
  EXPECT_EQ(deck.rings.material.density_kg_m3, toml.rings.material.density_kg_m3);
  EXPECT_EQ(deck.joints.type, toml.joints.type);
  ASSERT_TRUE(deck.impactor && toml.impactor);
  EXPECT_EQ(deck.impactor->mass_kg, toml.impactor->mass_kg);
  EXPECT_EQ(deck.impactor->velocity_m_s, toml.impactor->velocity_m_s);
  EXPECT_EQ(deck.analysis.end_time_s, toml.analysis.end_time_s);
  EXPECT_EQ(deck.fe.hht_alpha, toml.fe.hht_alpha);
  EXPECT_EQ(deck.fe.initial_step_s, toml.fe.initial_step_s);
  EXPECT_EQ(deck.fe.haftol_n, toml.fe.haftol_n);
}

TEST(DeckScene, DeckThatIsNotARingChainIsRefused) {
  // A single square CPS8 element has straight edges all round: no ring centre.
  const std::string quad =
      "*NODE\n1,0.,0.\n2,1.,0.\n3,1.,1.\n4,0.,1.\n5,.5,0.\n6,1.,.5\n7,.5,1.\n8,0.,.5\n"
      "*ELEMENT,TYPE=CPS8,ELSET=E\n1,1,2,3,4,5,6,7,8\n*SOLID SECTION,ELSET=E,MATERIAL=S\n1.\n"
      "*MATERIAL,NAME=S\n*ELASTIC\n2.E11,.3\n";
  EXPECT_THROW(fd::deck_parameters(fd::read_deck(quad)), std::invalid_argument);
}

TEST(DeckScene, ElementWithAllCornersOnOneRadiusIsRefusedNotDividedByZero) {
  // Radial edges 1–2 and 3–4 meet at the origin, but all four corners lie at radius 1: zero
  // elements through the wall (a division by zero before the guard in deck_parameters).
  const std::string flat =
      "*NODE\n1,1.,0.\n2,-1.,0.\n3,0.,1.\n4,0.,-1.\n5,1.E-9,1.E-9\n6,-0.5,0.8\n7,1.E-9,-1.E-9\n8,0.5,-0.8\n"
      "*ELEMENT,TYPE=CPS8,ELSET=E\n1,1,2,3,4,5,6,7,8\n*SOLID SECTION,ELSET=E,MATERIAL=S\n1.\n"
      "*MATERIAL,NAME=S\n*ELASTIC\n2.E11,.3\n*STEP\n*STATIC\n1.,1.\n*END STEP\n";
  try {
    fd::deck_parameters(fd::read_deck(flat));
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no wall"), std::string::npos) << e.what();
  }
}
