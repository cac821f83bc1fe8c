// camera_direction (camera.h) for a batch of pixels. Every operation is the scalar one in the
// same order (IEEE add, multiply, divide and square root round identically in every lane, and
// -ffp-contract=off rules out fused multiply-adds), so each lane equals the scalar result bit
// for bit.
#pragma once

#include "kernels/camera.h"
#include "kernels/simd/divide.h"

namespace snee::simd {

// Precondition of divide(): pixel indices below 2^31 (Film indexes pixels with int) and image
// edges below 2^22, which the scene loader's limit of 2^16 guarantees.
inline Vec3Batch camera_direction(const PinholeCamera& c, UintBatch pixel, FloatBatch u0,
                                  FloatBatch u1) {
  const QuotientRemainder row_col = divide(pixel, c.width);
  const FloatBatch px = xsimd::to_float(xsimd::bitwise_cast<IntBatch>(row_col.remainder));
  const FloatBatch py = xsimd::to_float(xsimd::bitwise_cast<IntBatch>(row_col.quotient));
  const FloatBatch x = FloatBatch(2.0f) * (px + u0) * FloatBatch(c.inv_width) - FloatBatch(1.0f);
  const FloatBatch y = FloatBatch(1.0f) - FloatBatch(2.0f) * (py + u1) * FloatBatch(c.inv_height);
  const FloatBatch dx =
      FloatBatch(c.forward.x) + FloatBatch(c.right.x) * x + FloatBatch(c.up.x) * y;
  const FloatBatch dy =
      FloatBatch(c.forward.y) + FloatBatch(c.right.y) * x + FloatBatch(c.up.y) * y;
  const FloatBatch dz =
      FloatBatch(c.forward.z) + FloatBatch(c.right.z) * x + FloatBatch(c.up.z) * y;
  const FloatBatch len = xsimd::sqrt(dx * dx + dy * dy + dz * dz);
  return {dx / len, dy / len, dz / len};
}

}  // namespace snee::simd
