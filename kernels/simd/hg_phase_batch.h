// hg_phase (medium/henyey_greenstein.h) for a batch of lanes, bit for bit equal to the scalar
// function: both forms of the denominator are computed and selected by the sign of g, in the
// scalar operation order, with IEEE-exact operations only.
#pragma once

#include "kernels/simd/arch.h"
#include "scene/math.h"

namespace snee::simd {

inline FloatBatch hg_phase(FloatBatch cos_theta, FloatBatch g) {
  const FloatBatch one(1.0f), two(2.0f);
  const FloatBatch forward = (one - g) * (one - g) + two * g * (one - cos_theta);
  const FloatBatch backward = (one + g) * (one + g) - two * g * (one + cos_theta);
  const FloatBatch denom = xsimd::select(g >= FloatBatch(0.0f), forward, backward);
  return FloatBatch(kInv4Pi) * (one - g * g) / (denom * xsimd::sqrt(denom));
}

}  // namespace snee::simd
