// cps8_force() on four or eight elements at once, one vector lane per element
// (cps8_force_lanes.hpp): one template on the width W, lane l of either width doing the same
// operations on element l.
//
// Every line below is a line of cps8_force() (cps8_force.cpp) and of the inline pieces it
// calls — deformation_gradient() and green_lagrange() (kinematics.hpp), the elastic branch of
// J2PlaneStress::update_stress() (j2_plane_stress.hpp), point_stress() (cps8_element.hpp),
// cauchy_from_pk2() — written on lanes with each sum in the same order and no product fused
// into an addition, so that each lane rounds exactly as the scalar kernel does on its element
// (IEEE arithmetic is lane by lane). The parenthesised forms in the comments are the scalar
// kernel's evaluation order. Selective rule: thesis §3.6.1.4; push-forward: §3.6.1.2.
#include "fe/element/cps8_force_lanes.hpp"

#include "fe/element/element_lanes.hpp"
#include "fe/element/geometry_lanes.hpp"
#include "fe/element/hardening_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <type_traits>
#include <stdexcept>

namespace ringcrush::fe {

namespace {

using namespace lanes;

constexpr int kMaxPoints = 13;  // 9 stress points + 4 reduced (Barlow) points

// The group's element data as lanes (structure of arrays): ∂N_a/∂X_j at every point, weights,
// Barlow matrices and displacement increments, each gathered once from the W elements.
template <class V>
struct GroupInput {
  V d[kMaxPoints][8][2];
  V weight[9], barlow[9][4];
  V u[8][2];
  V coefficient{}, dt{};  // bulk viscosity (zero when off)
};

// Per stress point, what the push-forward and the trial states need after the force pass.
template <class V>
struct PointLanes {
  V f00, f01, f10, f11;  // f
  V s0, s1, s2;          // S (the material's stress of the increment)
  V stretch;             // 1 + 2 ΔE33
  V history[5];          // trial plastic strain (3), ᾱ, plastic work: PointState's members 3 … 7
  V thickness;           // committed λ3
};

// A point state read and written as doubles (9 of them, in member order), four at a time:
// from 0 the stress and the first plastic strain, from 4 the last two plastic strains, ᾱ and
// the plastic work, from 5 the last plastic strain, ᾱ, the plastic work and λ3.
static_assert(std::is_standard_layout_v<PointState> && sizeof(PointState) == 9 * sizeof(double));
constexpr int kStressAt = offsetof(PointState, stress) / sizeof(double);
constexpr int kStrainAt = offsetof(PointState, plastic_strain) / sizeof(double) + 1;
constexpr int kHistoryAt = offsetof(PointState, plastic_strain) / sizeof(double) + 2;
static_assert(kStressAt == 0 && kStrainAt == 4 && kHistoryAt == 5 && offsetof(PointState, peeq) == 6 * sizeof(double) &&
              offsetof(PointState, plastic_work) == 7 * sizeof(double) &&
              offsetof(PointState, thickness_stretch) == 8 * sizeof(double));

// ∂N/∂x and the point weights of the W elements from their Cps8Geometry, by 4 × 4
// transposes of 4 consecutive values of each element (one vector load per element,
// shuffles): filling lanes one value at a time stalled on the store-to-load forwarding and
// took half of the kernel (perf).
template <bool kShuffle, int W, class V>
[[gnu::always_inline]] inline void gather_geometry(const Cps8LaneGroupOf<W>& lane, int np, int n, GroupInput<V>& in) {
  for (int i = 0; i < n; ++i) {
    const double* g[W];
    for (int e = 0; e < W; ++e)
      g[e] = (i < np ? lane[e].geo->dndx[i] : lane[e].geo->dndx_reduced[i - np]).data();  // column-major 8 × 2
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 8; k += 4) {
        V c[4];
        gather_transposed<kShuffle>(g, 8 * j + k, c);
        for (int m = 0; m < 4; ++m) in.d[i][k + m][j] = c[m];
      }
  }
  {
    const double* w[W];
    for (int e = 0; e < W; ++e) w[e] = lane[e].geo->weight.data();
    for (int i = 0; i + 4 <= np; i += 4) gather_transposed<kShuffle>(w, i, &in.weight[i]);
    if (np == 9) lanes_from([&](int l) { return w[l][8]; }, in.weight[8]);
  }
}

// Where the kernel's ∂N/∂x and point weights come from when it forms them itself
// (kFormGeometry): the rule's tables and the elements' coordinates on x_n.
template <int W>
struct GeometrySource {
  const Cps8RuleTables* tables = nullptr;
  const std::array<const ElementCoords*, W>* x = nullptr;
  double thickness = 0;
};

// The kernel body, compiled once per instruction set (below); always inlined so that each
// copy is compiled wholly for its own target. kFormGeometry: ∂N/∂x and the weights are formed
// on the lanes from source (geometry_lanes.hpp, bitwise Cps8GeometryUpdater::update()) instead
// of gathered from each element's Cps8Geometry; returns false, nothing written, if an element
// is inverted or degenerate there. Otherwise always true. W = 4 or 8 elements, lane l of
// either width doing the same operations on element l.
template <int W, bool kShuffle, bool kFormGeometry>
[[gnu::always_inline]] inline bool force_lanes(const Cps8LaneGroupOf<W>& lane, const J2PlaneStress& material,
                                               const GeometrySource<W>& source) {
  using Lanes = typename LaneTypes<W>::V;
  using LaneMask = typename LaneTypes<W>::Mask;
  const Cps8Geometry& g0 = *lane[0].geo;
  const bool selective = g0.rule == Integration::Selective;
  const bool viscous = lane[0].viscous != nullptr;
  for (const Cps8Lane& l : lane)
    if (l.geo->rule != g0.rule || l.geo->points != g0.points || (l.viscous != nullptr) != viscous)
      throw std::invalid_argument("cps8_force_lanes: the elements of a group mix integration rules or bulk viscosity");
  const int np = g0.points, nr = selective ? 4 : 0, n = np + nr;

  GroupInput<Lanes> in;
  if constexpr (kFormGeometry) {
    // The geometry straight into the kernel's arrays: not written to the elements' 2.6 kB
    // Cps8Geometry and read back (that round trip was ≈ 15 % of the step; README session 9).
    const Cps8RuleTables& t = *source.tables;
    if (t.rule != g0.rule || t.points != np)
      throw std::invalid_argument("cps8_force_lanes_on_coords: the rule tables are not the elements' rule");
    Lanes xs[2][8];
    gather_coords<kShuffle>(*source.x, xs);
    PointJacobian<Lanes> jac[kMaxPoints];
    if (!jacobians_lanes(t, xs, jac)) return false;
    for (int i = 0; i < n; ++i) gradients_lanes(t, i, jac[i], in.d[i]);
    for (int i = 0; i < np; ++i) weight_lanes(t, i, jac[i], source.thickness, in.weight[i]);
  } else {
    gather_geometry<kShuffle, W>(lane, np, n, in);
  }

  // The Barlow matrix depends on the rule only: one element's, unless they differ.
  // The same bits are the same matrix (a NaN is no Barlow weight): one memcmp per element in
  // place of 36 compares and branches, the comparison by value only where the bits differ.
  bool same_barlow = true;
  for (int l = 1; l < W && nr > 0; ++l)
    same_barlow = same_barlow && (std::memcmp(lane[l].geo->barlow.data(), g0.barlow.data(), sizeof g0.barlow) == 0 ||
                                  lane[l].geo->barlow == g0.barlow);
  for (int i = 0; i < np; ++i)
    for (int r = 0; r < nr; ++r) {
      if (same_barlow)
        in.barlow[i][r] = Lanes{} + g0.barlow(i, r);
      else
        lanes_from([&](int l) { return lane[l].geo->barlow(i, r); }, in.barlow[i][r]);
    }
  {
    const double* u[W];
    for (int e = 0; e < W; ++e) u[e] = lane[e].du;
    for (int k = 0; k < 16; k += 4) {
      Lanes c[4];  // ux, uy of node k/2, then of node k/2 + 1
      gather_transposed<kShuffle>(u, k, c);
      in.u[k / 2][0] = c[0];
      in.u[k / 2][1] = c[1];
      in.u[k / 2 + 1][0] = c[2];
      in.u[k / 2 + 1][1] = c[3];
    }
  }
  if (viscous) {
    lanes_from([&](int l) { return lane[l].viscous->coefficient; }, in.coefficient);
    lanes_from([&](int l) { return lane[l].viscous->dt; }, in.dt);
  }

  // f = I + Σ_a u_a ⊗ ∇N_a at every point, the sum over a = 0..7 in order.
  Lanes f00[kMaxPoints], f01[kMaxPoints], f10[kMaxPoints], f11[kMaxPoints];
  for (int i = 0; i < n; ++i) {
    f00[i] = Lanes{} + 1.0;
    f11[i] = Lanes{} + 1.0;
    f01[i] = Lanes{};
    f10[i] = Lanes{};
  }
  for (int i = 0; i < n; ++i)  // point by point: the four sums stay in registers
    for (int a = 0; a < 8; ++a) {
      f00[i] += in.u[a][0] * in.d[i][a][0];
      f10[i] += in.u[a][1] * in.d[i][a][0];
      f01[i] += in.u[a][0] * in.d[i][a][1];
      f11[i] += in.u[a][1] * in.d[i][a][1];
    }

  // ΔE = ½(fᵀf − I), Voigt [E11, E22, 2E12]; tr ΔE at the reduced points.
  Lanes e0[9], e1[9], e2[9], tr_r[4], q_r[4];
  for (int i = 0; i < n; ++i) {
    const Lanes ei0 = 0.5 * ((f00[i] * f00[i] + f10[i] * f10[i]) - 1.0);
    const Lanes ei1 = 0.5 * ((f01[i] * f01[i] + f11[i] * f11[i]) - 1.0);
    if (i < np) {
      e0[i] = ei0;
      e1[i] = ei1;
      e2[i] = f00[i] * f01[i] + f10[i] * f11[i];
    } else {
      tr_r[i - np] = ei0 + ei1;
      q_r[i - np] = Lanes{};
    }
  }
  // Bulk-viscous pressure of each stress point, (coefficient tr ΔE) / dt.
  Lanes q[9];
  if (viscous)
    for (int i = 0; i < np; ++i) q[i] = in.coefficient * (e0[i] + e1[i]) / in.dt;

  // The elastic branch's constants, as update_stress() reads them.
  const Mat3& c = material.elastic_tangent();
  const Mat3& c_inv = material.elastic_compliance();
  const double c11 = c(0, 0), c12 = c(0, 1), shear = c(2, 2), inv_e = c_inv(0, 0), inv_e_nu = c_inv(0, 1);
  const double two_inv_e_nu = 2.0 * inv_e_nu, inv_g = c_inv(2, 2);

  Lanes force[16], viscous_force[16];
  for (int k = 0; k < 16; ++k) force[k] = Lanes{};
  if (viscous) {
    const double* v[W];
    for (int l = 0; l < W; ++l) v[l] = lane[l].viscous->force->data();
    for (int k = 0; k < 16; k += 4) gather_transposed<kShuffle>(v, k, &viscous_force[k]);
  }
  Lanes elastic_energy{};
  Lanes plastic_work{};
  PointLanes<Lanes> pt[9];

  for (int i = 0; i < np; ++i) {
    Lanes de0 = e0[i], de1 = e1[i];
    const Lanes de2 = e2[i];
    if (selective) {
      Lanes tr_bar{};
      for (int r = 0; r < 4; ++r) tr_bar += in.barlow[i][r] * tr_r[r];
      const Lanes corr = 0.5 * ((tr_bar - de0) - de1);
      de0 += corr;
      de1 += corr;
    }
    // Material: elastic trial S = S_n + C ΔE and the yield check of update_stress().
    Lanes sn[4], strain[4], history[4], sy;
    {
      const double* state[W];
      for (int l = 0; l < W; ++l) state[l] = reinterpret_cast<const double*>(&lane[l].committed[i]);
      gather_transposed<kShuffle>(state, kStressAt, sn);        // S_n (3), Ep_11
      gather_transposed<kShuffle>(state, kStrainAt, strain);    // Ep_22, Ep_12, ᾱ, plastic work
      gather_transposed<kShuffle>(state, kHistoryAt, history);  // —, ᾱ, —, λ3
    }
    const Lanes sn0 = sn[0], sn1 = sn[1], sn2 = sn[2], thickness = history[3];
    yield_stress_lanes(material.hardening(), history[1], sy);
    Lanes t0 = (sn0 + c11 * de0) + c12 * de1, t1 = (sn1 + c12 * de0) + c11 * de1, t2 = sn2 + shear * de2;
    const Lanes xi_trial = 2.0 / 3.0 * ((t0 * t0 + t1 * t1) - t0 * t1) + (2.0 * t2) * t2;
    const LaneMask elastic = 0.5 * xi_trial - (sy * sy) * (1.0 / 3.0) <= (1e-12 * sy) * sy;
    Lanes energy = 0.5 * ((inv_e * (t0 * t0 + t1 * t1) + (two_inv_e_nu * t0) * t1) + (inv_g * t2) * t2);
    Lanes strain33 = inv_e_nu * (((t0 + t1) - sn0) - sn1);
    const Lanes w = in.weight[i] * thickness;
    // Trial history (start_trial of cps8_force.cpp), elastic on the lanes — Ep + 0 and
    // W_p + w · 0 as the scalar kernel forms them (the sums turn a −0 into +0) — and stored with
    // the stress after the push-forward; lanes that yield take the scalar return mapping of
    // update_stress() on the same ΔE.
    Lanes ep0 = sn[3] + 0.0, ep1 = strain[0] + 0.0, ep2 = strain[1] + 0.0, peeq = strain[2],
          work = strain[3] + w * 0.0;
    // The lanes are written one by one only inside this block, on copies: a vector indexed by a
    // run-time lane lives in memory, and the elastic path (most points) would store and reload
    // every one of these vectors at every point (the kernel's spills, disassembly).
    if (const unsigned yielding = clear_lanes(elastic); yielding != 0) {
      Lanes v[14] = {t0, t1, t2, energy, strain33, ep0, ep1, ep2, peeq, work, de0, de1, de2, w};
      for (int l = 0; l < W; ++l) {
        if (!(yielding >> l & 1u)) continue;
        const PointState& cs = lane[l].committed[i];
        const J2Update up = material.update_stress(Vec3(v[10][l], v[11][l], v[12][l]), cs);
        v[0][l] = up.stress(0);
        v[1][l] = up.stress(1);
        v[2][l] = up.stress(2);
        v[3][l] = up.elastic_energy;
        v[4][l] = up.strain33_increment;
        v[5][l] = cs.plastic_strain(0) + up.plastic_increment(0);
        v[6][l] = cs.plastic_strain(1) + up.plastic_increment(1);
        v[7][l] = cs.plastic_strain(2) + up.plastic_increment(2);
        v[8][l] = up.peeq;
        v[9][l] = cs.plastic_work + v[13][l] * up.dissipation;
      }
      t0 = v[0], t1 = v[1], t2 = v[2], energy = v[3], strain33 = v[4];
      ep0 = v[5], ep1 = v[6], ep2 = v[7], peeq = v[8], work = v[9];
    }
    plastic_work += work;
    // point_stress(): S, selective S − p I with w p M_r into q_r.
    Lanes s00 = t0, s11 = t1;
    const Lanes s01 = t2;
    if (selective) {
      const Lanes p = 0.5 * (t0 + t1);
      s00 -= p;
      s11 -= p;
      for (int r = 0; r < 4; ++r) q_r[r] += (w * p) * in.barlow[i][r];
    }
    // A = f s, its nodal force w A ∇N_a (and the bulk-viscous q w f ∇N_a) on every node.
    const Lanes a00 = f00[i] * s00 + f01[i] * s01, a01 = f00[i] * s01 + f01[i] * s11;
    const Lanes a10 = f10[i] * s00 + f11[i] * s01, a11 = f10[i] * s01 + f11[i] * s11;
    const Lanes wa00 = w * a00, wa10 = w * a10, wa01 = w * a01, wa11 = w * a11;
    if (viscous) {
      const Lanes cb = q[i] * in.weight[i];
      const Lanes b00 = cb * f00[i], b10 = cb * f10[i], b01 = cb * f01[i], b11 = cb * f11[i];
      for (int k = 0; k < 8; ++k) {
        const Lanes nx = in.d[i][k][0], ny = in.d[i][k][1];
        force[2 * k] += wa00 * nx + wa01 * ny;
        force[2 * k + 1] += wa10 * nx + wa11 * ny;
        viscous_force[2 * k] += b00 * nx + b01 * ny;
        viscous_force[2 * k + 1] += b10 * nx + b11 * ny;
      }
    } else {
      for (int k = 0; k < 8; ++k) {
        const Lanes nx = in.d[i][k][0], ny = in.d[i][k][1];
        force[2 * k] += wa00 * nx + wa01 * ny;
        force[2 * k + 1] += wa10 * nx + wa11 * ny;
      }
    }
    elastic_energy += w * energy;
    pt[i] = PointLanes<Lanes>{f00[i], f01[i], f10[i], f11[i], t0, t1, t2, 1.0 + 2.0 * strain33, {ep0, ep1, ep2, peeq, work},
                       thickness};
  }

  // Push-forward σ = f S fᵀ / (det f λ3), λ3 = √max(1e-12, 1 + 2ΔE33) (finish_trial).
  for (int i = 0; i < np; ++i) {
    const PointLanes<Lanes>& p = pt[i];
    const LaneMask floor = 1e-12 < p.stretch;
    Lanes l3 = floor ? p.stretch : Lanes{} + 1e-12;
    sqrt_lanes(l3);
    const Lanes det = p.f00 * p.f11 - p.f10 * p.f01;
    const Lanes m00 = p.f00 * p.s0 + p.f01 * p.s2, m01 = p.f00 * p.s2 + p.f01 * p.s1;
    const Lanes m10 = p.f10 * p.s0 + p.f11 * p.s2, m11 = p.f10 * p.s2 + p.f11 * p.s1;
    const Lanes scale = det * l3;
    const Lanes sigma00 = (m00 * p.f00 + m01 * p.f01) / scale, sigma11 = (m10 * p.f10 + m11 * p.f11) / scale,
                sigma01 = (m00 * p.f10 + m01 * p.f11) / scale;
    // The whole trial state: σ and Ep_11, Ep_22 … W_p (two 4 × 4 transposes), λ3.
    {
      double* state[W];
      for (int l = 0; l < W; ++l) state[l] = reinterpret_cast<double*>(&lane[l].trial[i]);
      const Lanes head[4] = {sigma00, sigma11, sigma01, p.history[0]};
      scatter_transposed<kShuffle>(head, kStressAt, state);
      scatter_transposed<kShuffle>(&p.history[1], kStrainAt, state);
      const Lanes stretch = p.thickness * l3;
      for (int l = 0; l < W; ++l) lane[l].trial[i].thickness_stretch = stretch[l];
    }
  }
  // Selective: the volumetric force q_r f_r ∇N^r_a of the reduced points.
  for (int r = 0; r < nr; ++r) {
    const int i = np + r;
    const Lanes b00 = q_r[r] * f00[i], b10 = q_r[r] * f10[i], b01 = q_r[r] * f01[i], b11 = q_r[r] * f11[i];
    for (int k = 0; k < 8; ++k) {
      const Lanes nx = in.d[i][k][0], ny = in.d[i][k][1];
      force[2 * k] += b00 * nx + b01 * ny;
      force[2 * k + 1] += b10 * nx + b11 * ny;
    }
  }

  double* f[W];
  for (int l = 0; l < W; ++l) f[l] = lane[l].out->force.data();
  for (int k = 0; k < 16; k += 4) scatter_transposed<kShuffle>(&force[k], k, f);
  if (viscous) {
    for (int l = 0; l < W; ++l) f[l] = lane[l].viscous->force->data();
    for (int k = 0; k < 16; k += 4) scatter_transposed<kShuffle>(&viscous_force[k], k, f);
  }
  for (int l = 0; l < W; ++l) {
    lane[l].out->elastic_energy = elastic_energy[l];
    lane[l].out->plastic_work = plastic_work[l];
  }
  return true;
}

}  // namespace

