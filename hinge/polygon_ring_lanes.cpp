// The central difference's ring pass (PolygonChain::ring_forces with the flow update,
// polygon_ring_forces.cpp) over all rings at once. The rings have the same N and the same
// lists of bars, hinges and nodes, so the per-ring loops run with the rings side by side: two
// to an SSE2 vector (hinge/ring_lanes.hpp), value k of ring r at k·lanes + r. Every lane does
// what the per-ring pass does for its ring, operation for operation (the bars' 1/ℓ, the hinge
// rotation's series with atan2 beyond, polygon_hinge_angle.hpp, the moments, the node forces
// gathered per node), so the forces, the flow update and its work are bitwise those of the
// per-ring pass; what changes is the count of instructions: the bars' square roots and
// divisions and the hinges' series are issued two rings at a time, and the index lists are
// walked once for all rings instead of once per ring.
//
// The order-dependent sums stay in the per-ring order: the hinges that yield are noted per
// ring and updated afterwards ring by ring, hinge by hinge (flow_hinge: θp, ā, the plastic
// work; then their flow rows and plastic power), as the per-ring pass does them. The mirrored
// hinges of the half model take their θp from the updated independent node, as there.
//
// Only where the pass has nothing to sum across rings besides those: the Kelvin–Voigt
// dampers implicit (or none) and no mass damping (ring_lanes_apply); the explicit dampers and
// the reference forms (IDA, Odeint, the Jacobians, recorded evaluations) keep the per-ring
// pass.
#pragma GCC diagnostic ignored "-Wpsabi"  // the AVX copy of the hinge pass (below)

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "hinge/polygon_bar_lanes.hpp"
#include "hinge/polygon_chain.hpp"
#include "hinge/polygon_hinge_angle.hpp"
#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge {

using lanes::Pair;
using lanes::PairMask;

namespace {

constexpr int kWordBits = 64;

int flow_words(int n_full) { return (n_full + kWordBits - 1) / kWordBits; }

}  // namespace

// An even lane count (a spare lane, repeating the last ring, when the ring count is odd);
// every array holds the full ring's indices 0…N (node N is node 0 again, as in gather_ring).
void PolygonChain::plan_ring_lanes() {
  lanes_ = n_rings_ + n_rings_ % 2;
  const auto values = static_cast<std::size_t>(n_full_ + 1) * static_cast<std::size_t>(lanes_);
  for (auto* a : {&lane_px_, &lane_py_, &lane_tp_, &lane_ab_, &lane_ex_, &lane_ey_, &lane_gx_, &lane_gy_, &lane_n_,
                  &lane_theta_, &lane_m_})
    a->assign(values, 0.0);
  lane_flowing_.assign(static_cast<std::size_t>(n_rings_ * flow_words(n_full_)), 0);
  flow_moment_.assign(static_cast<std::size_t>(n_ind_) * static_cast<std::size_t>(lanes_), 0.0);
}

// Not in a build with FMA (RINGCRUSH_NATIVE): GCC may fuse a product into a sum there, on the
// lanes differently from the per-ring pass (as cps8_lanes_bitwise_build).
bool PolygonChain::ring_lanes_apply() const {
#ifdef __FMA__
  return false;
#endif
  return ring_lanes_ && flow_y_ != nullptr && jac_ == nullptr && c_bar_ == 0.0 && c_hinge_ == 0.0 &&
         !(in_.mass_damping_per_s > 0.0);
}

