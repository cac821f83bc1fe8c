// Frame::from_normal, to_local and to_world (scene/math.h) for a batch of lanes, bit for bit:
// the same branchless basis in the same operation order, with only IEEE-exact operations.
#pragma once

#include "kernels/simd/vec3_batch.h"

namespace snee::simd {

struct FrameBatch {
  Vec3Batch s, t, n;

  static FrameBatch from_normal(const Vec3Batch& n) {
    const FloatBatch one(1.0f);
    const FloatBatch sign = xsimd::copysign(one, n.z);
    const FloatBatch a = FloatBatch(-1.0f) / (sign + n.z);
    const FloatBatch b = n.x * n.y * a;
    return {{one + sign * n.x * n.x * a, sign * b, -sign * n.x},
            {b, sign + n.y * n.y * a, neg(n.y)},
            n};
  }
  Vec3Batch to_local(const Vec3Batch& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3Batch to_world(const Vec3Batch& v) const {
    return {s.x * v.x + t.x * v.y + n.x * v.z, s.y * v.x + t.y * v.y + n.y * v.z,
            s.z * v.x + t.z * v.y + n.z * v.z};
  }
};

}  // namespace snee::simd
