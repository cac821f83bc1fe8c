// The media a chunk of slots travels in, one lane per slot, for the batched stage kernels.
#pragma once

#include <algorithm>

#include "kernels/simd/slot_chunk.h"
#include "kernels/simd/vec3_batch.h"
#include "kernels/wavefront/kernel_context.h"
#include "kernels/wavefront/path_state.h"

namespace snee {

using MediumLanes = HomogeneousMediumT<simd::FloatBatch>;

// One broadcast when the chunk is in one medium (the common case: one translucent object),
// else a lane-by-lane lookup.
inline MediumLanes load_media(const KernelContext& ctx, const PathState& state,
                              const simd::SlotChunk& chunk) {
  using simd::FloatBatch;
  alignas(64) int32_t index[simd::kLanes];
  chunk.load(state.medium).store_aligned(index);
  if (std::all_of(index, index + simd::kLanes, [&](int32_t i) { return i == index[0]; })) {
    const HomogeneousMedium& m = ctx.media[static_cast<size_t>(index[0])].medium;
    return {splat<FloatBatch>(m.sigma_s), splat<FloatBatch>(m.sigma_t), FloatBatch(m.g)};
  }
  alignas(64) float v[7][simd::kLanes];
  for (size_t l = 0; l < simd::kLanes; ++l) {
    const HomogeneousMedium& m = ctx.media[static_cast<size_t>(index[l])].medium;
    const float values[7] = {m.sigma_s.x, m.sigma_s.y, m.sigma_s.z, m.sigma_t.x,
                             m.sigma_t.y, m.sigma_t.z, m.g};
    for (int c = 0; c < 7; ++c) v[c][l] = values[c];
  }
  const auto lane = [&](int c) { return FloatBatch::load_aligned(v[c]); };
  return {{lane(0), lane(1), lane(2)}, {lane(3), lane(4), lane(5)}, lane(6)};
}

}  // namespace snee