// Positions, θp and ā of the independent nodes into the lanes, the mirrored nodes (−x) and
// node N after them; the node rows of φ that do not depend on the forces (x′ = v, the flow
// rows zero until a hinge flows) on the way.
void PolygonChain::ring_lanes_gather(const double* y, double* phi) {
  const auto L = static_cast<std::size_t>(lanes_);
  double* __restrict px = lane_px_.data();
  double* __restrict py = lane_py_.data();
  double* __restrict tp = lane_tp_.data();
  double* __restrict ab = lane_ab_.data();
  const Pair zero = {0.0, 0.0};
  // Two rings at a time: a node's (x, y) and (θp, ā) are pairs of the state, unpacked into
  // the two rings' lanes; the spare lane repeats the last ring.
  for (int p = 0; p < lanes_; p += 2) {
    const bool second = p + 1 < n_rings_;
    const double* __restrict node0 = y + node_offset(p, 0);
    const double* __restrict node1 = y + node_offset(second ? p + 1 : p, 0);
    double* __restrict row0 = phi + node_offset(p, 0);
    double* __restrict row1 = phi + node_offset(second ? p + 1 : p, 0);
    for (int j = 0; j < n_ind_; ++j, node0 += 6, node1 += 6, row0 += 6, row1 += 6) {
      const auto at = static_cast<std::size_t>(j) * L + static_cast<std::size_t>(p);
      const Pair a = lanes::load(node0), b = lanes::load(node1);
      const Pair c = lanes::load(node0 + 4), d = lanes::load(node1 + 4);
      lanes::store(px + at, __builtin_shuffle(a, b, PairMask{0, 2}));
      lanes::store(py + at, __builtin_shuffle(a, b, PairMask{1, 3}));
      lanes::store(tp + at, __builtin_shuffle(c, d, PairMask{0, 2}));
      lanes::store(ab + at, __builtin_shuffle(c, d, PairMask{1, 3}));
      lanes::store(row0, lanes::load(node0 + 2));
      lanes::store(row0 + 4, zero);
      if (second) {
        lanes::store(row1, lanes::load(node1 + 2));
        lanes::store(row1 + 4, zero);
      }
    }
  }
  if (half_)  // the axis nodes' x stays 0
    for (int r = 0; r < n_rings_; ++r) {
      phi[node_offset(r, 0)] = 0.0;
      phi[node_offset(r, n_ind_ - 1)] = 0.0;
    }
  for (const int k : ring_nodes_) {
    if (!(half_ && k >= n_ind_)) continue;
    const auto at = static_cast<std::size_t>(k) * L, from = static_cast<std::size_t>(n_full_ - k) * L;
    for (std::size_t l = 0; l < L; ++l) {
      px[at + l] = -px[from + l];
      py[at + l] = py[from + l];
    }
  }
  const auto end = static_cast<std::size_t>(n_full_) * L;
  for (std::size_t l = 0; l < L; ++l) {
    px[end + l] = px[l];
    py[end + l] = py[l];
  }
}

// Bars k ∈ bar_ranges_: e = w/ℓ, n/ℓ (the far end's ∂β/∂p) and the membrane force
// N = k_m (ℓ − ℓ0), as ring_bars and central_difference_ring_laws; each range one flat run of
// lanes, eight, four or two values to a vector (polygon_bar_lanes.hpp).
void PolygonChain::ring_lanes_bars() {
  const BarLanes b{lane_px_.data(), lane_py_.data(), lane_ex_.data(), lane_ey_.data(), lane_gx_.data(),
                   lane_gy_.data(), lane_n_.data(), static_cast<std::size_t>(lanes_), k_m_, l0_};
  const int width = lanes::wide_lanes_available();
  for (const auto& range : bar_ranges_) bar_lanes(b, range[0], range[1], width);
}

