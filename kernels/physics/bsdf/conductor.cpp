#include "kernels/physics/bsdf/conductor.h"

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/bsdf/ggx.h"

namespace snee {

BsdfSample conductor_sample(const ConductorParams& p, Vec3 wo, Vec2 u) {
  BsdfSample s;
  if (!(wo.z > 0.0f)) return s;
  if (p.delta()) {
    s.wi = {-wo.x, -wo.y, wo.z};
    s.f = 1.0f / wo.z;
    s.pdf = 1.0f;
    s.delta = true;
    s.valid = true;
    return s;
  }
  const Vec3 m = ggx_sample_visible_normal(wo, u, p.alpha);
  s.wi = reflect(wo, m);
  if (!(s.wi.z > 0.0f)) return s;
  s.f = conductor_eval(p, wo, s.wi);
  s.pdf = conductor_pdf(p, wo, s.wi);
  s.valid = s.f > 0.0f && s.pdf > 0.0f;
  return s;
}

namespace {

// The half vector of a reflection pair on the upper side; false if either lies below.
bool half_vector(Vec3 wo, Vec3 wi, Vec3* h) {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return false;
  *h = normalize(wo + wi);
  return true;
}

}  // namespace

float conductor_eval(const ConductorParams& p, Vec3 wo, Vec3 wi) {
  Vec3 h;
  if (p.delta() || !half_vector(wo, wi, &h)) return 0.0f;
  const float g = ggx_g1(wo, h, p.alpha) * ggx_g1(wi, h, p.alpha);
  return ggx_d(h, p.alpha) * g / (4.0f * wo.z * wi.z);
}

// Visible-normal density over the reflection Jacobian 1 / (4 wo.h).
float conductor_pdf(const ConductorParams& p, Vec3 wo, Vec3 wi) {
  Vec3 h;
  if (p.delta() || !half_vector(wo, wi, &h)) return 0.0f;
  const float cos_oh = dot(wo, h);
  if (!(cos_oh > 0.0f)) return 0.0f;
  return ggx_visible_normal_pdf(wo, h, p.alpha) / (4.0f * cos_oh);
}

Rgb conductor_fresnel(const ConductorParams& p, Vec3 wo, Vec3 wi) {
  Vec3 h;
  if (!half_vector(wo, wi, &h)) return Rgb(0.0f);
  return fresnel_conductor(dot(wo, h), p.eta, p.k);
}

}  // namespace snee
