#include "kernels/bsdf/dielectric.h"

#include "kernels/bsdf/fresnel.h"
#include "kernels/bsdf/ggx.h"

namespace snee {

namespace {

// Index of refraction on the side of the surface that w points into.
float side_index(Vec3 w, float eta) {
  return w.z > 0.0f ? 1.0f : eta;
}
float other_side_index(Vec3 w, float eta) {
  return w.z > 0.0f ? eta : 1.0f;
}
Vec3 side_normal(Vec3 w) {
  return {0.0f, 0.0f, w.z > 0.0f ? 1.0f : -1.0f};
}

struct LobeValue {
  float f = 0, pdf = 0;
};

// Reflection of the pair (wo, wi), both on one side, off the microfacet normal h (h.z > 0). The
// sampler only uses normals that face wo from its side, which the chi+ factor of G1 also needs.
LobeValue rough_reflection(const DielectricParams& p, Vec3 wo, Vec3 wi, Vec3 h) {
  const float wo_h = dot(wo, h);
  if (wo_h * wo.z <= 0.0f) return {};
  const float c = std::fabs(wo_h);
  const float fresnel = fresnel_dielectric(c, other_side_index(wo, p.eta) / side_index(wo, p.eta));
  const float d = ggx_d(h, p.alpha);
  const float g = ggx_g1(wo, h, p.alpha) * ggx_g1(wi, h, p.alpha);
  return {fresnel * d * g / (4.0f * std::fabs(wo.z) * std::fabs(wi.z)),
          d * h.z * fresnel / (4.0f * c)};
}

// Transmission of the pair (wo, wi), on opposite sides, through h (h.z > 0): Walter et al. 2007
// eq. 21 for f, and the half-vector Jacobian with the sampled direction's index (wi's) in the
// numerator for the pdf (docs/method.md 4.4).
LobeValue rough_transmission(const DielectricParams& p, Vec3 wo, Vec3 wi, Vec3 h) {
  const float wo_h = dot(wo, h), wi_h = dot(wi, h);
  if (wo_h * wo.z <= 0.0f || wi_h * wi.z <= 0.0f) return {};
  const float eta_o = side_index(wo, p.eta), eta_i = side_index(wi, p.eta);
  // F is the same from both sides of the pair; from the denser side near the critical angle
  // eta^2 - 1 + cos^2 cancels and loses most digits, so evaluate it from the rarer side.
  const float fresnel = eta_o <= eta_i ? fresnel_dielectric(std::fabs(wo_h), eta_i / eta_o)
                                       : fresnel_dielectric(std::fabs(wi_h), eta_o / eta_i);
  const float denom = eta_i * wi_h + eta_o * wo_h;
  if (fresnel >= 1.0f || denom == 0.0f) return {};
  const float denom2 = denom * denom;
  const float d = ggx_d(h, p.alpha);
  const float g = ggx_g1(wo, h, p.alpha) * ggx_g1(wi, h, p.alpha);
  const float f = std::fabs(wi_h * wo_h) / std::fabs(wi.z * wo.z) * eta_o * eta_o *
                  (1.0f - fresnel) * g * d / denom2;
  const float pdf = d * h.z * (1.0f - fresnel) * eta_i * eta_i * std::fabs(wi_h) / denom2;
  return {f, pdf};
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

LobeValue rough_value(const DielectricParams& p, Vec3 wo, Vec3 wi) {
  if (p.delta() || wo.z == 0.0f || wi.z == 0.0f) return {};
  if (wo.z * wi.z > 0.0f) return rough_reflection(p, wo, wi, reflection_half_vector(wo, wi));
  const Vec3 h = transmission_half_vector(wo, side_index(wo, p.eta), wi, side_index(wi, p.eta));
  return h.z > 0.0f ? rough_transmission(p, wo, wi, h) : LobeValue{};
}

BsdfSample smooth_sample(const DielectricParams& p, Vec3 wo, float u_lobe) {
  const float eta_o = side_index(wo, p.eta), eta_t = other_side_index(wo, p.eta);
  const float cos_o = std::fabs(wo.z);
  const float fresnel = fresnel_dielectric(cos_o, eta_t / eta_o);
  BsdfSample s;
  s.delta = true;
  if (u_lobe < fresnel) {
    s.wi = Vec3(-wo.x, -wo.y, wo.z);
    s.f = fresnel / cos_o;
    s.pdf = fresnel;
    s.valid = true;
    return s;
  }
  if (!refract(wo, side_normal(wo), eta_o / eta_t, &s.wi)) return s;
  s.f = sqr(eta_o / eta_t) * (1.0f - fresnel) / std::fabs(s.wi.z);
  s.pdf = 1.0f - fresnel;
  s.transmission = true;
  s.valid = s.wi.z != 0.0f;
  return s;
}

}  // namespace

BsdfSample dielectric_sample(const DielectricParams& p, Vec3 wo, Vec2 u, float u_lobe) {
  if (wo.z == 0.0f) return {};
  if (p.delta()) return smooth_sample(p, wo, u_lobe);
  const Vec3 m = ggx_sample_normal(u, p.alpha);
  const Vec3 m_side = wo.z > 0.0f ? m : -m;
  const float c = dot(wo, m_side);
  if (c <= 0.0f) return {};
  const float eta_o = side_index(wo, p.eta), eta_t = other_side_index(wo, p.eta);
  const float fresnel = fresnel_dielectric(c, eta_t / eta_o);
  BsdfSample s;
  LobeValue v;
  if (u_lobe < fresnel) {
    s.wi = reflect(wo, m_side);
    if (s.wi.z * wo.z <= 0.0f) return {};
    v = rough_reflection(p, wo, s.wi, m);
  } else {
    if (!refract(wo, m_side, eta_o / eta_t, &s.wi) || s.wi.z * wo.z >= 0.0f) return {};
    s.transmission = true;
    v = rough_transmission(p, wo, s.wi, m);
  }
  s.f = v.f;
  s.pdf = v.pdf;
  s.valid = v.pdf > 0.0f;
  return s;
}

float dielectric_eval(const DielectricParams& p, Vec3 wo, Vec3 wi) {
  return rough_value(p, wo, wi).f;
}

float dielectric_pdf(const DielectricParams& p, Vec3 wo, Vec3 wi) {
  return rough_value(p, wo, wi).pdf;
}

bool dielectric_sample_transmission(const DielectricParams& p, Vec3 g, Vec2 u, Vec3* s) {
  if (g.z == 0.0f) return false;
  const float eta_ratio = side_index(g, p.eta) / other_side_index(g, p.eta);
  if (p.delta()) return refract(g, side_normal(g), eta_ratio, s) && s->z != 0.0f;
  const Vec3 m = ggx_sample_normal(u, p.alpha);
  const Vec3 m_side = g.z > 0.0f ? m : -m;
  if (dot(g, m_side) <= 0.0f) return false;
  return refract(g, m_side, eta_ratio, s) && s->z * g.z < 0.0f;
}

float dielectric_transmission_pdf(const DielectricParams& p, Vec3 g, Vec3 s) {
  if (p.delta() || g.z * s.z >= 0.0f) return 0.0f;
  const float eta_g = side_index(g, p.eta), eta_s = side_index(s, p.eta);
  const Vec3 h = transmission_half_vector(g, eta_g, s, eta_s);
  const float g_h = dot(g, h), s_h = dot(s, h);
  if (h.z <= 0.0f || g_h * g.z <= 0.0f || s_h * s.z <= 0.0f) return 0.0f;
  const float denom = eta_g * g_h + eta_s * s_h;
  return ggx_d(h, p.alpha) * h.z * eta_s * eta_s * std::fabs(s_h) / (denom * denom);
}

}  // namespace snee
