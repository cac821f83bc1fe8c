// Small header-only value types shared by every layer: vectors, RGB, orthonormal frames and
// affine transforms. Kept free of dependencies so scene/, kernels/ and tests can all use them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/lane_math.h"

namespace snee {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInv4Pi = 1.0f / (4.0f * kPi);
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct Vec3 {
  float x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator+(Vec3 b) const { return {x + b.x, y + b.y, z + b.z}; }
  constexpr Vec3 operator-(Vec3 b) const { return {x - b.x, y - b.y, z - b.z}; }
  constexpr Vec3 operator*(Vec3 b) const { return {x * b.x, y * b.y, z * b.z}; }
  constexpr Vec3 operator/(Vec3 b) const { return {x / b.x, y / b.y, z / b.z}; }
  constexpr Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(Vec3 b) { return *this = *this + b; }
  Vec3& operator-=(Vec3 b) { return *this = *this - b; }
  Vec3& operator*=(Vec3 b) { return *this = *this * b; }
  Vec3& operator*=(float s) { return *this = *this * s; }
  Vec3& operator/=(float s) { return *this = *this / s; }
  constexpr bool operator==(Vec3 b) const { return x == b.x && y == b.y && z == b.z; }
  constexpr bool operator!=(Vec3 b) const { return !(*this == b); }
};

template <>
struct lane::vec3_of<float> {
  using type = Vec3;
};
namespace lane {
inline Vec3 select(bool m, Vec3 a, Vec3 b) {
  return m ? a : b;
}
}  // namespace lane

constexpr Vec3 operator*(float s, Vec3 v) {
  return v * s;
}
constexpr float dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 v) {
  return std::sqrt(dot(v, v));
}
inline Vec3 normalize(Vec3 v) {
  return v / length(v);
}
constexpr float max_component(Vec3 v) {
  return std::max(v.x, std::max(v.y, v.z));
}
constexpr float min_component(Vec3 v) {
  return std::min(v.x, std::min(v.y, v.z));
}
constexpr float average(Vec3 v) {
  return (v.x + v.y + v.z) * (1.0f / 3.0f);
}
inline Vec3 vmin(Vec3 a, Vec3 b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 vmax(Vec3 a, Vec3 b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline Vec3 vexp(Vec3 v) {
  return {std::exp(v.x), std::exp(v.y), std::exp(v.z)};
}
constexpr bool is_black(Vec3 v) {
  return v.x == 0 && v.y == 0 && v.z == 0;
}
inline bool is_finite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
// Relative luminance (Rec. 709 weights); used for importance sampling and RR, never for physics.
constexpr float luminance(Vec3 c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

// RGB radiance, throughput and coefficients use the same arithmetic as positions.
using Rgb = Vec3;

// sqrt(max(0, x)) with std::max's semantics (a NaN becomes 0), for any lane type.
template <lane::Lane F>
F safe_sqrt(F x) {
  using namespace lane;
  return sqrt(select(F(0.0f) < x, x, F(0.0f)));
}
inline float safe_sqrt(float x) {
  return safe_sqrt<float>(x);
}
inline float safe_acos(float x) {
  return std::acos(std::clamp(x, -1.0f, 1.0f));
}
constexpr float sqr(float x) {
  return x * x;
}
// 0 at or below lo, 1 at or above hi, the cubic 3t^2 - 2t^3 between; with lo == hi a step
// (1 from lo on).
inline float smoothstep(float lo, float hi, float x) {
  if (!(hi > lo)) return x < lo ? 0.0f : 1.0f;
  const float t = std::clamp((x - lo) / (hi - lo), 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}

// Orthonormal basis around n (Duff et al. 2017, branchless), over the 3-vector V of a lane type.
template <class V>
struct FrameT {
  V s, t, n;

  static FrameT from_normal(const V& n) {
    using F = decltype(n.x);
    const F one(1.0f);
    const F sign = lane::copysign(one, n.z);
    const F a = F(-1.0f) / (sign + n.z);
    const F b = n.x * n.y * a;
    return {V{one + sign * n.x * n.x * a, sign * b, lane::neg(sign) * n.x},
            V{b, sign + n.y * n.y * a, lane::neg(n.y)}, n};
  }
  V to_local(const V& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  V to_world(const V& v) const { return s * v.x + t * v.y + n * v.z; }
};
using Frame = FrameT<Vec3>;

// The azimuth's sine and cosine come from lane::sincos: libm's for float.
template <lane::Lane F>
lane::Vec3Of<F> spherical_direction(F sin_theta, F cos_theta, F phi) {
  const auto [sin_phi, cos_phi] = lane::sincos(phi);
  return {sin_theta * cos_phi, sin_theta * sin_phi, cos_theta};
}
inline Vec3 spherical_direction(float sin_theta, float cos_theta, float phi) {
  return spherical_direction<float>(sin_theta, cos_theta, phi);
}

// v in every lane.
template <lane::Lane F>
lane::Vec3Of<F> splat(Vec3 v) {
  return {F(v.x), F(v.y), F(v.z)};
}

// Row-major 3x4 affine transform (rotation/scale/shear + translation).
struct Transform {
  float m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

  static Transform translate(Vec3 t) {
    Transform r;
    r.m[0][3] = t.x;
    r.m[1][3] = t.y;
    r.m[2][3] = t.z;
    return r;
  }
  static Transform scale(Vec3 s) {
    Transform r;
    r.m[0][0] = s.x;
    r.m[1][1] = s.y;
    r.m[2][2] = s.z;
    return r;
  }
  // Rotation by angle (radians) about a unit axis (Rodrigues).
  static Transform rotate(Vec3 axis, float angle) {
    const Vec3 a = normalize(axis);
    const float c = std::cos(angle), s = std::sin(angle), k = 1 - c;
    Transform r;
    r.m[0][0] = c + a.x * a.x * k;
    r.m[0][1] = a.x * a.y * k - a.z * s;
    r.m[0][2] = a.x * a.z * k + a.y * s;
    r.m[1][0] = a.y * a.x * k + a.z * s;
    r.m[1][1] = c + a.y * a.y * k;
    r.m[1][2] = a.y * a.z * k - a.x * s;
    r.m[2][0] = a.z * a.x * k - a.y * s;
    r.m[2][1] = a.z * a.y * k + a.x * s;
    r.m[2][2] = c + a.z * a.z * k;
    return r;
  }

  // this * b: apply b first.
  Transform operator*(const Transform& b) const {
    Transform r;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) {
        float v = (j == 3) ? m[i][3] : 0.0f;
        for (int k = 0; k < 3; ++k) v += m[i][k] * b.m[k][j];
        r.m[i][j] = v;
      }
    }
    return r;
  }
  Vec3 point(Vec3 p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  }
  Vec3 vector(Vec3 v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  float determinant() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  // Uniform scale factor if the linear part is a similarity (used for sphere radii).
  float uniform_scale() const { return std::cbrt(std::fabs(determinant())); }
};

}  // namespace snee
