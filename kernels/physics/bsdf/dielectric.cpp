#include "kernels/physics/bsdf/dielectric.h"

namespace snee {

namespace {

using dielectric_lanes::Lobe;
using dielectric_lanes::side_index;

struct LobeValue {
  float f = 0, pdf = 0;
};

LobeValue value_of(const Lobe<float>& lobe) {
  return lobe.ok ? LobeValue{lobe.f, lobe.pdf} : LobeValue{};
}

Vec3 reflection_half_vector(Vec3 wo, Vec3 wi) {
  const Vec3 h = normalize(wo + wi);
  return h.z < 0.0f ? -h : h;
}

// Generalised half vector of a transmission pair (docs/method.md 4.4), oriented to +z; zero when
// the pair is a straight line through an index-matched interface.
Vec3 transmission_half_vector(Vec3 a, float eta_a, Vec3 b, float eta_b) {
  const Vec3 h = eta_a * a + eta_b * b;
  const float len2 = dot(h, h);
  if (len2 == 0.0f) return Vec3(0.0f);
  const Vec3 hn = h / std::sqrt(len2);
  return hn.z < 0.0f ? -hn : hn;
}

// Whether the microfacet normal h faces w from w's side: the lobes' own chi+ test, written as
// they write it (a NaN passes). Tested before a lobe is evaluated: the straight-line lobes
// compute everything, and many pairs the tracer evaluates one at a time fail here.
bool faces(Vec3 w, Vec3 h) {
  return !(dot(w, h) * w.z <= 0.0f);
}

LobeValue rough_value(const DielectricParams& p, Vec3 wo, Vec3 wi) {
  if (p.delta() || wo.z == 0.0f || wi.z == 0.0f) return {};
  if (wo.z * wi.z > 0.0f) {
    const Vec3 h = reflection_half_vector(wo, wi);
    return faces(wo, h) ? value_of(dielectric_lanes::rough_reflection(p, wo, wi, h)) : LobeValue{};
  }
  const Vec3 h = transmission_half_vector(wo, side_index(wo.z, p.eta), wi, side_index(wi.z, p.eta));
  return h.z > 0.0f && faces(wo, h) && faces(wi, h)
             ? value_of(dielectric_lanes::rough_transmission(p, wo, wi, h))
             : LobeValue{};
}

}  // namespace

BsdfSample dielectric_sample(const DielectricParams& p, Vec3 wo, Vec2 u, float u_lobe) {
  const BsdfSample s = dielectric_sample<float>(p, wo, u.x, u.y, u_lobe);
  return s.valid ? s : BsdfSample{};
}

float dielectric_eval(const DielectricParams& p, Vec3 wo, Vec3 wi) {
  return rough_value(p, wo, wi).f;
}

float dielectric_pdf(const DielectricParams& p, Vec3 wo, Vec3 wi) {
  return rough_value(p, wo, wi).pdf;
}

bool dielectric_sample_transmission(const DielectricParams& p, Vec3 g, Vec2 u, Vec3* s) {
  const Refracted<float> r = dielectric_sample_transmission<float>(p, g, u.x, u.y);
  if (r.ok) *s = r.direction;
  return r.ok;
}

float dielectric_transmission_pdf(const DielectricParams& p, Vec3 g, Vec3 s) {
  if (p.delta() || g.z * s.z >= 0.0f) return 0.0f;
  const float eta_g = side_index(g.z, p.eta), eta_s = side_index(s.z, p.eta);
  const Vec3 h = transmission_half_vector(g, eta_g, s, eta_s);
  const float g_h = dot(g, h), s_h = dot(s, h);
  if (h.z <= 0.0f || g_h * g.z <= 0.0f || s_h * s.z <= 0.0f) return 0.0f;
  const float denom = eta_g * g_h + eta_s * s_h;
  return ggx_d(h, p.alpha) * h.z * eta_s * eta_s * std::fabs(s_h) / (denom * denom);
}

}  // namespace snee
