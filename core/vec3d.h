// A double-precision 3-vector for the geometry solves that float cannot carry: refraction roots
// near grazing exits, the equiangular step's angles, a ray's hit on a facet far from its origin.
// Only those solves, and the double lane type of the SNEE densities and samplers
// (core/lane_math.h), use it; everything stored and traced stays Vec3.
#pragma once

#include <cmath>

#include "core/math.h"

namespace snee {

struct Vec3d {
  double x = 0, y = 0, z = 0;
  Vec3d() = default;
  Vec3d(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  explicit Vec3d(Vec3 v) : x(v.x), y(v.y), z(v.z) {}
  explicit operator Vec3() const {
    return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
  }
  Vec3d operator+(const Vec3d& b) const { return {x + b.x, y + b.y, z + b.z}; }
  Vec3d operator-(const Vec3d& b) const { return {x - b.x, y - b.y, z - b.z}; }
  Vec3d operator-() const { return {-x, -y, -z}; }
  Vec3d operator*(const Vec3d& b) const { return {x * b.x, y * b.y, z * b.z}; }
  Vec3d operator*(double s) const { return {x * s, y * s, z * s}; }
  Vec3d operator/(double s) const { return {x / s, y / s, z / s}; }
};
template <>
struct lane::vec3_of<double> {
  using type = Vec3d;
};
// Found by argument-dependent lookup from the lane-generic templates, which may be defined before
// this header is included.
inline Vec3d select(bool m, const Vec3d& a, const Vec3d& b) {
  return m ? a : b;
}

inline Vec3d operator*(double s, const Vec3d& v) {
  return {s * v.x, s * v.y, s * v.z};
}
inline double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3d& v) {
  return std::sqrt(dot(v, v));
}
inline Vec3d normalize(const Vec3d& v) {
  return v / length(v);
}

}  // namespace snee
