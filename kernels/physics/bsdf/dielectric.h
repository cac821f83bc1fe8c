// Dielectric interface BSDF, smooth (delta) or rough (GGX, Walter et al. 2007), in the local
// frame of the surface with the *outward* normal = +z. The interior has index `eta` relative
// to the exterior. All directions point away from the surface. Radiance mode: `wo` is the
// camera side, `wi` the light side; transmission carries the (eta_o / eta_i)^2 factor
// (docs/method.md section 4.5). The pdfs include the reflect/transmit selection probability,
// which is the Fresnel reflectance of the sampled (micro)normal. Microfacet normals are drawn
// from D(m) m.z (not visible normals); a normal facing away from wo makes the sample fail, so
// the rough pdfs integrate to the success probability (< 1 at grazing angles).
// An index-matched interface (eta == 1) is treated as smooth whatever alpha: every microfacet
// then refracts straight through, a delta event.
#pragma once

#include <limits>

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/bsdf/ggx.h"
#include "kernels/physics/sampling.h"

namespace snee {

// Roughness below which an interface is smooth (a delta BSDF). A rough lobe is only as good as
// the half vector rebuilt from a direction pair: after the refraction, the weighted sum and the
// normalisation it is off by about 4 float epsilons of angle, which changes D(h) by up to
// 2 * 4 eps / alpha relative. Holding that to 1% needs alpha >= 800 eps = 9.5e-5; below, the
// rebuilt pdfs (NEE, MIS weights, SNEE's exit pdfs) disagree with the sampled ones, so pt and
// snee drift apart, and near 1e-9 D overflows float (black objects, NaN). A lobe this narrow
// (0.005 degrees) is invisible, so treating it as smooth changes no image.
inline constexpr float kSmoothRoughness = 800.0f * std::numeric_limits<float>::epsilon();

// The interface of one lane type F (core/lane_math.h): float for the scalar functions, a batch
// for kernels/simd, each lane with its own interface.
template <lane::Lane F>
struct DielectricT {
  F eta = F(1.5f);    // interior / exterior
  F alpha = F(0.0f);  // below kSmoothRoughness: smooth
  lane::MaskOf<F> smooth() const { return !(alpha >= F(kSmoothRoughness)); }
  lane::MaskOf<F> delta() const { return smooth() || eta == F(1.0f); }
  // The same interface at a scalar lane type G (double, for SNEE's scalar code).
  template <class G>
  DielectricT<G> as() const {
    return {G(eta), G(alpha)};
  }
};
using DielectricParams = DielectricT<float>;

template <lane::Lane F>
struct BsdfSampleT {
  lane::Vec3Of<F> wi;  // sampled light-side direction (away from the surface)
  F f = F(0.0f);       // BSDF value (for delta lobes: the value that multiplies the delta)
  F pdf = F(0.0f);     // solid-angle pdf (for delta lobes: the discrete lobe probability)
  lane::MaskOf<F> transmission = lane::MaskOf<F>(false);
  lane::MaskOf<F> delta = lane::MaskOf<F>(false);
  lane::MaskOf<F> valid = lane::MaskOf<F>(false);
};
using BsdfSample = BsdfSampleT<float>;

// Samples wi given wo. u_lobe picks reflection vs transmission; u picks the microfacet normal.
// An invalid sample is all zero.
BsdfSample dielectric_sample(const DielectricParams& p, Vec3 wo, Vec2 u, float u_lobe);
// f(wo <- wi); 0 for a delta interface (delta lobes are never evaluated).
float dielectric_eval(const DielectricParams& p, Vec3 wo, Vec3 wi);
// Pdf of dielectric_sample producing wi from wo (solid angle); 0 for a delta interface.
float dielectric_pdf(const DielectricParams& p, Vec3 wo, Vec3 wi);

// Transmission-only sampling used by SNEE (docs/method.md 4.4): given direction g on one side,
// produce s on the other side by refracting through a GGX-sampled normal (or the macro normal
// when delta). No lobe selection factor. Returns false on TIR, if the normal faces away from g,
// or if s ends on g's side.
bool dielectric_sample_transmission(const DielectricParams& p, Vec3 g, Vec2 u, Vec3* s);
// p^T_btdf(s | g) in solid angle; 0 for invalid pairs and for delta interfaces.
float dielectric_transmission_pdf(const DielectricParams& p, Vec3 g, Vec3 s);

// The straight-line form of the samplers over lane type F: both lobes (and, where an F holds
// smooth and rough interfaces together, both paths) computed and then selected, so a batch of
// lanes gets bit for bit what the scalar functions above get lane by lane.
namespace dielectric_lanes {

// Index of refraction on the side of the surface that w (with z component wz) points into.
template <lane::Lane F>
F side_index(F wz, F eta) {
  using namespace lane;
  return select(wz > F(0.0f), F(1.0f), eta);
}
template <lane::Lane F>
F other_side_index(F wz, F eta) {
  using namespace lane;
  return select(wz > F(0.0f), eta, F(1.0f));
}

template <lane::Lane F>
struct Lobe {
  F f, pdf;
  lane::MaskOf<F> ok;  // f and pdf are meaningless where false
};

// Reflection of the pair (wo, wi), both on one side, off the microfacet normal h (h.z > 0). The
// sampler only uses normals that face wo from its side, which the chi+ factor of G1 also needs.
template <lane::Lane F>
Lobe<F> rough_reflection(const DielectricT<F>& p, const lane::Vec3Of<F>& wo,
                         const lane::Vec3Of<F>& wi, const lane::Vec3Of<F>& h) {
  using namespace lane;
  const F wo_h = dot(wo, h);
  const F c = abs(wo_h);
  const F fresnel = fresnel_dielectric(c, other_side_index(wo.z, p.eta) / side_index(wo.z, p.eta));
  const F d = ggx_d(h, p.alpha);
  const F g = ggx_g1(wo, h, p.alpha) * ggx_g1(wi, h, p.alpha);
  return {fresnel * d * g / (F(4.0f) * abs(wo.z) * abs(wi.z)), d * h.z * fresnel / (F(4.0f) * c),
          !(wo_h * wo.z <= F(0.0f))};
}

// Transmission of the pair (wo, wi), on opposite sides, through h (h.z > 0): Walter et al. 2007
// eq. 21 for f, and the half-vector Jacobian with the sampled direction's index (wi's) in the
// numerator for the pdf (docs/method.md 4.4).
template <lane::Lane F>
Lobe<F> rough_transmission(const DielectricT<F>& p, const lane::Vec3Of<F>& wo,
                           const lane::Vec3Of<F>& wi, const lane::Vec3Of<F>& h) {
  using namespace lane;
  const F one(1.0f), zero(0.0f);
  const F wo_h = dot(wo, h), wi_h = dot(wi, h);
  const F eta_o = side_index(wo.z, p.eta), eta_i = side_index(wi.z, p.eta);
  // F is the same from both sides of the pair; from the denser side near the critical angle
  // eta^2 - 1 + cos^2 cancels and loses most digits, so evaluate it from the rarer side (the
  // arguments are selected, not two results: one evaluation per lane).
  const MaskOf<F> from_o = eta_o <= eta_i;
  const F fresnel = fresnel_dielectric(select(from_o, abs(wo_h), abs(wi_h)),
                                       select(from_o, eta_i / eta_o, eta_o / eta_i));
  const F denom = eta_i * wi_h + eta_o * wo_h;
  const F denom2 = denom * denom;
  const F d = ggx_d(h, p.alpha);
  const F g = ggx_g1(wo, h, p.alpha) * ggx_g1(wi, h, p.alpha);
  const F f =
      abs(wi_h * wo_h) / abs(wi.z * wo.z) * eta_o * eta_o * (one - fresnel) * g * d / denom2;
  const F pdf = d * h.z * (one - fresnel) * eta_i * eta_i * abs(wi_h) / denom2;
  return {f, pdf,
          !(wo_h * wo.z <= zero || wi_h * wi.z <= zero) && !(fresnel >= one || denom == zero)};
}

template <lane::Lane F>
BsdfSampleT<F> smooth_sample(const DielectricT<F>& p, const lane::Vec3Of<F>& wo, F u_lobe) {
  using namespace lane;
  using V = Vec3Of<F>;
  const F one(1.0f), zero(0.0f);
  const F eta_o = side_index(wo.z, p.eta), eta_t = other_side_index(wo.z, p.eta);
  const F cos_o = abs(wo.z);
  const F fresnel = fresnel_dielectric(cos_o, eta_t / eta_o);
  const MaskOf<F> reflects = u_lobe < fresnel;
  const Refracted<F> t =
      refract(wo, V{zero, zero, select(wo.z > zero, one, F(-1.0f))}, eta_o / eta_t);
  const F ratio = eta_o / eta_t;
  BsdfSampleT<F> s;
  s.wi = select(reflects, V{neg(wo.x), neg(wo.y), wo.z}, t.direction);
  s.f = select(reflects, fresnel / cos_o, ratio * ratio * (one - fresnel) / abs(t.direction.z));
  s.pdf = select(reflects, fresnel, one - fresnel);
  s.transmission = !reflects;
  s.delta = MaskOf<F>(true);
  s.valid = reflects || (t.ok && t.direction.z != zero);
  return s;
}

template <lane::Lane F>
BsdfSampleT<F> rough_sample(const DielectricT<F>& p, const lane::Vec3Of<F>& wo, F u0, F u1,
                            F u_lobe) {
  using namespace lane;
  const F zero(0.0f);
  const Vec3Of<F> m = ggx_sample_normal(u0, u1, p.alpha);
  const Vec3Of<F> m_side = select(wo.z > zero, m, -m);
  const F c = dot(wo, m_side);
  const F eta_o = side_index(wo.z, p.eta), eta_t = other_side_index(wo.z, p.eta);
  const F fresnel = fresnel_dielectric(c, eta_t / eta_o);
  const MaskOf<F> reflects = u_lobe < fresnel;
  const Vec3Of<F> wr = reflect(wo, m_side);
  const Refracted<F> wt = refract(wo, m_side, eta_o / eta_t);
  const Lobe<F> r = rough_reflection(p, wo, wr, m);
  const Lobe<F> t = rough_transmission(p, wo, wt.direction, m);
  BsdfSampleT<F> s;
  s.wi = select(reflects, wr, wt.direction);
  s.f = select(reflects, r.f, t.f);
  s.pdf = select(reflects, r.pdf, t.pdf);
  s.transmission = !reflects;
  s.delta = MaskOf<F>(false);
  s.valid = !(c <= zero) &&
            select_mask(reflects, !(wr.z * wo.z <= zero) && r.ok,
                        wt.ok && !(wt.direction.z * wo.z >= zero) && t.ok) &&
            s.pdf > zero;
  return s;
}

}  // namespace dielectric_lanes

// Invalid lanes report valid = false and nothing else. An F of only smooth or only rough
// interfaces (the usual case: one material) computes only that path.
template <lane::Lane F>
BsdfSampleT<F> dielectric_sample(const DielectricT<F>& p, const lane::Vec3Of<F>& wo, F u0, F u1,
                                 F u_lobe) {
  using namespace lane;
  using namespace dielectric_lanes;
  const MaskOf<F> delta = p.delta();
  const MaskOf<F> facing = !(wo.z == F(0.0f));
  if (all(delta)) {
    BsdfSampleT<F> s = smooth_sample(p, wo, u_lobe);
    s.valid = facing && s.valid;
    return s;
  }
  BsdfSampleT<F> s = rough_sample(p, wo, u0, u1, u_lobe);
  if (any(delta)) {
    const BsdfSampleT<F> smooth = smooth_sample(p, wo, u_lobe);
    s.wi = select(delta, smooth.wi, s.wi);
    s.f = select(delta, smooth.f, s.f);
    s.pdf = select(delta, smooth.pdf, s.pdf);
    s.transmission = select_mask(delta, smooth.transmission, s.transmission);
    s.valid = select_mask(delta, smooth.valid, s.valid);
    s.delta = delta;
  }
  s.valid = facing && s.valid;
  return s;
}

// g on one side refracted to the other through the macro normal (delta lanes) or a GGX normal
// facing g; `ok` is false where the sample fails.
template <lane::Lane F>
Refracted<F> dielectric_sample_transmission(const DielectricT<F>& p, const lane::Vec3Of<F>& g, F u0,
                                            F u1) {
  using namespace lane;
  using namespace dielectric_lanes;
  using V = Vec3Of<F>;
  const F zero(0.0f), one(1.0f);
  const MaskOf<F> outside = g.z > zero;
  const MaskOf<F> delta = p.delta();
  const V macro{zero, zero, select(outside, one, F(-1.0f))};
  V normal = macro;
  if (!all(delta)) {
    const V m = ggx_sample_normal(u0, u1, p.alpha);
    normal = select(delta, macro, select(outside, m, -m));
  }
  Refracted<F> s = refract(g, normal, side_index(g.z, p.eta) / other_side_index(g.z, p.eta));
  s.ok = !(g.z == zero) && s.ok &&
         select_mask(delta, !(s.direction.z == zero),
                     dot(g, normal) > zero && s.direction.z * g.z < zero);
  return s;
}

// A transmission pair through a rough interface in its local frame (outward normal +z):
// local_in on the medium side, local_out outside. Its generalised half vector (oriented to +z)
// and dielectric_transmission_pdf in both directions, which share it.
template <lane::Lane F>
struct TransmissionPair {
  lane::Vec3Of<F> h;
  F inward;   // pdf of local_in given local_out (light side to medium side)
  F outward;  // pdf of local_out given local_in
};

template <lane::Lane F>
TransmissionPair<F> transmission_pair(const DielectricT<F>& p, const lane::Vec3Of<F>& local_in,
                                      const lane::Vec3Of<F>& local_out) {
  using namespace lane;
  const F zero(0.0f);
  Vec3Of<F> h = local_in * p.eta + local_out;
  h = h / sqrt(dot(h, h));
  h = select(h.z < zero, -h, h);
  const F in_h = dot(local_in, h), out_h = dot(local_out, h);
  const MaskOf<F> ok = h.z > zero && in_h * local_in.z > zero && out_h * local_out.z > zero &&
                       local_in.z * local_out.z < zero;
  const F denom = out_h + p.eta * in_h;
  const F d_h = ggx_d(h, p.alpha) * h.z / (denom * denom);
  return {h, select(ok, d_h * p.eta * p.eta * abs(in_h), zero), select(ok, d_h * abs(out_h), zero)};
}

}  // namespace snee