void cps8_force_lanes_portable(const Cps8LaneGroup& group, const J2PlaneStress& material) {
  force_lanes<4, false, false>(group, material, GeometrySource<4>{});
}

// AVX2 without FMA: "avx2" implies AVX but not FMA in GCC, so no product is fused into a sum
// (-ffp-contract=fast would fuse them if FMA were enabled, and the lanes would round
// differently from the scalar kernel).
#if defined(__x86_64__) || defined(__i386__)
[[gnu::target("avx2")]] void cps8_force_lanes_avx2(const Cps8LaneGroup& group, const J2PlaneStress& material) {
  force_lanes<4, true, false>(group, material, GeometrySource<4>{});
}
namespace {
[[gnu::target("avx2")]] bool force_lanes_on_coords_avx2(const Cps8LaneGroup& group, const J2PlaneStress& material,
                                                        const GeometrySource<4>& source) {
  return force_lanes<4, true, true>(group, material, source);
}
}  // namespace
#else
void cps8_force_lanes_avx2(const Cps8LaneGroup& group, const J2PlaneStress& material) {
  force_lanes<4, false, false>(group, material, GeometrySource<4>{});
}
#endif

// AVX-512 without contraction: avx512f, unlike avx2, gives GCC fused multiply–adds, and
// -ffp-contract=fast (GCC's default for C++) would fuse the lanes' products into their sums;
// contraction off, each lane rounds every product and sum as the 4-lane copy and cps8_force().
#if defined(__x86_64__) || defined(__i386__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
[[gnu::target("avx512f")]] void cps8_force_lanes_avx512(const Cps8WideLaneGroup& group, const J2PlaneStress& material) {
  force_lanes<8, true, false>(group, material, GeometrySource<8>{});
}
namespace {
[[gnu::target("avx512f")]] bool force_lanes_on_coords_avx512(const Cps8WideLaneGroup& group,
                                                             const J2PlaneStress& material,
                                                             const GeometrySource<8>& source) {
  return force_lanes<8, true, true>(group, material, source);
}
}  // namespace
#pragma GCC pop_options
#endif

