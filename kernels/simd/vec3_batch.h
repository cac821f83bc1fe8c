// Componentwise arithmetic on Vec3Batch (core/math.h's Vec3 operators, one batch per
// component), the cross product and lane selection: the named forms for the batched kernels,
// the operators for the templates written once over the lane type (the same operations).
#pragma once

#include "kernels/simd/lane_batch.h"

namespace snee::simd {

using BoolBatch = FloatBatch::batch_bool_type;

inline FloatBatch dot(const Vec3Batch& a, const Vec3Batch& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3Batch add(const Vec3Batch& a, const Vec3Batch& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3Batch sub(const Vec3Batch& a, const Vec3Batch& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3Batch cross(const Vec3Batch& a, const Vec3Batch& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3Batch mul(const Vec3Batch& a, const Vec3Batch& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
inline Vec3Batch scale(const Vec3Batch& v, FloatBatch s) {
  return {v.x * s, v.y * s, v.z * s};
}
inline Vec3Batch div(const Vec3Batch& v, FloatBatch s) {
  return {v.x / s, v.y / s, v.z / s};
}
inline Vec3Batch negate(const Vec3Batch& v) {
  return {neg(v.x), neg(v.y), neg(v.z)};
}
inline Vec3Batch operator+(const Vec3Batch& a, const Vec3Batch& b) {
  return add(a, b);
}
inline Vec3Batch operator-(const Vec3Batch& a, const Vec3Batch& b) {
  return sub(a, b);
}
inline Vec3Batch operator*(const Vec3Batch& a, const Vec3Batch& b) {
  return mul(a, b);
}
inline Vec3Batch operator*(const Vec3Batch& v, FloatBatch s) {
  return scale(v, s);
}
inline Vec3Batch operator*(FloatBatch s, const Vec3Batch& v) {
  return scale(v, s);
}
inline Vec3Batch operator/(const Vec3Batch& v, FloatBatch s) {
  return div(v, s);
}
inline Vec3Batch operator-(const Vec3Batch& v) {
  return negate(v);
}
inline Vec3Batch normalize(const Vec3Batch& v) {
  return v / xsimd::sqrt(dot(v, v));
}
// Stores the components to three aligned arrays.
inline void store_aligned(const Vec3Batch& v, float* x, float* y, float* z) {
  v.x.store_aligned(x);
  v.y.store_aligned(y);
  v.z.store_aligned(z);
}
inline Vec3Batch select(BoolBatch m, const Vec3Batch& a, const Vec3Batch& b) {
  return {xsimd::select(m, a.x, b.x), xsimd::select(m, a.y, b.y), xsimd::select(m, a.z, b.z)};
}

}  // namespace snee::simd
