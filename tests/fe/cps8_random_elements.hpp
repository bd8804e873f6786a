// Random distorted CPS8 elements and point states for the force-kernel tests (equivalence of
// the force-only path with the reference path, and its timing). Sizes and stresses are those
// of the thesis rings (§3.6.1: 1.6 mm wall, 48 elements per half ring, 202 GPa steel).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "fe/element/cps8_element.hpp"
#include "fe/element/cps8_shape.hpp"

namespace ringcrush::fe::kernel_test {

inline MaterialInput thesis_steel() {
  MaterialInput m;
  m.youngs_modulus_pa = 202e9;
  m.poisson_ratio = 0.3;
  m.hardening = {{273e6, 0.0}, {320e6, 0.02113}};
  return m;
}

// One element with its state: reference coordinates, displacement increment, committed states.
struct RandomElement {
  ElementCoords x;
  double du[16];
  std::vector<PointState> committed;
};

// `strain` sets the size of the strain increment (1e-4: elastic steps of an explicit run;
// 1e-2: increments that yield); `near_yield` puts the committed stresses just below yield,
// with a random PEEQ on either hardening segment.
inline RandomElement random_element(std::mt19937& rng, double strain, bool near_yield) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RandomElement r;
  const double hx = 1.7e-3, hy = 0.8e-3;  // half sizes: a 3.3 mm × 1.6 mm ring element
  for (;;) {
    for (int a = 0; a < 8; ++a) {
      r.x(a, 0) = hx * (cps8_node_coords[a][0] + 0.2 * u(rng)) + 0.02;
      r.x(a, 1) = hy * (cps8_node_coords[a][1] + 0.2 * u(rng)) - 0.01;
    }
    // Accept only elements with det J > 0 at every point.
    try {
      (void)cps8_geometry(r.x, Integration::Full, 0.0125);
      break;
    } catch (const std::invalid_argument&) {
    }
  }
  // Δu = (R − I)(x − x₀) + random: a finite rotation plus a strain of size `strain`.
  const double angle = 0.05 * u(rng), c = std::cos(angle) - 1.0, s = std::sin(angle);
  for (int a = 0; a < 8; ++a) {
    const double dx = r.x(a, 0) - 0.02, dy = r.x(a, 1) + 0.01;
    r.du[2 * a] = c * dx - s * dy + strain * hx * u(rng);
    r.du[2 * a + 1] = s * dx + c * dy + strain * hy * u(rng);
  }
  r.committed.resize(9);
  for (auto& p : r.committed) {
    const double level = near_yield ? 0.97 : 0.5;
    p.peeq = near_yield ? 0.04 * std::abs(u(rng)) : 0.0;
    // A random direction in stress space scaled to `level` of the yield stress (Mises).
    Vec3 dir(u(rng), u(rng), 0.5 * u(rng));
    const double sy = p.peeq < 0.02113 ? 273e6 + (320e6 - 273e6) * p.peeq / 0.02113 : 320e6;
    p.stress = dir * (level * sy / mises(dir));
    p.plastic_strain = Vec3(u(rng), u(rng), u(rng)) * p.peeq;
    p.plastic_work = 1e6 * p.peeq * std::abs(u(rng));
    p.thickness_stretch = 1.0 + 0.01 * u(rng);
  }
  return r;
}

// One element's kernel results: force, bulk-viscous force, energies and the trial states.
struct ElementResult {
  Cps8Output out;
  ElementVector viscous = ElementVector::Zero();
  std::array<PointState, 9> trial{};
};

// The lane kernels must reproduce the scalar kernel bit for bit: every output and every
// trial-state value of the first `points` points.
inline void expect_bitwise_equal(const ElementResult& a, const ElementResult& b, int points) {
  EXPECT_EQ(a.out.force, b.out.force);
  EXPECT_EQ(a.viscous, b.viscous);
  EXPECT_EQ(a.out.elastic_energy, b.out.elastic_energy);
  EXPECT_EQ(a.out.plastic_work, b.out.plastic_work);
  for (int i = 0; i < points; ++i) {
    SCOPED_TRACE(::testing::Message() << "point " << i);
    const PointState &p = a.trial[static_cast<std::size_t>(i)], &q = b.trial[static_cast<std::size_t>(i)];
    EXPECT_EQ(p.stress, q.stress);
    EXPECT_EQ(p.plastic_strain, q.plastic_strain);
    EXPECT_EQ(p.peeq, q.peeq);
    EXPECT_EQ(p.plastic_work, q.plastic_work);
    EXPECT_EQ(p.thickness_stretch, q.thickness_stretch);
  }
}

}  // namespace ringcrush::fe::kernel_test
