// The frame of core/math.h (FrameT) for a batch of lanes: the same template, so the same
// operations in the same order, bit for bit.
#pragma once

#include "kernels/simd/vec3_batch.h"

namespace snee::simd {

using FrameBatch = FrameT<Vec3Batch>;

}  // namespace snee::simd
