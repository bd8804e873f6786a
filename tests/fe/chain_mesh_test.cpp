// The chain mesh (issue 4 item 1; seed/thesis_dynamic.inp): welded rings share exactly one
// node per joint (the deck's *MPC 501–1597 ties ring i's bottom outer node to ring i+1's top
// outer node), free rings share none, plates add one rigid-body node each at the right
// height; outer nodes are ordered by θ from the top apex; the x = 0 symmetry and the rigid
// bodies' x dofs are fixed; inconsistent inputs are named errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fe/chain/chain_mesh.hpp"

using namespace ringcrush::fe;

namespace {
ChainInput chain(int rings, JointKind joints, bool half = true) {
  ChainInput in;
  in.rings = rings;
  in.mesh.elements_around = 8;
  in.mesh.half_ring = half;
  in.joints = joints;
  in.pitch_m = 2 * in.ring.outer_radius_m;
  if (joints == JointKind::Plates) {
    in.plate_thickness_m = 0.003;
    in.plate_mass_kg = 0.05;
    in.pitch_m += in.plate_thickness_m;
  }
  return in;
}
std::string error_of(const ChainInput& in) {
  try {
    make_chain_topology(in);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ChainMesh, WeldedRingsShareOneNodePerJoint) {
  for (bool half : {true, false}) {
    const auto t = make_chain_topology(chain(4, JointKind::Welded, half));
    const int ring_nodes = static_cast<int>(t.ring.nodes.size());
    EXPECT_EQ(static_cast<int>(t.mesh.nodes.size()), 4 * ring_nodes - 3 + 1);
    EXPECT_EQ(t.mesh.elements.size(), 4 * t.ring.elements.size());
    for (int i = 0; i + 1 < 4; ++i) {
      const int shared = t.ring_node[i][t.ring.bottom_node];
      EXPECT_EQ(t.ring_node[i + 1][t.ring.top_node], shared);
      EXPECT_NEAR(t.mesh.nodes[shared].y(), -i * 2 * 25.4e-3 - 25.4e-3, 1e-15);
      EXPECT_NEAR(t.mesh.nodes[shared].x(), 0.0, 1e-15);
    }
    // No other node is shared.
    std::vector<int> uses(t.mesh.nodes.size(), 0);
    for (const auto& map : t.ring_node)
      for (int g : map) ++uses[g];
    int shared = 0;
    for (int u : uses) shared += u > 1;
    EXPECT_EQ(shared, 3);
  }
}

TEST(ChainMesh, FreeAndPlatedChains) {
  const auto f = make_chain_topology(chain(3, JointKind::Free));
  EXPECT_EQ(f.mesh.nodes.size(), 3 * f.ring.nodes.size() + 1);
  EXPECT_TRUE(f.mesh.plate_nodes.empty());
  const ChainInput pin = chain(3, JointKind::Plates);
  const auto p = make_chain_topology(pin);
  EXPECT_EQ(p.mesh.nodes.size(), 3 * p.ring.nodes.size() + 1 + 2);
  ASSERT_EQ(p.mesh.plate_nodes.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    // Plate k's faces touch ring k's bottom and ring k+1's top.
    const double yc = p.mesh.nodes[p.mesh.plate_nodes[k]].y();
    EXPECT_NEAR(yc + p.plate_half_thickness, p.mesh.ring_centre_y[k] - 25.4e-3, 1e-15);
    EXPECT_NEAR(yc - p.plate_half_thickness, p.mesh.ring_centre_y[k + 1] + 25.4e-3, 1e-12);
  }
  EXPECT_NEAR(p.target_y, -2 * pin.pitch_m - 25.4e-3, 1e-15);
  // Rigid bodies: x fixed, y free.
  for (int n : p.mesh.plate_nodes) {
    EXPECT_TRUE(std::binary_search(p.fixed_dofs.begin(), p.fixed_dofs.end(), 2 * n));
    EXPECT_FALSE(std::binary_search(p.fixed_dofs.begin(), p.fixed_dofs.end(), 2 * n + 1));
  }
  EXPECT_TRUE(std::binary_search(p.fixed_dofs.begin(), p.fixed_dofs.end(), 2 * p.mesh.impactor_node));
  EXPECT_NEAR(p.mesh.nodes[p.mesh.impactor_node].y(), 25.4e-3, 1e-15);
}

TEST(ChainMesh, SymmetryPlaneNodesHaveTheirXFixed) {
  const auto t = make_chain_topology(chain(2, JointKind::Welded));
  int on_axis = 0;
  for (std::size_t n = 0; n < t.mesh.nodes.size(); ++n) {
    const bool fixed = std::binary_search(t.fixed_dofs.begin(), t.fixed_dofs.end(), static_cast<int>(2 * n));
    if (static_cast<int>(n) == t.mesh.impactor_node) continue;
    EXPECT_EQ(fixed, std::abs(t.mesh.nodes[n].x()) < 1e-15) << "node " << n;
    on_axis += fixed;
  }
  // 3 nodes through the wall at the top and bottom of each ring, one of them shared.
  EXPECT_EQ(on_axis, 2 * 6 - 1);
}

TEST(ChainMesh, OuterNodesRunFromTheTopApex) {
  for (bool half : {true, false}) {
    const auto t = make_chain_topology(chain(2, JointKind::Free, half));
    const double pi = std::numbers::pi, r = 25.4e-3;
    for (int i = 0; i < 2; ++i) {
      const auto& ids = t.mesh.ring_outer_nodes[i];
      const auto& th = t.mesh.ring_outer_theta[i];
      ASSERT_EQ(ids.size(), th.size());
      ASSERT_EQ(static_cast<int>(ids.size()), half ? 17 : 32);
      EXPECT_NEAR(th.front(), 0.0, 1e-12);
      for (std::size_t k = 0; k < ids.size(); ++k) {
        if (k > 0) {
          EXPECT_GT(th[k], th[k - 1]);
        }
        // θ from the top: x = R sin θ, y = y_c + R cos θ.
        const auto& p = t.mesh.nodes[ids[k]];
        EXPECT_NEAR(p.x(), r * std::sin(th[k]), 1e-12);
        EXPECT_NEAR(p.y(), t.mesh.ring_centre_y[i] + r * std::cos(th[k]), 1e-12);
      }
      EXPECT_NEAR(th.back(), half ? pi : 2 * pi - pi / 16, 1e-12);
    }
  }
}

TEST(ChainMesh, BadInputsAreNamedErrors) {
  auto in = chain(3, JointKind::Welded);
  in.pitch_m = 0.06;
  EXPECT_NE(error_of(in).find("welded joints need pitch"), std::string::npos) << error_of(in);
  in = chain(3, JointKind::Free);
  in.pitch_m = 0.04;
  EXPECT_NE(error_of(in).find("free joints need pitch"), std::string::npos);
  in = chain(0, JointKind::Welded);
  EXPECT_NE(error_of(in).find("rings must be >= 1"), std::string::npos);
  in = chain(3, JointKind::Welded);
  in.impactor_mass_kg = 0;
  EXPECT_NE(error_of(in).find("impactor mass"), std::string::npos);
  in = chain(3, JointKind::Welded);
  in.density_kg_m3 = -1;
  EXPECT_NE(error_of(in).find("density"), std::string::npos);
  in = chain(3, JointKind::Plates);
  in.plate_mass_kg = 0;
  EXPECT_NE(error_of(in).find("plate mass"), std::string::npos);
  in = chain(3, JointKind::Plates);
  in.plate_thickness_m = 0;
  EXPECT_NE(error_of(in).find("plate thickness"), std::string::npos);
  in = chain(3, JointKind::Plates);
  in.pitch_m = 2 * 25.4e-3;
  EXPECT_NE(error_of(in).find("plates joints need pitch"), std::string::npos);
  in = chain(3, JointKind::Welded);
  in.impactor_velocity_m_s = std::nan("");
  EXPECT_NE(error_of(in).find("impactor velocity"), std::string::npos);
  in = chain(3, JointKind::Welded);
  in.mesh.elements_around = 7;
  EXPECT_NE(error_of(in).find("elements_around"), std::string::npos);
}
