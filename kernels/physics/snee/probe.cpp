#include "kernels/physics/snee/probe.h"

#include <cmath>

#include "kernels/physics/medium/henyey_greenstein.h"

namespace snee {

Vec3 probe_direction_sample(ProbeDirections kind, Vec3 omega_in, float g, Vec2 u) {
  if (kind == ProbeDirections::kPhaseFunction) {
    float pdf;
    return hg_sample(omega_in, g, u, &pdf);
  }
  return sample_uniform_sphere(u);
}

float probe_direction_pdf(ProbeDirections kind, Vec3 omega_in, float g, Vec3 w) {
  if (kind == ProbeDirections::kPhaseFunction) return hg_phase(dot(omega_in, w), g);
  return uniform_sphere_pdf();
}

double probe_area_pdf(ProbeDirections kind, Vec3 omega_in, float g, Vec3 x_i, Vec3 x_k, Vec3 n_k) {
  const double x = static_cast<double>(x_k.x) - x_i.x, y = static_cast<double>(x_k.y) - x_i.y,
               z = static_cast<double>(x_k.z) - x_i.z;
  const double d2 = x * x + y * y + z * z;
  if (!(d2 > 0)) return 0.0;
  const double d = std::sqrt(d2);
  const Vec3 w(static_cast<float>(x / d), static_cast<float>(y / d), static_cast<float>(z / d));
  const double cos_k = dot(n_k, w);
  if (!(cos_k > 0)) return 0.0;
  return probe_direction_pdf(kind, omega_in, g, w) * cos_k / d2;
}

}  // namespace snee
