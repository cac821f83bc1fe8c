// sample_uniform_sphere (kernels/sampling.h) for a batch of lanes: the polar part in the scalar
// operation order, the azimuth through xsimd's sincos (directions within the bound of
// README.md, checked by tests/test_shading_batch.cpp).
#pragma once

#include "kernels/simd/arch.h"
#include "scene/math.h"

namespace snee::simd {

// sqrt(max(0, x)) with safe_sqrt's std::max semantics (a NaN becomes 0).
inline FloatBatch safe_sqrt(FloatBatch x) {
  return xsimd::sqrt(xsimd::select(FloatBatch(0.0f) < x, x, FloatBatch(0.0f)));
}

// spherical_direction (scene/math.h) for a batch.
inline Vec3Batch spherical_direction(FloatBatch sin_theta, FloatBatch cos_theta, FloatBatch phi) {
  const auto [sin_phi, cos_phi] = xsimd::sincos(phi);
  return {sin_theta * cos_phi, sin_theta * sin_phi, cos_theta};
}

inline Vec3Batch sample_uniform_sphere(FloatBatch u0, FloatBatch u1) {
  const FloatBatch z = FloatBatch(1.0f) - FloatBatch(2.0f) * u0;
  return spherical_direction(safe_sqrt(FloatBatch(1.0f) - z * z), z, FloatBatch(2.0f * kPi) * u1);
}

}  // namespace snee::simd
