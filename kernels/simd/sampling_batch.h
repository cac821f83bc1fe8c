// sample_uniform_sphere (kernels/sampling.h) for a batch of lanes: the polar part in the scalar
// operation order, the azimuth through xsimd's sincos (directions within the bound of
// README.md, checked by tests/test_shading_batch.cpp), and the lane-by-lane sincos every
// batched kernel uses.
#pragma once

#include <utility>

#include "kernels/simd/arch.h"
#include "scene/math.h"

namespace snee::simd {

// sqrt(max(0, x)) with safe_sqrt's std::max semantics (a NaN becomes 0).
inline FloatBatch safe_sqrt(FloatBatch x) {
  return xsimd::sqrt(xsimd::select(FloatBatch(0.0f) < x, x, FloatBatch(0.0f)));
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

// spherical_direction (scene/math.h) for a batch.
inline Vec3Batch spherical_direction(FloatBatch sin_theta, FloatBatch cos_theta, FloatBatch phi) {
  const auto [sin_phi, cos_phi] = lanewise_sincos(phi);
  return {sin_theta * cos_phi, sin_theta * sin_phi, cos_theta};
}

inline Vec3Batch sample_uniform_sphere(FloatBatch u0, FloatBatch u1) {
  const FloatBatch z = FloatBatch(1.0f) - FloatBatch(2.0f) * u0;
  return spherical_direction(safe_sqrt(FloatBatch(1.0f) - z * z), z, FloatBatch(2.0f * kPi) * u1);
}

}  // namespace snee::simd
