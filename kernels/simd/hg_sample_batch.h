// hg_sample (medium/henyey_greenstein.cpp) for a batch of lanes. The polar angle, the frame and
// the pdf are the scalar operations in the same order; only the azimuth's cosine and sine come
// from xsimd's sincos instead of libm's, so directions agree with the scalar ones to a few units
// in the last place of 1 (bound in README.md, checked by tests/test_shading_batch.cpp) and the
// pdf, which does not depend on the azimuth, bit for bit.
#pragma once

#include "kernels/lane_math.h"
#include "kernels/medium/henyey_greenstein.h"
#include "kernels/simd/frame_batch.h"
#include "kernels/simd/sampling_batch.h"

namespace snee::simd {

struct HgSampleBatch {
  Vec3Batch direction;
  FloatBatch pdf;
};

inline HgSampleBatch hg_sample(const Vec3Batch& w_before, FloatBatch g, FloatBatch u0,
                               FloatBatch u1) {
  const FloatBatch one(1.0f), half(0.5f);
  const FloatBatch s = FloatBatch(2.0f) * u0 - one;
  const FloatBatch num =
      s + g * (half * (FloatBatch(3.0f) + s * s) + g * (s + half * g * (s * s - one)));
  const FloatBatch den = one + g * s;
  const FloatBatch cos_theta = lane::clamp(num / (den * den), FloatBatch(-1.0f), one);
  const FloatBatch sin_theta = safe_sqrt(one - cos_theta * cos_theta);
  const Vec3Batch local = spherical_direction(sin_theta, cos_theta, FloatBatch(2.0f * kPi) * u1);
  return {FrameBatch::from_normal(w_before).to_world(local), hg_phase(cos_theta, g)};
}

}  // namespace snee::simd
