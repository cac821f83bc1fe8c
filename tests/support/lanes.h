// One SIMD batch's worth of values in memory, for filling a batch lane by lane and reading a
// result back lane by lane in the tests of kernels/simd/.
#pragma once

#include "kernels/simd/arch.h"

namespace snee::test {

template <class T>
struct Lanes {
  alignas(64) T v[simd::kLanes];
  xsimd::batch<T, simd::Arch> batch() const { return xsimd::batch<T, simd::Arch>::load_aligned(v); }
};

template <class T>
Lanes<T> to_lanes(xsimd::batch<T, simd::Arch> b) {
  Lanes<T> l;
  b.store_aligned(l.v);
  return l;
}

}  // namespace snee::test
