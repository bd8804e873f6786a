// The run-time choice of the wide kernels' vector (hinge/ring_lanes.hpp, ring_lanes_wide.hpp).
#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge::lanes {

int wide_lanes_available() {
#if defined(__x86_64__) && !defined(__FMA__)
  static const int width = __builtin_cpu_supports("avx512f") ? 8 : __builtin_cpu_supports("avx2") ? 4 : 2;
  return width;
#else
  return 2;  // a build with FMA: GCC may fuse the scalar reference's products, not the lanes' alike
#endif
}

}  // namespace ringcrush::hinge::lanes