namespace {

// Four rings on the lanes of one AVX vector (the hinges' series, below): generic vector
// operations only, inlined into the avx2-compiled pass (no FMA: "avx2" does not imply it).
// Every function taking or returning a Quad is always inlined there, so none is ever called
// with the non-AVX ABI that -Wpsabi warns about (silenced for this file, above its includes:
// small_atan's vector copy is diagnosed at its definition).
using lanes::Quad;
using lanes::QuadMask;
using lanes::QuadMem;

template <class V>
struct Ops;
template <>
struct Ops<Pair> {
  using Mask = PairMask;
  static constexpr int width = 2;
  [[gnu::always_inline]] static Pair load(const double* p) { return lanes::load(p); }
  [[gnu::always_inline]] static void store(double* p, Pair v) { lanes::store(p, v); }
  [[gnu::always_inline]] static Pair abs(Pair x) { return lanes::abs(x); }
  [[gnu::always_inline]] static Pair min(Pair a, Pair b) { return lanes::min(a, b); }
  [[gnu::always_inline]] static Pair select(Mask m, Pair a, Pair b) { return lanes::select(m, a, b); }
  [[gnu::always_inline]] static bool any(Mask m) { return lanes::any(m); }
  [[gnu::always_inline]] static bool all(Mask m) { return m[0] && m[1]; }
};
template <>
struct Ops<Quad> {
  using Mask = QuadMask;
  static constexpr int width = 4;
  [[gnu::always_inline]] static Quad load(const double* p) { return *reinterpret_cast<const QuadMem*>(p); }
  [[gnu::always_inline]] static void store(double* p, Quad v) { *reinterpret_cast<QuadMem*>(p) = v; }
  [[gnu::always_inline]] static Quad select(Mask m, Quad a, Quad b) {
    return reinterpret_cast<Quad>((reinterpret_cast<Mask>(a) & m) | (reinterpret_cast<Mask>(b) & ~m));
  }
  [[gnu::always_inline]] static Quad abs(Quad x) {
    constexpr long long magnitude = 0x7fffffffffffffffLL;
    return reinterpret_cast<Quad>(reinterpret_cast<Mask>(x) & Mask{magnitude, magnitude, magnitude, magnitude});
  }
  [[gnu::always_inline]] static Quad min(Quad a, Quad b) { return select(b < a, b, a); }  // std::min
  [[gnu::always_inline]] static bool any(Mask m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }
  [[gnu::always_inline]] static bool all(Mask m) { return m[0] && m[1] && m[2] && m[3]; }
};

// What the hinge pass reads and writes (PolygonChain::ring_lanes_hinges).
struct HingePass {
  const double *ex, *ey, *tp, *ab;
  double *th, *m, *fm;
  std::uint64_t* flowing;
  const int* hinges;
  std::size_t hinge_count, lanes;
  int n_full, n_ind, n_rings, words;
  double turn0, turn_cos, turn_sin, k_theta, M0, H, cap;
};

// Hinge k on lanes p … p + width − 1 (prev: bar k − 1's values, at: bar and hinge k's).
template <class V>
[[gnu::always_inline]] inline void hinge_lanes(const HingePass& h, int k, std::size_t at, std::size_t prev,
                                               std::size_t p) {
  using O = Ops<V>;
  const V exm = O::load(h.ex + prev), eym = O::load(h.ey + prev);
  const V exk = O::load(h.ex + at), eyk = O::load(h.ey + at);
  const V tx = exm * h.turn_cos + eym * h.turn_sin;
  const V ty = eym * h.turn_cos - exm * h.turn_sin;
  const V cross = exk * ty - eyk * tx, dot = exk * tx + eyk * ty;
  const V w = cross / (1.0 + dot);
  V theta = 2.0 * small_atan(w);
  const typename O::Mask series = (dot > 0.0) & (O::abs(w) <= kHingeSeriesLimit);
  if (!O::all(series))
    for (int i = 0; i < O::width; ++i)
      if (!series[i]) theta[i] = hinge_rotation_atan2(cross[i], dot[i], h.turn0);
  O::store(h.th + at, theta);
  if (k >= h.n_ind) return;  // mirrored: its moment after the flow update (ring_lanes_flow)
  const V M = h.k_theta * (theta - O::load(h.tp + at));
  const V yield = O::min(h.M0 + h.H * O::load(h.ab + at), V{} + h.cap);
  const typename O::Mask flowing = O::abs(M) > yield;
  O::store(h.m + at, M);
  O::store(h.fm + at, O::select(flowing, O::load(h.fm + at), M));
  if (O::any(flowing))
    for (int i = 0; i < O::width; ++i) {
      const int r = static_cast<int>(p) + i;
      if (flowing[i] && r < h.n_rings)
        h.flowing[static_cast<std::size_t>(r * h.words + k / kWordBits)] |= std::uint64_t{1} << (k % kWordBits);
    }
}

// All hinges, the lanes four at a time where Wide (then a pair for the rest), else in pairs.
template <bool Wide>
[[gnu::always_inline]] inline void hinge_pass(const HingePass& h) {
  for (std::size_t i = 0; i < h.hinge_count; ++i) {
    const int k = h.hinges[i];
    const int km = k == 0 ? h.n_full - 1 : k - 1;
    const auto at0 = static_cast<std::size_t>(k) * h.lanes, prev0 = static_cast<std::size_t>(km) * h.lanes;
    std::size_t p = 0;
    if constexpr (Wide)
      for (; p + 4 <= h.lanes; p += 4) hinge_lanes<Quad>(h, k, at0 + p, prev0 + p, p);
    for (; p < h.lanes; p += 2) hinge_lanes<Pair>(h, k, at0 + p, prev0 + p, p);
  }
}

void hinge_pass_sse2(const HingePass& h) { hinge_pass<false>(h); }

#if defined(__x86_64__) && !defined(__FMA__)
[[gnu::target("avx2")]] void hinge_pass_avx2(const HingePass& h) { hinge_pass<true>(h); }
bool avx2_available() { return __builtin_cpu_supports("avx2"); }
#else
void hinge_pass_avx2(const HingePass& h) { hinge_pass<false>(h); }
bool avx2_available() { return false; }
#endif

}  // namespace

