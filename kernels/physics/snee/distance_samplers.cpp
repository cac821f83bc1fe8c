#include "kernels/physics/snee/distance_samplers.h"

#include <cmath>

#include "core/vec3d.h"
#include "kernels/physics/medium/free_flight.h"

namespace snee {

DistanceSample equiangular_sample(Vec3 o, Vec3 w, Vec3 c, float u) {
  const Equiangular<double> e{Vec3d(o), Vec3d(w), Vec3d(c)};
  if (!e.usable()) return {};
  const double t = e.sample(u);
  const float tf = static_cast<float>(t);
  if (!(tf >= 0) || !std::isfinite(tf)) return {};
  return {tf, static_cast<float>(e.density(t)), true};
}

float equiangular_pdf(Vec3 o, Vec3 w, Vec3 c, float t) {
  return static_cast<float>(Equiangular<double>(Vec3d(o), Vec3d(w), Vec3d(c)).density(t));
}

DistanceSample distance_mixture_sample(const DistanceMixture& m, float u_technique, float u_channel,
                                       float u) {
  float t = 0;
  if (u_technique < m.c_exponential) {
    t = free_flight_sample(m.sigma_t, u_channel, u);
  } else {
    const DistanceSample s = equiangular_sample(m.o, m.w, m.c, u);
    if (!s.valid) return {};
    t = s.t;
  }
  if (!(t >= 0) || !std::isfinite(t)) return {};
  const float pdf = distance_mixture_pdf(m, t);
  if (!(pdf > 0)) return {};
  return {t, pdf, true};
}

float distance_mixture_pdf(const DistanceMixture& m, float t) {
  if (!(t >= 0)) return 0.0f;
  const double flight = free_flight_pdf<double>(Vec3d(m.sigma_t), t);
  return static_cast<float>(distance_mixture_pdf<double>(
      m.c_exponential, flight, Equiangular<double>(Vec3d(m.o), Vec3d(m.w), Vec3d(m.c)), t));
}

}  // namespace snee
