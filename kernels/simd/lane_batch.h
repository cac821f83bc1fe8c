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

// exp, log1p, sincos and atan2 are polynomials that xsimd evaluates with fma(): one fused
// instruction on a batch of an FMA architecture (fma3<avx2>, what -march=x86-64-v3 selects), a
// multiply and an add on every other (xsimd 8.1's AVX-512 included), so a lane would round
// differently in an AVX2 build than in the others. They are evaluated here on the same
// registers seen as the architecture without FMA (avx2), where they round as on SSE4.2 and
// AVX-512: images are bitwise identical across SIMD levels (tests/test_simd_dispatch.cpp).
template <class A>
struct without_fma {
  using type = A;
};
#if XSIMD_WITH_FMA3_SSE || XSIMD_WITH_FMA3_AVX || XSIMD_WITH_FMA3_AVX2
template <class A>
struct without_fma<xsimd::fma3<A>> {
  using type = A;
};
#endif
using UnfusedBatch = xsimd::batch<float, typename without_fma<Arch>::type>;
static_assert(UnfusedBatch::size == kLanes);

inline FloatBatch exp(FloatBatch x) {
  return FloatBatch(xsimd::exp(UnfusedBatch(x.data)).data);
}
inline FloatBatch log1p(FloatBatch x) {
  return FloatBatch(xsimd::log1p(UnfusedBatch(x.data)).data);
}
inline FloatBatch atan2(FloatBatch y, FloatBatch x) {
  return FloatBatch(xsimd::atan2(UnfusedBatch(y.data), UnfusedBatch(x.data)).data);
}

// sincos with each lane a function of that lane alone. xsimd picks its argument reduction for
// the whole batch (all lanes below pi/4, pi/2, 20 pi, or larger), and the first three give the
// same bits on every lane in range, but one NaN or huge lane (a failed sample next to good
// ones) switches the whole batch to a reduction that rounds differently. Lanes outside
// [-20 pi, 20 pi] are therefore computed as 0; callers never use their results.
inline std::pair<FloatBatch, FloatBatch> lanewise_sincos(FloatBatch x) {
  const FloatBatch limit(20.0f * kPi);
  const auto [s, c] =
      xsimd::sincos(UnfusedBatch(xsimd::select(xsimd::abs(x) <= limit, x, FloatBatch(0.0f)).data));
  return {FloatBatch(s.data), FloatBatch(c.data)};
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
  static simd::FloatBatch exp(simd::FloatBatch x) { return simd::exp(x); }
  static simd::FloatBatch log1p(simd::FloatBatch x) { return simd::log1p(x); }
  static simd::FloatBatch atan2(simd::FloatBatch y, simd::FloatBatch x) {
    return simd::atan2(y, x);
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