// Hinge rotations θ (the series, atan2 on the lanes beyond it), and for the independent
// hinges the trial moment k_θ(θ − θp) against the yield moment: the ones above it are noted
// for ring_lanes_flow, the others keep their moment for the next step's work (flow_moment_).
// Four rings to an AVX vector where the CPU has AVX2 (and the build no FMA, which could fuse
// a product into a sum on these lanes only), two to an SSE2 one otherwise: the same bits.
void PolygonChain::ring_lanes_hinges() {
  const HingePass h{lane_ex_.data(), lane_ey_.data(), lane_tp_.data(), lane_ab_.data(), lane_theta_.data(),
                    lane_m_.data(), flow_moment_.data(), lane_flowing_.data(), ring_hinges_.data(),
                    ring_hinges_.size(), static_cast<std::size_t>(lanes_), n_full_, n_ind_, n_rings_,
                    flow_words(n_full_), 2.0 * std::numbers::pi / n_full_, turn_cos_, turn_sin_, k_theta_, M0_, H_,
                    cap_};
  static const bool avx2 = avx2_available();
  if (avx2) hinge_pass_avx2(h);
  else hinge_pass_sse2(h);
}

// The yielding hinges ring by ring, hinge by hinge (the per-ring pass's order of the work and
// power sums): the flow update, the moment after it, the flow rows and the plastic power; then
// the mirrored hinges' moments with the updated θp of their images.
void PolygonChain::ring_lanes_flow(double* phi, Tally& tally) {
  const auto L = static_cast<std::size_t>(lanes_);
  const int words = flow_words(n_full_);
  for (int r = 0; r < n_rings_; ++r)
    for (int word = 0; word < words; ++word) {
      auto& bits = lane_flowing_[static_cast<std::size_t>(r * words + word)];
      for (std::uint64_t b = bits; b != 0; b &= b - 1) {
        const int k = word * kWordBits + std::countr_zero(b);
        const auto at = static_cast<std::size_t>(k) * L + static_cast<std::size_t>(r);
        const double M = flow_hinge(r, k, lane_theta_[at], lane_m_[at]);
        lane_m_[at] = M;
        const auto o = node_offset(r, k);
        lane_tp_[at] = flow_y_[o + 4];
        const Flow fl = flow(M, flow_y_[o + 5]);
        if (fl.over > 0.0) {
          phi[o + 4] = M > 0 ? fl.rate : -fl.rate;
          phi[o + 5] = fl.rate;
          tally.plastic_power += node_weight(k) * std::abs(M) * fl.rate;
        }
      }
      bits = 0;
    }
  for (const int k : ring_hinges_) {
    if (k < n_ind_) continue;
    const auto at = static_cast<std::size_t>(k) * L, image = static_cast<std::size_t>(n_full_ - k) * L;
    for (std::size_t p = 0; p < L; p += 2)
      lanes::store(lane_m_.data() + at + p,
                   k_theta_ * (lanes::load(lane_theta_.data() + at + p) - lanes::load(lane_tp_.data() + image + p)));
  }
}

