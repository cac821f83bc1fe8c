// Full 32 x 32 -> 64-bit unsigned products per lane, split into high and low words, as Philox
// needs them. xsimd 8.1 has no widening multiply, so the one instruction that does it (pmuludq:
// even lanes only) is called directly; the odd lanes are shifted into even position first. The
// low words come from the plain 32-bit multiply, which measured faster than blending them out of
// the wide products.
#pragma once

#include <type_traits>

#include "kernels/simd/arch.h"

namespace snee::simd {

namespace detail {

template <class A>
inline constexpr bool kUnsupportedArch = false;

// Products of the even 32-bit lanes (0, 2, ...) as 64-bit lanes.
template <class A>
xsimd::batch<uint64_t, A> mul_even(xsimd::batch<uint32_t, A> a, xsimd::batch<uint32_t, A> b) {
  if constexpr (std::is_base_of_v<xsimd::avx512f, A>) {
    return _mm512_mul_epu32(a, b);
  } else if constexpr (std::is_base_of_v<xsimd::avx2, A>) {
    return _mm256_mul_epu32(a, b);
  } else if constexpr (std::is_base_of_v<xsimd::sse2, A>) {
    return _mm_mul_epu32(a, b);
  } else {
    static_assert(kUnsupportedArch<A>, "mul_even needs a widening multiply for this architecture");
  }
}

struct OddLanes {
  static constexpr bool get(size_t i, size_t) { return i % 2 == 1; }
};

}  // namespace detail

template <class A>
void mul_hilo(xsimd::batch<uint32_t, A> a, xsimd::batch<uint32_t, A> b,
              xsimd::batch<uint32_t, A>* hi, xsimd::batch<uint32_t, A>* lo) {
  using U32 = xsimd::batch<uint32_t, A>;
  using U64 = xsimd::batch<uint64_t, A>;
  const U64 even = detail::mul_even(a, b);
  const U64 odd = detail::mul_even(xsimd::bitwise_cast<U32>(xsimd::bitwise_cast<U64>(a) >> 32),
                                   xsimd::bitwise_cast<U32>(xsimd::bitwise_cast<U64>(b) >> 32));
  // Lane 2k of a u32 batch is the low word of u64 lane k (little endian): the high words of the
  // odd products already sit in the odd lanes.
  *hi = xsimd::select(xsimd::make_batch_bool_constant<U32, detail::OddLanes>(),
                      xsimd::bitwise_cast<U32>(odd), xsimd::bitwise_cast<U32>(even >> 32));
  *lo = a * b;
}

}  // namespace snee::simd
