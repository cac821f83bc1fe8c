// The batched pass of a stage kernel: a function over a queue's slots in SIMD chunks of
// kLanes (the last one padded, simd/slot_chunk.h), with the chunks' lanes counted.
#pragma once

#include <algorithm>

#include "kernels/simd/slot_chunk.h"
#include "kernels/wavefront/kernel_context.h"

namespace snee {

// Calls pass(chunk, k) for the chunks of slots[0, n); k is the chunk's first queue position.
template <class Pass>
void for_each_chunk(const uint32_t* slots, size_t n, Pass&& pass) {
  for (size_t k = 0; k < n; k += simd::kLanes)
    pass(simd::SlotChunk(slots + k, std::min(simd::kLanes, n - k)), k);
}

// The same, counting the chunks' lanes as `kernel`'s.
template <class Pass>
void for_each_chunk(const uint32_t* slots, size_t n, BatchedKernel kernel, KernelCounters& counters,
                    Pass&& pass) {
  for_each_chunk(slots, n, [&](const simd::SlotChunk& chunk, size_t k) {
    pass(chunk, k);
    counters.count_lanes(kernel, chunk.count(), simd::kLanes);
  });
}

}  // namespace snee
