// fresnel_dielectric (bsdf/fresnel.h) for a batch of lanes. Both branches are computed and
// selected; the arithmetic is the scalar one in the same order with only IEEE-exact operations
// (no transcendentals), so every lane equals the scalar result bit for bit.
#pragma once

#include "kernels/simd/arch.h"

namespace snee::simd {

// std::clamp's exact semantics (a NaN passes through), which min/max instructions do not keep.
inline FloatBatch clamp(FloatBatch v, FloatBatch lo, FloatBatch hi) {
  return xsimd::select(v < lo, lo, xsimd::select(hi < v, hi, v));
}

inline FloatBatch fresnel_dielectric(FloatBatch cos_i, FloatBatch eta) {
  const FloatBatch one(1.0f);
  const FloatBatch c = clamp(cos_i, FloatBatch(0.0f), one);
  const FloatBatch g2 = eta * eta - one + c * c;
  const FloatBatch g = xsimd::sqrt(g2);
  const FloatBatch a = (g - c) / (g + c);
  const FloatBatch b = (c * (g + c) - one) / (c * (g - c) + one);
  const FloatBatch r = FloatBatch(0.5f) * a * a * (one + b * b);
  return xsimd::select(g2 < FloatBatch(0.0f) || g + c == FloatBatch(0.0f), one, r);
}

}  // namespace snee::simd
