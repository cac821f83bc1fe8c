// Distance samplers along a ray o + t w, t in [0, inf), used by top-to-bottom subdivision to
// place the middle vertex x_j on the refracted light ray (docs/method.md 4.2). The distances are
// untruncated (Q3): a point beyond the boundary is rejected by a visibility test instead, so the
// pdfs can be evaluated for any path without knowing where the ray leaves the medium.
#pragma once

#include "core/math.h"

namespace snee {

// The ray o + t w seen from c, over the lane type F (core/lane_math.h): closest approach at
// t = delta, at distance h, and the range of angles at c that t in [0, inf) sweeps,
// atan2(h, -delta) (pi/2 minus the angle at which t = 0 is seen, without forming that
// difference, so float keeps its digits when c lies far behind the ray's start).
template <lane::Lane F>
struct Equiangular {
  F delta, h, range;
  Equiangular(const lane::Vec3Of<F>& o, const lane::Vec3Of<F>& w, const lane::Vec3Of<F>& c) {
    using namespace lane;
    const lane::Vec3Of<F> v = c - o;
    delta = dot(v, w);
    const lane::Vec3Of<F> p = v - w * delta;
    h = sqrt(dot(p, p));
    range = lane::atan2(h, neg(delta));
  }
  // Whether c lies off the ray's line, where the density is defined.
  lane::MaskOf<F> usable() const { return h > F(0.0f) && range > F(0.0f); }
  F density(F t) const {
    using namespace lane;
    const F r = t - delta, zero(0.0f);
    return select(usable() && t >= zero, h / (range * (h * h + r * r)), zero);
  }
  // The distance for u: the angle left to pi/2 is psi = (1 - u) range, and
  // t = delta + h tan(pi/2 - psi) = delta + h cot(psi), which never evaluates tan at its pole.
  F sample(F u) const {
    const auto [sin_psi, cos_psi] = lane::sincos((F(1.0f) - u) * range);
    return delta + h * cos_psi / sin_psi;
  }
};

struct DistanceSample {
  float t = 0;
  float pdf = 0;  // density of t, computed while sampling
  bool valid = false;
};

// Equiangular sampling toward a point c (Kulla & Fajardo 2012): the density is proportional to
// 1 / |o + t w - c|^2, so the inverse-square falloff of the connection to c is cancelled.
// Fails (and the pdf is 0) when c lies on the ray's line, where the density degenerates. These
// scalar forms are the templates in double.
DistanceSample equiangular_sample(Vec3 o, Vec3 w, Vec3 c, float u);
float equiangular_pdf(Vec3 o, Vec3 w, Vec3 c, float t);

// One-sample MIS of the tracer's free-flight sampler (probability c_exponential) and equiangular
// sampling toward c: sample from the mixture, always report the mixture density, which is the
// balance heuristic over the two techniques. u_technique picks the technique; u_channel is the
// free-flight sampler's colour channel; u the distance.
struct DistanceMixture {
  Rgb sigma_t;
  float c_exponential = 0.5f;
  Vec3 o, w, c;
};
DistanceSample distance_mixture_sample(const DistanceMixture& m, float u_technique, float u_channel,
                                       float u);
float distance_mixture_pdf(const DistanceMixture& m, float t);

// The mixture's density at t over the lane type F, from the free-flight density at t (flight)
// and the equiangular sampler toward c.
template <lane::Lane F>
F distance_mixture_pdf(float c_exponential, F flight, const Equiangular<F>& equiangular, F t) {
  return F(c_exponential > 0 ? c_exponential : 0.0f) * flight +
         F(c_exponential < 1 ? 1.0f - c_exponential : 0.0f) * equiangular.density(t);
}

}  // namespace snee
