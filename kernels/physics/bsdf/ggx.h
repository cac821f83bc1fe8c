// GGX (Trowbridge-Reitz) microfacet distribution with Smith separable shadowing, in the local
// frame of the macro surface (normal = +z). alpha is used directly (no perceptual remap).
// Formulas: Walter et al. 2007 and docs/method.md 4.4. Unit vectors are assumed, so that
// sin^2 = x^2 + y^2 avoids the cancellation of 1 - z^2 near the pole for small alpha.
#pragma once

#include "kernels/physics/sampling.h"

namespace snee {

// D(m); 0 for m.z <= 0. cos^4 (alpha^2 + tan^2)^2 = (alpha^2 cos^2 + sin^2)^2. F is the lane
// type (core/lane_math.h), as below.
template <lane::Lane F>
F ggx_d(const lane::Vec3Of<F>& m, F alpha) {
  using namespace lane;
  const F a2 = alpha * alpha;
  const F denom = a2 * m.z * m.z + (m.x * m.x + m.y * m.y);
  return select(m.z <= F(0.0f), F(0.0f), a2 / (F(kPi) * denom * denom));
}
inline float ggx_d(Vec3 m, float alpha) {
  return ggx_d<float>(m, alpha);
}

// Smith G1 with the chi+(v.m / v.n) factor.
template <lane::Lane F>
F ggx_g1(const lane::Vec3Of<F>& v, const lane::Vec3Of<F>& m, F alpha) {
  using namespace lane;
  const F one(1.0f), zero(0.0f);
  const F tan2 = (v.x * v.x + v.y * v.y) / (v.z * v.z);
  const F g1 = F(2.0f) / (one + sqrt(one + alpha * alpha * tan2));
  return select(v.z == zero || dot(v, m) * v.z <= zero, zero, g1);
}
inline float ggx_g1(Vec3 v, Vec3 m, float alpha) {
  return ggx_g1<float>(v, m, alpha);
}

// m with density D(m) * m.z (solid angle): tan^2 theta_m = alpha^2 u0 / (1 - u0). The azimuth's
// sine and cosine are libm's on every lane type, so the batched BSDF sample of shade_surface is
// bit for bit the scalar one.
template <lane::Lane F>
lane::Vec3Of<F> ggx_sample_normal(F u0, F u1, F alpha) {
  using namespace lane;
  const F one(1.0f);
  const F a2u = alpha * alpha * u0;
  const F denom = (one - u0) + a2u;
  const F cos_theta = sqrt((one - u0) / denom);
  const F sin_theta = sqrt(a2u / denom);
  const auto [sin_phi, cos_phi] = libm_sincos(F(2.0f * kPi) * u1);
  return {sin_theta * cos_phi, sin_theta * sin_phi, cos_theta};
}
inline Vec3 ggx_sample_normal(Vec2 u, float alpha) {
  return ggx_sample_normal<float>(u.x, u.y, alpha);
}

inline float ggx_normal_pdf(Vec3 m, float alpha) {
  return ggx_d(m, alpha) * std::max(m.z, 0.0f);
}

// m with density G1(v, m) max(0, v.m) D(m) / v.z, the normals visible from v (v.z > 0): Heitz,
// "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), 2018. A sampler for reflection
// that never draws a normal facing away from v, so no sample is wasted at grazing angles.
inline Vec3 ggx_sample_visible_normal(Vec3 v, Vec2 u, float alpha) {
  // Stretch to the hemisphere configuration, sample the projected half disk, unstretch.
  const Vec3 vh = normalize(Vec3(alpha * v.x, alpha * v.y, v.z));
  const float len2 = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = len2 > 0.0f ? Vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 t2 = cross(vh, t1);
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + vh.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
  const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return normalize(Vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)));
}

inline float ggx_visible_normal_pdf(Vec3 v, Vec3 m, float alpha) {
  if (v.z <= 0.0f) return 0.0f;
  return ggx_g1(v, m, alpha) * std::max(0.0f, dot(v, m)) * ggx_d(m, alpha) / v.z;
}

}  // namespace snee
