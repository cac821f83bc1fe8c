#include "kernels/physics/snee/probe.h"

#include "core/vec3d.h"

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
  return probe_area_pdf<double>(kind, Vec3d(omega_in), g, Vec3d(x_i), Vec3d(x_k), Vec3d(n_k));
}

}  // namespace snee
