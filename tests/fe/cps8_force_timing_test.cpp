// Timing of the CPS8 internal-force kernel (DESIGN.md "Performance"): ns per element call,
// force only (the explicit driver's path) and with the tangent, for each integration rule,
// elastic and yielding states, and the per-commit geometry update. PRINTS the numbers
// (thread CPU time, CLOCK_THREAD_CPUTIME_ID, and wall time: the machine is shared) and
// asserts only that the timed calls produced finite forces equal to the reference path's —
// timings are not asserted (machines differ).
#include <gtest/gtest.h>
#include <time.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <random>

#include "cps8_random_elements.hpp"
#include "fe/chain/geometry_update.hpp"
#include "fe/element/cps8_force_lanes.hpp"

using namespace ringcrush::fe;

namespace {

double thread_cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e9 * static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec);
}
double wall_ns() {
  return static_cast<double>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count());
}

const char* name(Integration r) {
  return r == Integration::Full ? "full 3x3" : r == Integration::Reduced ? "reduced 2x2" : "selective";
}

}  // namespace

TEST(Cps8ForceTiming, NanosecondsPerElementCall) {
  const J2PlaneStress material(kernel_test::thesis_steel());
  constexpr int kElements = 64, kSweeps = 300;
  for (const Integration rule : {Integration::Reduced, Integration::Selective, Integration::Full}) {
    for (const bool yielding : {false, true}) {
      std::mt19937 rng(7);
      std::vector<kernel_test::RandomElement> els;
      std::vector<Cps8Geometry> geos;
      for (int e = 0; e < kElements; ++e) {
        els.push_back(kernel_test::random_element(rng, yielding ? 1e-2 : 1e-4, yielding));
        geos.push_back(cps8_geometry(els.back().x, rule, 0.0125));
      }
      std::vector<PointState> trial(9);
      Cps8Output out, ref;
      double check = 0;
      for (const bool tangent : {false, true}) {
        const double c0 = thread_cpu_ns(), w0 = wall_ns();
        for (int s = 0; s < kSweeps; ++s)
          for (int e = 0; e < kElements; ++e) {
            cps8_evaluate(geos[e], els[e].du, els[e].committed.data(), trial.data(), material, tangent, out);
            check += out.force(3);
          }
        const double n = double(kSweeps) * kElements;
        std::printf("cps8_evaluate %-12s %-8s %-13s cpu %7.0f ns  wall %7.0f ns per call\n", name(rule),
                    yielding ? "yielding" : "elastic", tangent ? "force+tangent" : "force only",
                    (thread_cpu_ns() - c0) / n, (wall_ns() - w0) / n);
      }
      EXPECT_TRUE(std::isfinite(check));
      // The last element's force-only result equals the reference (tangent) path's.
      cps8_evaluate(geos.back(), els.back().du, els.back().committed.data(), trial.data(), material, false, out);
      cps8_evaluate(geos.back(), els.back().du, els.back().committed.data(), trial.data(), material, true, ref);
      EXPECT_LE((out.force - ref.force).norm(), 1e-12 * ref.force.norm()) << name(rule);
    }
    // Geometry update at commit (every explicit step).
    std::mt19937 rng(11);
    const auto el = kernel_test::random_element(rng, 1e-4, false);
    Cps8Geometry geo = cps8_geometry(el.x, rule, 0.0125);
    const Cps8GeometryUpdater updater(rule);
    ElementCoords x = el.x;
    constexpr int kCalls = 20000;
    const double c0 = thread_cpu_ns(), w0 = wall_ns();
    for (int k = 0; k < kCalls; ++k) {
      x(k % 8, 0) += 1e-12;
      updater.update(x, 0.0125, geo);
    }
    std::printf("geometry update %-12s cpu %7.0f ns  wall %7.0f ns per call\n", name(rule),
                (thread_cpu_ns() - c0) / kCalls, (wall_ns() - w0) / kCalls);
    EXPECT_GT(geo.weight[0], 0.0);
  }
}

// The explicit pass's per-element work — geometry re-derived on x_n, then the force-only
// kernel with bulk viscosity — element by element against four elements on vector lanes
// (Cps8GeometryUpdater::update_lanes, cps8_force_lanes; README "Performance", session 8).
// PRINTS thread CPU ns per element for both; asserts the two give the same forces bitwise.
TEST(Cps8ForceTiming, LanesAgainstElementByElement) {
  const J2PlaneStress material(kernel_test::thesis_steel());
  constexpr int kElements = 64, kSweeps = 300;
  const Integration rule = Integration::Selective;
  const Cps8GeometryUpdater updater(rule);
  std::mt19937 rng(7);
  std::vector<kernel_test::RandomElement> els;
  std::vector<Cps8Geometry> geo_one, geo_lanes;
  for (int e = 0; e < kElements; ++e) {
    els.push_back(kernel_test::random_element(rng, 1e-4, false));
    geo_one.push_back(cps8_geometry(els.back().x, rule, 0.0125));
  }
  geo_lanes = geo_one;
  std::vector<std::array<PointState, 9>> trial_one(kElements), trial_lanes(kElements);
  std::vector<Cps8Output> out_one(kElements), out_lanes(kElements);
  std::vector<ElementVector> visc_one(kElements), visc_lanes(kElements);
  std::vector<BulkViscousLoad> load_one(kElements), load_lanes(kElements);
  for (int e = 0; e < kElements; ++e) {
    load_one[e] = BulkViscousLoad{3.7e3, 5e-8, &visc_one[e]};
    load_lanes[e] = BulkViscousLoad{3.7e3, 5e-8, &visc_lanes[e]};
  }
  const double c0 = thread_cpu_ns();
  for (int s = 0; s < kSweeps; ++s)
    for (int e = 0; e < kElements; ++e) {
      updater.update(els[e].x, 0.0125, geo_one[e]);
      visc_one[e].setZero();
      cps8_force(geo_one[e], els[e].du, els[e].committed.data(), trial_one[e].data(), material, out_one[e],
                 &load_one[e]);
    }
  const double c1 = thread_cpu_ns();
  for (int s = 0; s < kSweeps; ++s)
    for (int e = 0; e < kElements; e += kCps8Lanes) {
      updater.update_lanes({&els[e].x, &els[e + 1].x, &els[e + 2].x, &els[e + 3].x}, 0.0125,
                           {&geo_lanes[e], &geo_lanes[e + 1], &geo_lanes[e + 2], &geo_lanes[e + 3]});
      Cps8LaneGroup group;
      for (int l = 0; l < kCps8Lanes; ++l) {
        visc_lanes[e + l].setZero();
        group[l] = Cps8Lane{&geo_lanes[e + l], els[e + l].du, els[e + l].committed.data(), trial_lanes[e + l].data(),
                            &out_lanes[e + l], &load_lanes[e + l]};
      }
      cps8_force_lanes(group, material);
    }
  const double c2 = thread_cpu_ns(), n = double(kSweeps) * kElements;
  std::printf("selective elastic, geometry + force + bulk viscosity: element by element cpu %5.0f ns, "
              "lanes (%s) cpu %5.0f ns per element\n",
              (c1 - c0) / n, cps8_lanes_avx2_available() && cps8_lanes_bitwise_build() ? "AVX2" : "element by element",
              (c2 - c1) / n);
  for (int e = 0; e < kElements; ++e) {
    EXPECT_EQ(out_lanes[e].force, out_one[e].force);
    EXPECT_EQ(visc_lanes[e], visc_one[e]);
  }
}
