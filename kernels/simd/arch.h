// The one SIMD architecture of a build, chosen at compile time from the compiler flags: the
// portable default (-march=x86-64-v2) gives SSE4.2 with 4 float lanes, SNEE_NATIVE on an
// AVX-512 machine gives 16. Every batched kernel uses these aliases, so a build never mixes
// widths and the lane count is a constant the compiler can unroll over.
#pragma once

#include <xsimd/xsimd.hpp>

#include <cstddef>
#include <cstdint>

namespace snee::simd {

using Arch = xsimd::default_arch;
using FloatBatch = xsimd::batch<float, Arch>;
using IntBatch = xsimd::batch<int32_t, Arch>;
using UintBatch = xsimd::batch<uint32_t, Arch>;

inline constexpr size_t kLanes = FloatBatch::size;
static_assert(UintBatch::size == kLanes && IntBatch::size == kLanes);
// PathState rounds its capacity up to 16 slots, a whole number of batches for every x86 width.
static_assert(16 % kLanes == 0);

// Lane indices 0, 1, ..., kLanes - 1.
inline UintBatch lane_index() {
  alignas(64) uint32_t lanes[kLanes];
  for (size_t i = 0; i < kLanes; ++i) lanes[i] = static_cast<uint32_t>(i);
  return UintBatch::load_aligned(lanes);
}

// A three-component vector with one batch per component (SoA in registers).
struct Vec3Batch {
  FloatBatch x, y, z;
};

}  // namespace snee::simd
