#include "kernels/physics/snee/joint_importance.h"

#include "core/vec3d.h"

namespace snee {

namespace {

JointImportanceT<double> in_double(const JointImportance& j) {
  return {Vec3d(j.x_i), Vec3d(j.omega_in), Vec3d(j.x_k), j.g, j.c_joint};
}

}  // namespace

JointImportanceSample joint_importance_sample(
    const JointImportance& j, std::span<const float, kJointImportanceDimensions> u) {
  const JointImportanceSampleT<double> s =
      joint_importance_sample<double>(in_double(j), u[0], u[1], u[2], u[3]);
  const Vec3 x_j(s.x_j);
  if (!s.valid || !is_finite(x_j)) return {};
  return {x_j, static_cast<float>(s.pdf), true};
}

float joint_importance_pdf(const JointImportance& j, Vec3 x_j) {
  const Vec3d x_i(j.x_i), x_k(j.x_k), at(x_j);
  const Vec3d ik = x_k - x_i, ij = at - x_i, jk = x_k - at;
  const double d2 = dot(ik, ik), r_ij2 = dot(ij, ij), r_jk2 = dot(jk, jk);
  if (!(d2 > 0) || !(r_ij2 > 0) || !(r_jk2 > 0)) return 0.0f;
  const Vec3d omega_ij = ij / std::sqrt(r_ij2);
  const double phase_i = hg_phase<double>(dot(Vec3d(j.omega_in), omega_ij), j.g);
  const JointImportanceDensity<double> density = joint_importance_density<double>(
      j.g, j.c_joint, std::sqrt(d2), omega_ij, ik / std::sqrt(d2), phase_i, r_ij2, r_jk2);
  return density.placed ? static_cast<float>(density.pdf) : 0.0f;
}

}  // namespace snee
