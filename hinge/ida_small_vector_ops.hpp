// SUNDIALS serial N_Vector operations for IDA on a few components (the inertial Level 3
// chain's 5–15 live ones, hinge/ida_live_state.hpp): the same arithmetic, element by element
// in the same order, as SUNDIALS 6.4's serial vector with its fused operations off, so IDA's
// results are the same to the bit; but one call per operation instead of three to four
// (generic wrapper, N_VLinearSum_Serial's dispatch, its helper), and a linear combination
// in one call instead of one N_VScale and one N_VLinearSum per term. On a vector of ten
// components those calls, not the arithmetic, were IDA's vector work (h52, README "Hinge
// models": 25 % of the run's instructions at 45 m/s).
#pragma once

#include <nvector/nvector_serial.h>

namespace ringcrush::hinge {

// Replaces the operations of serial vector v (before IDA clones it: clones copy them):
// linear sum, scale, constant, weighted RMS norm, linear combination, linear sum of arrays.
void use_small_vector_ops(N_Vector v);

}  // namespace ringcrush::hinge
