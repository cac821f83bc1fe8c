// Distance samplers along a ray o + t w, t in [0, inf), used by top-to-bottom subdivision to
// place the middle vertex x_j on the refracted light ray (docs/method.md 4.2). The distances are
// untruncated (Q3): a point beyond the boundary is rejected by a visibility test instead, so the
// pdfs can be evaluated for any path without knowing where the ray leaves the medium.
#pragma once

#include "core/math.h"

namespace snee {

struct DistanceSample {
  float t = 0;
  float pdf = 0;  // density of t, computed while sampling
  bool valid = false;
};

// Equiangular sampling toward a point c (Kulla & Fajardo 2012): the density is proportional to
// 1 / |o + t w - c|^2, so the inverse-square falloff of the connection to c is cancelled.
// Fails (and the pdf is 0) when c lies on the ray's line, where the density degenerates.
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

}  // namespace snee
