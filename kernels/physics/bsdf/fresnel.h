// Unpolarised Fresnel reflectance of dielectric and conductor interfaces, and Snell refraction.
#pragma once

#include "core/lane_math.h"
#include "core/math.h"

namespace snee {

// Reflectance for light arriving with cosine cos_i (> 0) on the side of index eta_i, the other
// side having index eta_t; eta = eta_t / eta_i. Returns 1 under total internal reflection.
// The value is the same from both sides of a refraction pair (docs/method.md 4.3). F is the lane
// type (core/lane_math.h); both outcomes are computed and selected.
template <class F>
F fresnel_dielectric(F cos_i, F eta) {
  using namespace lane;
  const F one(1.0f);
  const F c = clamp(cos_i, F(0.0f), one);
  const F g2 = eta * eta - one + c * c;
  const F g = sqrt(g2);
  const F a = (g - c) / (g + c);
  const F b = (c * (g + c) - one) / (c * (g - c) + one);
  const F r = F(0.5f) * a * a * (one + b * b);
  // g2 < 0: total internal reflection. g + c == 0 only at grazing incidence on an index-matched
  // interface, where the limit is 1.
  return select(g2 < F(0.0f) || g + c == F(0.0f), one, r);
}

// The scalar form, which also takes arguments that convert to float.
inline float fresnel_dielectric(float cos_i, float eta) {
  return fresnel_dielectric<float>(cos_i, eta);
}

// Reflectance of a conductor of complex index eta + i k (relative to the exterior) for light
// arriving with cosine cos_i; exact for unpolarised light (Born and Wolf; the arrangement of
// pbrt-v3's FrConductor, which stays finite at grazing incidence, where it is 1). eta = 0,
// k >= 0 reflects everything at every angle.
inline float fresnel_conductor(float cos_i, float eta, float k) {
  const float c = std::clamp(cos_i, 0.0f, 1.0f);
  const float cos2 = c * c, sin2 = 1.0f - cos2;
  const float t0 = eta * eta - k * k - sin2;
  const float a2_plus_b2 = std::sqrt(t0 * t0 + 4.0f * eta * eta * k * k);
  const float t1 = a2_plus_b2 + cos2;
  const float a = std::sqrt(std::max(0.0f, 0.5f * (a2_plus_b2 + t0)));
  const float t2 = 2.0f * c * a;
  // The denominators vanish only in limits where the reflectance is known: grazing incidence on
  // eta = 1, k = 0 (1), and normal incidence on eta = k = 0 (rp = rs there).
  const float rs = t1 + t2 > 0.0f ? (t1 - t2) / (t1 + t2) : 1.0f;
  const float t3 = cos2 * a2_plus_b2 + sin2 * sin2;
  const float t4 = t2 * sin2;
  const float rp = t3 + t4 > 0.0f ? rs * (t3 - t4) / (t3 + t4) : rs;
  return 0.5f * (rp + rs);
}

inline Rgb fresnel_conductor(float cos_i, Rgb eta, Rgb k) {
  return {fresnel_conductor(cos_i, eta.x, k.x), fresnel_conductor(cos_i, eta.y, k.y),
          fresnel_conductor(cos_i, eta.z, k.z)};
}

// Refracts w (pointing away from the surface) through the interface whose normal m lies on w's
// side. eta = eta_w / eta_other. `ok` is false on total internal reflection (the direction is
// then meaningless); otherwise the direction points away from the surface on the other side.
template <lane::Lane F>
struct Refracted {
  lane::Vec3Of<F> direction;
  lane::MaskOf<F> ok;
};
template <lane::Lane F>
Refracted<F> refract(const lane::Vec3Of<F>& w, const lane::Vec3Of<F>& m, F eta) {
  using namespace lane;
  const F one(1.0f);
  const F c = dot(w, m);
  const F cos2 = one - c * c;
  const F sin2_t = eta * eta * select(F(0.0f) < cos2, cos2, F(0.0f));
  const F k = eta * c - sqrt(one - sin2_t);
  return {w * neg(eta) + m * k, sin2_t < one};
}
// The scalar form: false on total internal reflection, leaving *wt as it was.
inline bool refract(Vec3 w, Vec3 m, float eta, Vec3* wt) {
  const Refracted<float> r = refract<float>(w, m, eta);
  if (r.ok) *wt = r.direction;
  return r.ok;
}

// V is a lane type's 3-vector.
template <class V>
V reflect(const V& w, const V& m) {
  using F = decltype(w.x);
  return m * (F(2.0f) * dot(w, m)) - w;
}

}  // namespace snee
