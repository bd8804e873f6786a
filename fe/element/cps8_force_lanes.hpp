// The force-only CPS8 kernel on four elements at once (issue 4 performance, README
// "Performance"): one vector lane per element, each lane doing exactly the operations of
// cps8_force() (cps8_force.cpp) in the same order, so that every bit of every result —
// force, bulk-viscous force, energies, trial states — is that of cps8_force() on the element
// alone (tests/fe/cps8_force_lanes_test.cpp). The explicit step is the same physics, only
// four elements share each instruction.
//
// Why across elements: within one element the kernel is a chain of dependent sums (the 8
// nodes of f, the 9 points of the force) that keeps 2-wide operations at best; four elements
// are independent, so every operation of the kernel is 4-wide with no rearrangement.
//
// Points whose trial stress reaches the yield surface take the scalar return mapping
// (J2PlaneStress::update_stress) lane by lane; the elastic trial, the common case, is
// vectorised.
//
// Instruction sets: three copies are compiled from one template on the width — portable (the
// 4-wide operations as two SSE2 halves), AVX2 WITHOUT fused multiply–add (which would round
// differently), and AVX-512 on eight elements a group (contraction off; the groups of eight
// below) — and cps8_force_lanes() takes the AVX2 copy where the CPU has it, else cps8_force()
// element by element (the portable copy measured slower than that; README "Performance",
// session 8), so one binary gives the same bits on every x86-64.
#pragma once

#include <array>

#include "fe/element/cps8_element.hpp"
#include "fe/element/cps8_rule_tables.hpp"

namespace ringcrush::fe {

constexpr int kCps8Lanes = 4;
constexpr int kCps8WideLanes = 8;  // AVX-512

// One element of a lane group: the arguments of cps8_force().
struct Cps8Lane {
  const Cps8Geometry* geo = nullptr;
  const double* du = nullptr;  // 16 displacement increments
  const PointState* committed = nullptr;
  PointState* trial = nullptr;
  Cps8Output* out = nullptr;
  const BulkViscousLoad* viscous = nullptr;  // all four set or all four null
};
template <int W>
using Cps8LaneGroupOf = std::array<Cps8Lane, W>;
using Cps8LaneGroup = Cps8LaneGroupOf<kCps8Lanes>;
using Cps8WideLaneGroup = Cps8LaneGroupOf<kCps8WideLanes>;

// cps8_force() on four elements of one integration rule. Throws std::invalid_argument if the
// lanes mix rules or mix bulk viscosity on and off.
void cps8_force_lanes(const Cps8LaneGroup& group, const J2PlaneStress& material);

// cps8_force_lanes() on the elements' geometry on x_n formed inside the kernel from their node
// coordinates x_n (bitwise what Cps8GeometryUpdater::update(x_n, thickness, geo) would store;
// tables: the updater's, cps8_rule_tables(rule)) instead of read from each lane's geo, whose
// ∂N/∂x and weights are neither read nor written (its rule, point count and Barlow matrix are
// used). The explicit step re-derives every element's geometry once per step: formed here it
// is not stored to the element's 2.6 kB Cps8Geometry and read back (README, session 9).
// Returns false, having written nothing, when the lanes cannot do it bitwise
// (!cps8_force_lanes_forms_geometry()) or an element is inverted or degenerate at x_n: the
// caller then updates the stored geometry (which reports the element) and calls
// cps8_force_lanes(). Throws std::invalid_argument as cps8_force_lanes(), or if tables is for
// another rule.
bool cps8_force_lanes_on_coords(const Cps8LaneGroup& group, const Cps8RuleTables& tables,
                                const std::array<const ElementCoords*, kCps8Lanes>& x_n, double thickness,
                                const J2PlaneStress& material);
// Whether cps8_force_lanes_on_coords() runs on this CPU and build (AVX2, no FMA, an Eigen
// dot-product tree the lanes reproduce).
bool cps8_force_lanes_forms_geometry();

// The two compiled copies (tests: both must be bitwise cps8_force()); the AVX2 one only where
// cps8_lanes_avx2_available().
void cps8_force_lanes_portable(const Cps8LaneGroup& group, const J2PlaneStress& material);
void cps8_force_lanes_avx2(const Cps8LaneGroup& group, const J2PlaneStress& material);
bool cps8_lanes_avx2_available();
// False in a build with fused multiply–add (RINGCRUSH_NATIVE on an FMA CPU): Eigen then fuses
// the scalar kernel's 2×2 products into their sums and the lanes (which never fuse) would round
// differently, so cps8_force_lanes() goes element by element there.
bool cps8_lanes_bitwise_build();

// Eight elements a group (AVX-512: 8 doubles a vector): the same kernel, lane l of the 8-wide
// vector doing on element l exactly what lane l of the 4-wide one does, so every result is
// bitwise that of the 4-lane kernel and of cps8_force(). AVX-512 without FMA contraction
// (avx512f would let GCC fuse a product into its sum; the copy is compiled with contraction
// off). cps8_force_wide_lanes_available(): AVX-512F on this CPU, a bitwise build and the Eigen
// dot-product tree the lanes reproduce; elsewhere the callers use groups of four, and these
// functions fall back: cps8_force_lanes() on two groups of four, ..._on_coords() returns false.
bool cps8_force_wide_lanes_available();
void cps8_force_lanes(const Cps8WideLaneGroup& group, const J2PlaneStress& material);
bool cps8_force_lanes_on_coords(const Cps8WideLaneGroup& group, const Cps8RuleTables& tables,
                                const std::array<const ElementCoords*, kCps8WideLanes>& x_n, double thickness,
                                const J2PlaneStress& material);
// The compiled AVX-512 copy (tests), only where cps8_lanes_avx512_available().
void cps8_force_lanes_avx512(const Cps8WideLaneGroup& group, const J2PlaneStress& material);
bool cps8_lanes_avx512_available();

}  // namespace ringcrush::fe
