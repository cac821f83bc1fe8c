// Distance in units in the last place between two floats, for comparing SIMD kernels with
// their scalar references.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace snee::test {

// Floats in order of value as integers: adjacent floats differ by 1, +0 and -0 coincide.
inline int64_t ordered_bits(float f) {
  const int32_t i = std::bit_cast<int32_t>(f);
  return i < 0 ? -static_cast<int64_t>(i & 0x7FFFFFFF) : static_cast<int64_t>(i);
}

// 0 for equal values (two NaNs count as equal), else the number of floats between them.
inline int64_t ulp_distance(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : INT64_MAX;
  return std::llabs(ordered_bits(a) - ordered_bits(b));
}

}  // namespace snee::test
