// A thin translucent sheet (pbrt-v4's DiffuseTransmission, Mitsuba's "difftrans" under
// "twosided"): Lambertian reflection of reflectance R on the side light arrives from and
// Lambertian transmission of transmittance T to the other side, the same from both sides;
// R + T <= 1 per channel. The sheet has no thickness, so the medium does not change across it.
// Local frame (normal = +z), wo on either side. As for the diffuse surface, sample.f is 1/pi
// and the colour (R or T, by the side of wi) comes from diffuse_transmission_tint.
#pragma once

#include "kernels/physics/bsdf/diffuse.h"

namespace snee {

struct DiffuseTransmissionParams {
  Rgb reflectance{0.5f};
  Rgb transmittance{0.5f};
  // Probability of choosing the reflection lobe, by the channel sums; 0 and 1 where a lobe is
  // black, so no sample lands where the BSDF is zero.
  float reflect_probability() const {
    const float r = reflectance.x + reflectance.y + reflectance.z;
    const float t = transmittance.x + transmittance.y + transmittance.z;
    return r + t > 0.0f ? r / (r + t) : 0.0f;
  }
};

inline float diffuse_transmission_pdf(const DiffuseTransmissionParams& p, Vec3 wo, Vec3 wi) {
  if (wo.z == 0.0f) return 0.0f;
  const float lobe = wo.z * wi.z > 0.0f ? p.reflect_probability() : 1.0f - p.reflect_probability();
  return lobe * std::fabs(wi.z) * kInvPi;
}

// u_lobe picks reflection (below reflect_probability) or transmission; u the cosine direction.
inline BsdfSample diffuse_transmission_sample(const DiffuseTransmissionParams& p, Vec3 wo, Vec2 u,
                                              float u_lobe) {
  BsdfSample s = diffuse_sample(wo, u);
  if (!s.valid) return s;
  s.transmission = !(u_lobe < p.reflect_probability());
  if (s.transmission) s.wi.z = -s.wi.z;
  s.pdf = diffuse_transmission_pdf(p, wo, s.wi);
  s.valid = s.pdf > 0.0f;
  return s;
}

// 1/pi on both sides (times the tint by the caller); 0 only in the surface plane.
inline float diffuse_transmission_eval(Vec3 wo, Vec3 wi) {
  return wo.z * wi.z != 0.0f ? kInvPi : 0.0f;
}

inline Rgb diffuse_transmission_tint(const DiffuseTransmissionParams& p, Vec3 wo, Vec3 wi) {
  return wo.z * wi.z > 0.0f ? p.reflectance : p.transmittance;
}

}  // namespace snee
