// The batch as a lane type (core/lane_math.h): its 3-vector is Vec3Batch, negation flips the
// sign bit, and sine and cosine are lanewise_sincos, so every template written once over the
// lane type runs on FloatBatch with the operations below.
#pragma once

#include <cmath>
#include <utility>

#include "core/math.h"
#include "kernels/simd/arch.h"

namespace snee::simd {

// -x with IEEE sign semantics (-0 for +0), as the scalar code's unary minus. xsimd 8.1 negates
// an AVX-512 float batch as 0 - x, which gives +0 for +0 and so parts from the scalar result on
// zero components; flipping the sign bit is exact on every architecture.
inline FloatBatch neg(FloatBatch x) {
  return xsimd::bitwise_xor(x, FloatBatch(-0.0f));
}

// xsimd::sincos with each lane a function of that lane alone. xsimd picks its argument
// reduction for the whole batch (all lanes below pi/4, pi/2, 20 pi, or larger), and the first
// three give the same bits on every lane in range, but one NaN or huge lane (a failed sample
// next to good ones) switches the whole batch to a reduction that rounds differently. Lanes
// outside [-20 pi, 20 pi] are therefore computed as 0; callers never use their results.
inline std::pair<FloatBatch, FloatBatch> lanewise_sincos(FloatBatch x) {
  const FloatBatch limit(20.0f * kPi);
  return xsimd::sincos(xsimd::select(xsimd::abs(x) <= limit, x, FloatBatch(0.0f)));
}

}  // namespace snee::simd

namespace snee::lane {

template <>
struct ops<simd::FloatBatch> {
  static constexpr bool is_lane = true;
  static simd::FloatBatch neg(simd::FloatBatch x) { return simd::neg(x); }
  static simd::FloatBatch copysign(simd::FloatBatch magnitude, simd::FloatBatch sign) {
    return xsimd::copysign(magnitude, sign);
  }
  static std::pair<simd::FloatBatch, simd::FloatBatch> sincos(simd::FloatBatch x) {
    return simd::lanewise_sincos(x);
  }
  static std::pair<simd::FloatBatch, simd::FloatBatch> libm_sincos(simd::FloatBatch x) {
    alignas(64) float v[simd::kLanes], sin_v[simd::kLanes], cos_v[simd::kLanes];
    x.store_aligned(v);
    for (size_t l = 0; l < simd::kLanes; ++l) {
      sin_v[l] = std::sin(v[l]);
      cos_v[l] = std::cos(v[l]);
    }
    return {simd::FloatBatch::load_aligned(sin_v), simd::FloatBatch::load_aligned(cos_v)};
  }
};

template <>
struct vec3_of<simd::FloatBatch> {
  using type = simd::Vec3Batch;
};

}  // namespace snee::lane
