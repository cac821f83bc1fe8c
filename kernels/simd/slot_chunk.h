// Up to kLanes entries of a slot list, processed as one batch. Loads and stores of SoA path
// state go through one vector load or store when the slots form a contiguous run (a freshly
// started work unit hands out slots 0, 1, 2, ...), and through gather/scatter otherwise. A
// short tail chunk is padded with its first slot, so the padding lanes compute on valid data
// through the same vector code, and only the real lanes are ever stored.
#pragma once

#include "kernels/simd/arch.h"

namespace snee::simd {

// `count` entries of `src` (1 <= count <= kLanes) as one batch, padded with src[0].
template <class T>
xsimd::batch<T, Arch> load_padded(const T* src, size_t count) {
  if (count == kLanes) return xsimd::batch<T, Arch>::load_unaligned(src);
  alignas(64) T lanes[kLanes];
  for (size_t i = 0; i < kLanes; ++i) lanes[i] = src[i < count ? i : 0];
  return xsimd::batch<T, Arch>::load_aligned(lanes);
}

class SlotChunk {
 public:
  // slots[0, count) with 1 <= count <= kLanes; slot numbers must be below 2^31.
  SlotChunk(const uint32_t* slots, size_t count)
      : slots_(load_padded(slots, count)),
        first_(slots[0]),
        count_(count),
        contiguous_(count == kLanes && xsimd::all(slots_ == UintBatch(first_) + lane_index())) {}

  size_t count() const { return count_; }
  bool contiguous() const { return contiguous_; }

  template <class T>
  xsimd::batch<T, Arch> load(const T* src) const {
    if (contiguous_) return xsimd::batch<T, Arch>::load_unaligned(src + first_);
    return xsimd::batch<T, Arch>::gather(src, xsimd::bitwise_cast<IntBatch>(slots_));
  }

  template <class T>
  void store(T* dst, xsimd::batch<T, Arch> v) const {
    if (contiguous_) {
      v.store_unaligned(dst + first_);
    } else if (count_ == kLanes) {
      v.scatter(dst, xsimd::bitwise_cast<IntBatch>(slots_));
    } else {
      alignas(64) T lanes[kLanes];
      alignas(64) uint32_t slots[kLanes];
      v.store_aligned(lanes);
      slots_.store_aligned(slots);
      for (size_t i = 0; i < count_; ++i) dst[slots[i]] = lanes[i];
    }
  }

 private:
  UintBatch slots_;
  uint32_t first_;
  size_t count_;
  bool contiguous_;
};

}  // namespace snee::simd
