// Unpolarised Fresnel reflectance and Snell refraction for a dielectric interface.
#pragma once

#include "scene/math.h"

namespace snee {

// Reflectance for light arriving with cosine cos_i (> 0) on the side of index eta_i, the other
// side having index eta_t; eta = eta_t / eta_i. Returns 1 under total internal reflection.
// The value is the same from both sides of a refraction pair (docs/method.md 4.3).
inline float fresnel_dielectric(float cos_i, float eta) {
  const float c = std::clamp(cos_i, 0.0f, 1.0f);
  const float g2 = eta * eta - 1.0f + c * c;
  if (g2 < 0.0f) return 1.0f;
  const float g = std::sqrt(g2);
  // g + c == 0 only at grazing incidence on an index-matched interface, where the limit is 1.
  if (g + c == 0.0f) return 1.0f;
  const float a = (g - c) / (g + c);
  const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

// Refracts w (pointing away from the surface) through the interface whose normal m lies on w's
// side. eta = eta_w / eta_other. Returns false on total internal reflection. *wt points away
// from the surface on the other side.
inline bool refract(Vec3 w, Vec3 m, float eta, Vec3* wt) {
  const float c = dot(w, m);
  const float sin2_t = eta * eta * std::max(0.0f, 1.0f - c * c);
  if (sin2_t >= 1.0f) return false;
  *wt = -eta * w + (eta * c - std::sqrt(1.0f - sin2_t)) * m;
  return true;
}

inline Vec3 reflect(Vec3 w, Vec3 m) {
  return 2.0f * dot(w, m) * m - w;
}

}  // namespace snee