// Node j's force (M_{j−1} − M_j) g_{j−1} + (M_{j+1} − M_j) g_j + N_j e_j − N_{j−1} e_{j−1}, as
// ring_node_forces, weighted as φ (the axis nodes ½, their x rows 0) into the rings' rows: a
// ring's (f_x, f_y) are adjacent rows of φ, so each lane's pair goes out as one store.
void PolygonChain::ring_lanes_node_forces(double* phi) {
  const auto L = static_cast<std::size_t>(lanes_);
  const auto ring_rows = 6 * static_cast<std::size_t>(n_ind_);
  const int n_rings = n_rings_;
  const double* __restrict m = lane_m_.data();
  const double* __restrict n = lane_n_.data();
  const double* __restrict gx = lane_gx_.data();
  const double* __restrict gy = lane_gy_.data();
  const double* __restrict ex = lane_ex_.data();
  const double* __restrict ey = lane_ey_.data();
  const auto node = [&](int j, int jm, int jp, bool end) {
    const auto a = static_cast<std::size_t>(j) * L, am = static_cast<std::size_t>(jm) * L,
               ap = static_cast<std::size_t>(jp) * L;
    double* row = phi + 6 * static_cast<std::size_t>(j) + 2;  // ring 0's (f_x, f_y) rows of node j
    for (std::size_t p = 0; p < L; p += 2, row += 2 * ring_rows) {
      const Pair mj = lanes::load(m + a + p);
      const Pair before = lanes::load(m + am + p) - mj, after = lanes::load(m + ap + p) - mj;
      const Pair fx = before * lanes::load(gx + am + p) + after * lanes::load(gx + a + p) +
                      lanes::load(n + a + p) * lanes::load(ex + a + p) -
                      lanes::load(n + am + p) * lanes::load(ex + am + p);
      const Pair fy = before * lanes::load(gy + am + p) + after * lanes::load(gy + a + p) +
                      lanes::load(n + a + p) * lanes::load(ey + a + p) -
                      lanes::load(n + am + p) * lanes::load(ey + am + p);
      const bool second = static_cast<int>(p) + 1 < n_rings;  // not the spare lane
      if (!end) {  // weight 1: w·f is f
        lanes::store(row, __builtin_shuffle(fx, fy, PairMask{0, 2}));
        if (second) lanes::store(row + ring_rows, __builtin_shuffle(fx, fy, PairMask{1, 3}));
        continue;
      }
      const double w = node_weight(j);
      const bool on_axis = half_;
      row[0] = on_axis ? 0.0 : w * fx[0];
      row[1] = w * fy[0];
      if (second) {
        row[ring_rows] = on_axis ? 0.0 : w * fx[1];
        row[ring_rows + 1] = w * fy[1];
      }
    }
  };
  // The ends wrap round the ring (and carry the axis weight in the half model).
  const int last = n_ind_ - 1;
  node(0, n_full_ - 1, 1, true);
  for (int j = 1; j < last; ++j) node(j, j - 1, j + 1, false);
  node(last, last - 1, last + 1 == n_full_ ? 0 : last + 1, true);
}

void PolygonChain::central_difference_ring_lanes(const double* y, double* phi, Tally& tally) {
  ++ring_lane_passes_;
  ring_lanes_gather(y, phi);
  ring_lanes_bars();
  ring_lanes_hinges();
  ring_lanes_flow(phi, tally);
  ring_lanes_node_forces(phi);
}

}  // namespace ringcrush::hinge
