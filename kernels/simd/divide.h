// Exact unsigned division of a batch by one divisor. SSE and AVX have no integer divide, so
// the quotient is estimated in float and corrected with integer arithmetic.
#pragma once

#include "kernels/simd/arch.h"

namespace snee::simd {

struct QuotientRemainder {
  UintBatch quotient, remainder;
};

// n / d and n % d per lane, exactly, for n < 2^31, 0 < d < 2^24 and n / d < 2^22 (a pixel
// index of any image up to 16M pixels wide and 4M rows high). Why one correction suffices: the
// float estimate float(n) * (1 / float(d)) carries three roundings, a relative error below
// 3 * 2^-24, so below 0.75 in absolute terms for quotients under 2^22; truncating it is off by at
// most one. The remainder is computed modulo 2^32 and lies in [-d, 2d) before the correction,
// which int32 holds.
inline QuotientRemainder divide(UintBatch n, uint32_t d) {
  const IntBatch ni = xsimd::bitwise_cast<IntBatch>(n);
  const IntBatch di(static_cast<int32_t>(d));
  IntBatch q = xsimd::to_int(xsimd::to_float(ni) * FloatBatch(1.0f / static_cast<float>(d)));
  IntBatch r = ni - q * di;
  const auto below = r < IntBatch(0);
  q = xsimd::select(below, q - IntBatch(1), q);
  r = xsimd::select(below, r + di, r);
  const auto above = r >= di;
  q = xsimd::select(above, q + IntBatch(1), q);
  r = xsimd::select(above, r - di, r);
  return {xsimd::bitwise_cast<UintBatch>(q), xsimd::bitwise_cast<UintBatch>(r)};
}

}  // namespace snee::simd
