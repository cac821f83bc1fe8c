// Two-sided Lambertian reflector in the local frame (normal = +z); wo may lie on either side,
// and reflection stays on wo's side.
#pragma once

#include "kernels/physics/bsdf/dielectric.h"

namespace snee {

struct DiffuseParams {
  Rgb albedo{0.5f};
};

// wi on wo's side, cosine-weighted; sample.f is 1/pi (multiply by albedo).
inline BsdfSample diffuse_sample(Vec3 wo, Vec2 u) {
  BsdfSample s;
  if (wo.z == 0.0f) return s;
  s.wi = sample_cosine_hemisphere(u);
  if (wo.z < 0.0f) s.wi.z = -s.wi.z;
  s.f = kInvPi;
  s.pdf = std::fabs(s.wi.z) * kInvPi;
  s.valid = s.pdf > 0.0f;
  return s;
}

// 1/pi if same side, else 0 (times albedo by the caller).
inline float diffuse_eval(Vec3 wo, Vec3 wi) {
  return wo.z * wi.z > 0.0f ? kInvPi : 0.0f;
}
inline float diffuse_pdf(Vec3 wo, Vec3 wi) {
  return wo.z * wi.z > 0.0f ? std::fabs(wi.z) * kInvPi : 0.0f;
}

}  // namespace snee