bool cps8_lanes_bitwise_build() {
#ifdef __FMA__
  return false;
#else
  return true;
#endif
}

bool cps8_lanes_avx2_available() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

bool cps8_lanes_avx512_available() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx512f");
#else
  return false;
#endif
}

bool cps8_force_wide_lanes_available() {
  static const bool on = cps8_lanes_bitwise_build() && cps8_lanes_avx512_available() && lanes::kDotTreeKnown;
  return on;
}

// Without AVX2 the portable copy is slower than cps8_force() element by element (its 4-wide
// operations are two SSE2 halves, as the scalar kernel's 2-wide ones; README "Performance"):
// the elements then go one by one — bitwise the same results either way.
void cps8_force_lanes(const Cps8LaneGroup& group, const J2PlaneStress& material) {
  static const bool avx2 = cps8_lanes_bitwise_build() && cps8_lanes_avx2_available();
  if (avx2) {
    cps8_force_lanes_avx2(group, material);
    return;
  }
  for (const Cps8Lane& l : group) cps8_force(*l.geo, l.du, l.committed, l.trial, material, *l.out, l.viscous);
}

}  // namespace ringcrush::fe

namespace ringcrush::fe {

bool cps8_force_lanes_forms_geometry() {
  static const bool on = cps8_lanes_bitwise_build() && cps8_lanes_avx2_available() && lanes::kDotTreeKnown;
  return on;
}

bool cps8_force_lanes_on_coords(const Cps8LaneGroup& group, const Cps8RuleTables& tables,
                                const std::array<const ElementCoords*, kCps8Lanes>& x_n, double thickness,
                                const J2PlaneStress& material) {
#if defined(__x86_64__) || defined(__i386__)
  if (cps8_force_lanes_forms_geometry())
    return force_lanes_on_coords_avx2(group, material, GeometrySource<4>{&tables, &x_n, thickness});
#else
  (void)group, (void)tables, (void)x_n, (void)thickness, (void)material;
#endif
  return false;
}

// Eight a group: the AVX-512 copy, else the two halves as groups of four (the same bits).
void cps8_force_lanes(const Cps8WideLaneGroup& group, const J2PlaneStress& material) {
#if defined(__x86_64__) || defined(__i386__)
  if (cps8_force_wide_lanes_available()) {
    cps8_force_lanes_avx512(group, material);
    return;
  }
#endif
  for (int h = 0; h < kCps8WideLanes; h += kCps8Lanes) {
    Cps8LaneGroup half;
    std::copy_n(group.begin() + h, kCps8Lanes, half.begin());
    cps8_force_lanes(half, material);
  }
}

bool cps8_force_lanes_on_coords(const Cps8WideLaneGroup& group, const Cps8RuleTables& tables,
                                const std::array<const ElementCoords*, kCps8WideLanes>& x_n, double thickness,
                                const J2PlaneStress& material) {
#if defined(__x86_64__) || defined(__i386__)
  if (cps8_force_wide_lanes_available())
    return force_lanes_on_coords_avx512(group, material, GeometrySource<8>{&tables, &x_n, thickness});
#else
  (void)group, (void)tables, (void)x_n, (void)thickness, (void)material;
#endif
  return false;
}

}  // namespace ringcrush::fe
