// The few operations the physics needs beyond + - * / and comparisons, for code written once
// over its lane type F: float for the scalar functions, an xsimd float batch for the batched
// kernels (kernels/simd/), double for SNEE's scalar densities and samplers, whose products of
// inverse squares need its range (kernels/physics/snee/). A lane-generic function brings
// them in with `using namespace lane;` and calls select, sqrt and abs unqualified: the
// scalar overloads here are found by ordinary lookup, xsimd's by argument-dependent lookup on the
// batch, so this header needs no xsimd and snee_physics stays free of it. Both sides of a
// select are computed; the scalar overloads give exactly what the branch they replace gave,
// since every operation here is exact or correctly rounded.
//
// What xsimd lacks or gets wrong for the renderer (a sign-exact negation; exp, log1p and sincos
// that round alike at every SIMD width and whose lanes do not depend on each other), and what a
// lane's 3-vector is, goes through the trait ops<F>, which kernels/simd/lane_batch.h specialises
// for the batch: a template cannot reach a helper in snee::simd by argument-dependent lookup, but
// it does see a specialisation declared before it is instantiated. A type without one is not a lane
// type (`Lane`), so the templates below never capture a call with double arguments that used to
// convert to the float function.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

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

inline float abs(float x) {
  return std::fabs(x);
}
inline double abs(double x) {
  return std::fabs(x);
}

// Selection between masks (bool, or a batch of booleans, which xsimd's select does not take).
template <class M>
M select_mask(M m, M a, M b) {
  return (m && a) || (!m && b);
}
// Whether every or any lane of a mask is set; a float lane has one.
inline bool all(bool m) {
  return m;
}
inline bool any(bool m) {
  return m;
}

// std::clamp's exact semantics (a NaN passes through), which min/max instructions do not keep.
template <class F>
F clamp(F v, F lo, F hi) {
  return select(v < lo, lo, select(hi < v, hi, v));
}

// Per-lane-type operations; the primary template marks a type that is not a lane type.
template <class F>
struct ops {
  static constexpr bool is_lane = false;
};

template <>
struct ops<float> {
  static constexpr bool is_lane = true;
  static float neg(float x) { return -x; }
  static float copysign(float magnitude, float sign) { return std::copysign(magnitude, sign); }
  static float exp(float x) { return std::exp(x); }
  static float log1p(float x) { return std::log1p(x); }
  // libm's sine and cosine, as the scalar functions always called them.
  static std::pair<float, float> sincos(float x) { return {std::sin(x), std::cos(x)}; }
  static std::pair<float, float> libm_sincos(float x) { return sincos(x); }
  static float atan2(float y, float x) { return std::atan2(y, x); }
};

// Double lanes are the scalar functions of the SNEE densities and samplers (kernels/physics/snee/):
// their products of inverse squares need double's range where vertices nearly coincide.
template <>
struct ops<double> {
  static constexpr bool is_lane = true;
  static double neg(double x) { return -x; }
  static double copysign(double magnitude, double sign) { return std::copysign(magnitude, sign); }
  static double exp(double x) { return std::exp(x); }
  static double log1p(double x) { return std::log1p(x); }
  static std::pair<double, double> sincos(double x) { return {std::sin(x), std::cos(x)}; }
  static std::pair<double, double> libm_sincos(double x) { return sincos(x); }
  static double atan2(double y, double x) { return std::atan2(y, x); }
};

template <class F>
concept Lane = ops<F>::is_lane;

// -x with IEEE sign semantics (-0 for +0) on every lane type.
template <Lane F>
F neg(F x) {
  return ops<F>::neg(x);
}
template <Lane F>
F copysign(F magnitude, F sign) {
  return ops<F>::copysign(magnitude, sign);
}
// Call these three qualified (lane::exp): unqualified, argument-dependent lookup would also find
// xsimd's own for a batch, which rounds differently from one SIMD width to another.
template <Lane F>
F exp(F x) {
  return ops<F>::exp(x);
}
template <Lane F>
F log1p(F x) {
  return ops<F>::log1p(x);
}
template <Lane F>
F atan2(F y, F x) {
  return ops<F>::atan2(y, x);
}
// {sin x, cos x}.
template <Lane F>
std::pair<F, F> sincos(F x) {
  return ops<F>::sincos(x);
}
// {sin x, cos x} from libm on every lane: slower than sincos on a batch, but bit for bit what
// the scalar code gets, where a kernel's images must not move when it is batched.
template <Lane F>
std::pair<F, F> libm_sincos(F x) {
  return ops<F>::libm_sincos(x);
}

// The result of comparing two F: bool for float, a batch of booleans for a batch.
template <class F>
using MaskOf = decltype(std::declval<F>() < std::declval<F>());

// The 3-vector whose components are F (core/math.h: Vec3 for float; core/vec3d.h: Vec3d for
// double; kernels/simd: Vec3Batch).
template <class F>
struct vec3_of;
template <class F>
using Vec3Of = typename vec3_of<F>::type;

}  // namespace snee::lane
