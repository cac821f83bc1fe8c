// The few operations the physics needs beyond + - * / and comparisons, for code written once
// over its lane type F: float for the scalar functions, an xsimd float batch for the batched
// kernels (kernels/simd/), double where a test oracle wants one. A lane-generic function brings
// them in with `using namespace lane;` and calls them unqualified: the scalar overloads here
// are found by ordinary lookup, xsimd's (select, sqrt, ...) by argument-dependent lookup on the
// batch, so this header needs no xsimd and snee_physics stays free of it. Both sides of a
// select are computed; the scalar overloads give exactly what the branch they replace gave,
// since every operation here is exact or correctly rounded.
#pragma once

#include <algorithm>
#include <cmath>

namespace snee::lane {

inline float select(bool m, float a, float b) {
  return m ? a : b;
}
inline double select(bool m, double a, double b) {
  return m ? a : b;
}
inline float sqrt(float x) {
  return std::sqrt(x);
}
inline double sqrt(double x) {
  return std::sqrt(x);
}

// std::clamp's exact semantics (a NaN passes through), which min/max instructions do not keep.
template <class F>
F clamp(F v, F lo, F hi) {
  return select(v < lo, lo, select(hi < v, hi, v));
}

}  // namespace snee::lane
