// dielectric_sample (bsdf/dielectric.cpp) for a batch of lanes, each with its own interface,
// bit for bit equal to the scalar function on every valid sample: the same operations in the
// same order, both lobes (and, in a mixed chunk, both the smooth and rough paths) computed and
// then selected. The one transcendental, the azimuth of the GGX normal, is evaluated per lane
// with libm's cos and sin, as the scalar sampler does, for the chunk's active lanes only (the
// others are padding and get an arbitrary normal). Invalid lanes report valid = false and
// nothing else.
#pragma once

#include <cmath>

#include "kernels/bsdf/dielectric.h"
#include "kernels/bsdf/fresnel.h"
#include "kernels/simd/frame_batch.h"

namespace snee::simd {

struct DielectricLanes {
  FloatBatch eta, alpha;
  BoolBatch delta() const {
    return !(alpha >= FloatBatch(kSmoothRoughness)) || eta == FloatBatch(1.0f);
  }
};

struct BsdfSampleBatch {
  Vec3Batch wi;  // local frame
  FloatBatch f, pdf;
  BoolBatch transmission, delta, valid;
};

namespace dielectric_detail {

inline FloatBatch side_index(FloatBatch wz, FloatBatch eta) {
  return xsimd::select(wz > FloatBatch(0.0f), FloatBatch(1.0f), eta);
}
inline FloatBatch other_side_index(FloatBatch wz, FloatBatch eta) {
  return xsimd::select(wz > FloatBatch(0.0f), eta, FloatBatch(1.0f));
}

inline FloatBatch ggx_d(const Vec3Batch& m, FloatBatch alpha) {
  const FloatBatch a2 = alpha * alpha;
  const FloatBatch denom = a2 * m.z * m.z + (m.x * m.x + m.y * m.y);
  return xsimd::select(m.z <= FloatBatch(0.0f), FloatBatch(0.0f),
                       a2 / (FloatBatch(kPi) * denom * denom));
}

inline FloatBatch ggx_g1(const Vec3Batch& v, const Vec3Batch& m, FloatBatch alpha) {
  const FloatBatch tan2 = (v.x * v.x + v.y * v.y) / (v.z * v.z);
  const FloatBatch g1 =
      FloatBatch(2.0f) / (FloatBatch(1.0f) + xsimd::sqrt(FloatBatch(1.0f) + alpha * alpha * tan2));
  return xsimd::select(v.z == FloatBatch(0.0f) || dot(v, m) * v.z <= FloatBatch(0.0f),
                       FloatBatch(0.0f), g1);
}

inline Vec3Batch ggx_sample_normal(FloatBatch u0, FloatBatch u1, FloatBatch alpha,
                                   size_t active_lanes) {
  const FloatBatch a2u = alpha * alpha * u0;
  const FloatBatch denom = (FloatBatch(1.0f) - u0) + a2u;
  const FloatBatch cos_theta = xsimd::sqrt((FloatBatch(1.0f) - u0) / denom);
  const FloatBatch sin_theta = xsimd::sqrt(a2u / denom);
  alignas(64) float phi[kLanes], cos_phi[kLanes] = {}, sin_phi[kLanes] = {};
  (FloatBatch(2.0f * kPi) * u1).store_aligned(phi);
  for (size_t l = 0; l < active_lanes; ++l) {
    cos_phi[l] = std::cos(phi[l]);
    sin_phi[l] = std::sin(phi[l]);
  }
  return {sin_theta * FloatBatch::load_aligned(cos_phi),
          sin_theta * FloatBatch::load_aligned(sin_phi), cos_theta};
}

// refract of bsdf/fresnel.h; `ok` is false under total internal reflection.
inline Vec3Batch refract(const Vec3Batch& w, const Vec3Batch& m, FloatBatch eta, BoolBatch* ok) {
  const FloatBatch c = dot(w, m);
  const FloatBatch cos2 = FloatBatch(1.0f) - c * c;
  const FloatBatch sin2_t =
      eta * eta * xsimd::select(FloatBatch(0.0f) < cos2, cos2, FloatBatch(0.0f));
  *ok = sin2_t < FloatBatch(1.0f);
  const FloatBatch k = eta * c - xsimd::sqrt(FloatBatch(1.0f) - sin2_t);
  const Vec3Batch a = scale(w, neg(eta)), b = scale(m, k);
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}

inline Vec3Batch reflect(const Vec3Batch& w, const Vec3Batch& m) {
  const Vec3Batch r = scale(m, FloatBatch(2.0f) * dot(w, m));
  return {r.x - w.x, r.y - w.y, r.z - w.z};
}

struct Lobe {
  FloatBatch f, pdf;
  BoolBatch ok;
};

inline Lobe rough_reflection(const DielectricLanes& p, const Vec3Batch& wo, const Vec3Batch& wi,
                             const Vec3Batch& h) {
  const FloatBatch wo_h = dot(wo, h);
  const FloatBatch c = xsimd::abs(wo_h);
  const FloatBatch fresnel =
      fresnel_dielectric(c, other_side_index(wo.z, p.eta) / side_index(wo.z, p.eta));
  const FloatBatch d = ggx_d(h, p.alpha);
  const FloatBatch g = ggx_g1(wo, h, p.alpha) * ggx_g1(wi, h, p.alpha);
  return {fresnel * d * g / (FloatBatch(4.0f) * xsimd::abs(wo.z) * xsimd::abs(wi.z)),
          d * h.z * fresnel / (FloatBatch(4.0f) * c), !(wo_h * wo.z <= FloatBatch(0.0f))};
}

inline Lobe rough_transmission(const DielectricLanes& p, const Vec3Batch& wo, const Vec3Batch& wi,
                               const Vec3Batch& h) {
  const FloatBatch wo_h = dot(wo, h), wi_h = dot(wi, h);
  const FloatBatch eta_o = side_index(wo.z, p.eta), eta_i = side_index(wi.z, p.eta);
  const FloatBatch fresnel =
      xsimd::select(eta_o <= eta_i, fresnel_dielectric(xsimd::abs(wo_h), eta_i / eta_o),
                    fresnel_dielectric(xsimd::abs(wi_h), eta_o / eta_i));
  const FloatBatch denom = eta_i * wi_h + eta_o * wo_h;
  const FloatBatch denom2 = denom * denom;
  const FloatBatch d = ggx_d(h, p.alpha);
  const FloatBatch g = ggx_g1(wo, h, p.alpha) * ggx_g1(wi, h, p.alpha);
  const FloatBatch one(1.0f);
  const FloatBatch f = xsimd::abs(wi_h * wo_h) / xsimd::abs(wi.z * wo.z) * eta_o * eta_o *
                       (one - fresnel) * g * d / denom2;
  const FloatBatch pdf = d * h.z * (one - fresnel) * eta_i * eta_i * xsimd::abs(wi_h) / denom2;
  const BoolBatch ok = !(wo_h * wo.z <= FloatBatch(0.0f) || wi_h * wi.z <= FloatBatch(0.0f)) &&
                       !(fresnel >= one || denom == FloatBatch(0.0f));
  return {f, pdf, ok};
}

inline BsdfSampleBatch smooth_sample(const DielectricLanes& p, const Vec3Batch& wo,
                                     FloatBatch u_lobe) {
  const FloatBatch one(1.0f), zero(0.0f);
  const FloatBatch eta_o = side_index(wo.z, p.eta), eta_t = other_side_index(wo.z, p.eta);
  const FloatBatch cos_o = xsimd::abs(wo.z);
  const FloatBatch fresnel = fresnel_dielectric(cos_o, eta_t / eta_o);
  const BoolBatch reflects = u_lobe < fresnel;
  const Vec3Batch normal{zero, zero, xsimd::select(wo.z > zero, one, FloatBatch(-1.0f))};
  BoolBatch refracted;
  const Vec3Batch wt = refract(wo, normal, eta_o / eta_t, &refracted);
  const FloatBatch ratio = eta_o / eta_t;
  BsdfSampleBatch s;
  s.wi = select(reflects, Vec3Batch{neg(wo.x), neg(wo.y), wo.z}, wt);
  s.f =
      xsimd::select(reflects, fresnel / cos_o, ratio * ratio * (one - fresnel) / xsimd::abs(wt.z));
  s.pdf = xsimd::select(reflects, fresnel, one - fresnel);
  s.transmission = !reflects;
  s.delta = BoolBatch(true);
  s.valid = reflects || (refracted && wt.z != zero);
  return s;
}

inline BsdfSampleBatch rough_sample(const DielectricLanes& p, const Vec3Batch& wo, FloatBatch u0,
                                    FloatBatch u1, FloatBatch u_lobe, size_t active_lanes) {
  const FloatBatch zero(0.0f);
  const Vec3Batch m = ggx_sample_normal(u0, u1, p.alpha, active_lanes);
  const Vec3Batch m_side = select(wo.z > zero, m, negate(m));
  const FloatBatch c = dot(wo, m_side);
  const FloatBatch eta_o = side_index(wo.z, p.eta), eta_t = other_side_index(wo.z, p.eta);
  const FloatBatch fresnel = fresnel_dielectric(c, eta_t / eta_o);
  const BoolBatch reflects = u_lobe < fresnel;
  const Vec3Batch wr = reflect(wo, m_side);
  BoolBatch refracted;
  const Vec3Batch wt = refract(wo, m_side, eta_o / eta_t, &refracted);
  const Lobe r = rough_reflection(p, wo, wr, m);
  const Lobe t = rough_transmission(p, wo, wt, m);
  const BoolBatch lobe_ok =
      select(reflects, !(wr.z * wo.z <= zero) && r.ok, refracted && !(wt.z * wo.z >= zero) && t.ok);
  BsdfSampleBatch s;
  s.wi = select(reflects, wr, wt);
  s.f = xsimd::select(reflects, r.f, t.f);
  s.pdf = xsimd::select(reflects, r.pdf, t.pdf);
  s.transmission = !reflects;
  s.delta = BoolBatch(false);
  s.valid = !(c <= zero) && lobe_ok && s.pdf > zero;
  return s;
}

}  // namespace dielectric_detail

// Lanes [0, active_lanes) hold real samples. A chunk of only smooth or only rough interfaces
// (the usual case: one material) computes only that path.
inline BsdfSampleBatch dielectric_sample(const DielectricLanes& p, const Vec3Batch& wo,
                                         FloatBatch u0, FloatBatch u1, FloatBatch u_lobe,
                                         size_t active_lanes = kLanes) {
  using namespace dielectric_detail;
  const BoolBatch delta = p.delta();
  const BoolBatch facing = !(wo.z == FloatBatch(0.0f));
  if (xsimd::all(delta)) {
    BsdfSampleBatch s = smooth_sample(p, wo, u_lobe);
    s.valid = facing && s.valid;
    return s;
  }
  BsdfSampleBatch s = rough_sample(p, wo, u0, u1, u_lobe, active_lanes);
  if (xsimd::any(delta)) {
    const BsdfSampleBatch smooth = smooth_sample(p, wo, u_lobe);
    s.wi = select(delta, smooth.wi, s.wi);
    s.f = xsimd::select(delta, smooth.f, s.f);
    s.pdf = xsimd::select(delta, smooth.pdf, s.pdf);
    s.transmission = select(delta, smooth.transmission, s.transmission);
    s.valid = select(delta, smooth.valid, s.valid);
    s.delta = delta;
  }
  s.valid = facing && s.valid;
  return s;
}

// dielectric_sample_transmission (bsdf/dielectric.cpp): g on one side refracted to the other
// through the macro normal (delta lanes) or a GGX normal facing g. `ok` is false where the
// scalar function returns false.
inline Vec3Batch sample_transmission(const DielectricLanes& p, const Vec3Batch& g, FloatBatch u0,
                                     FloatBatch u1, size_t active_lanes, BoolBatch* ok) {
  using namespace dielectric_detail;
  const FloatBatch zero(0.0f), one(1.0f);
  const BoolBatch outside = g.z > zero;
  const BoolBatch delta = p.delta();
  const Vec3Batch macro{zero, zero, xsimd::select(outside, one, FloatBatch(-1.0f))};
  const Vec3Batch m = ggx_sample_normal(u0, u1, p.alpha, active_lanes);
  const Vec3Batch normal = select(delta, macro, select(outside, m, negate(m)));
  BoolBatch refracted;
  const Vec3Batch s =
      refract(g, normal, side_index(g.z, p.eta) / other_side_index(g.z, p.eta), &refracted);
  *ok = !(g.z == zero) && refracted &&
        select(delta, !(s.z == zero), dot(g, normal) > zero && s.z * g.z < zero);
  return s;
}

}  // namespace snee::simd
