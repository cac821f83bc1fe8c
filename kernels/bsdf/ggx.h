// GGX (Trowbridge-Reitz) microfacet distribution with Smith separable shadowing, in the local
// frame of the macro surface (normal = +z). alpha is used directly (no perceptual remap).
// Formulas: Walter et al. 2007 and docs/method.md 4.4. Unit vectors are assumed, so that
// sin^2 = x^2 + y^2 avoids the cancellation of 1 - z^2 near the pole for small alpha.
#pragma once

#include "kernels/sampling.h"

namespace snee {

// D(m); 0 for m.z <= 0. cos^4 (alpha^2 + tan^2)^2 = (alpha^2 cos^2 + sin^2)^2.
inline float ggx_d(Vec3 m, float alpha) {
  if (m.z <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float denom = a2 * m.z * m.z + (m.x * m.x + m.y * m.y);
  return a2 / (kPi * denom * denom);
}

// Smith G1 with the chi+(v.m / v.n) factor.
inline float ggx_g1(Vec3 v, Vec3 m, float alpha) {
  if (v.z == 0.0f || dot(v, m) * v.z <= 0.0f) return 0.0f;
  const float tan2 = (v.x * v.x + v.y * v.y) / (v.z * v.z);
  return 2.0f / (1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}

// m with density D(m) * m.z (solid angle): tan^2 theta_m = alpha^2 u / (1 - u).
inline Vec3 ggx_sample_normal(Vec2 u, float alpha) {
  const float a2u = alpha * alpha * u.x;
  const float denom = (1.0f - u.x) + a2u;
  const float cos_theta = std::sqrt((1.0f - u.x) / denom);
  const float sin_theta = std::sqrt(a2u / denom);
  return spherical_direction(sin_theta, cos_theta, 2.0f * kPi * u.y);
}

inline float ggx_normal_pdf(Vec3 m, float alpha) {
  return ggx_d(m, alpha) * std::max(m.z, 0.0f);
}

}  // namespace snee
