// joint_importance_sample (kernels/physics/snee/joint_importance.cpp) for a batch of lanes, in
// float. The scalar sampler works in double because it forms pi - gamma and pi/2 - theta by
// cancellation and takes tan(theta) next to its pole; this one never forms them: the geometric
// lobe's pi - gamma = pi sqrt(1 - u) comes straight from the inverse CDF, the phase lobe's from
// atan2(sin gamma, -cos gamma), and the equiangular step uses psi = pi/2 - theta =
// (1 - u3)(pi - gamma) with tan(theta) = cot(psi). The density uses the same variables:
// r_jk = h / sin(psi). Agreement with the scalar sampler is measured in
// tests/test_snee_batch.cpp and stated in README.md.
#pragma once

#include <limits>
#include <numbers>

#include "kernels/simd/hg_sample_batch.h"

namespace snee::simd {

struct JointImportanceBatch {
  Vec3Batch x_i, omega_in, x_k;
  FloatBatch g;
  float c_joint = 0.5f;
};

struct JointImportanceSampleBatch {
  Vec3Batch x_j;
  FloatBatch pdf;
  BoolBatch valid;
};

inline JointImportanceSampleBatch joint_importance_sample(const JointImportanceBatch& j,
                                                          FloatBatch u0, FloatBatch u1,
                                                          FloatBatch u2, FloatBatch u3) {
  const FloatBatch zero(0.0f), one(1.0f), pi(kPi);
  const Vec3Batch ik = sub(j.x_k, j.x_i);
  const FloatBatch d = xsimd::sqrt(dot(ik, ik));
  const Vec3Batch a = div(ik, d);
  const FloatBatch geometric_weight = xsimd::select(j.g == zero, one, FloatBatch(j.c_joint));
  const BoolBatch geometric = u0 < geometric_weight;

  // Geometric lobe: p(gamma) = 2 (pi - gamma) / pi^2 about the direction to x_k.
  const FloatBatch pi_minus_gamma_geo = pi * xsimd::sqrt(one - u1);
  const auto [sin_gamma_geo, cos_pmg] = lanewise_sincos(pi_minus_gamma_geo);
  const Vec3Batch around = FrameBatch::from_normal(a).to_world(
      spherical_direction(sin_gamma_geo, neg(cos_pmg), FloatBatch(2.0f * kPi) * u2));
  // Phase lobe: HG about the incoming direction.
  Vec3Batch phase = hg_sample(j.omega_in, j.g, u1, u2).direction;
  phase = div(phase, xsimd::sqrt(dot(phase, phase)));
  const Vec3Batch w = select(geometric, around, phase);

  const Vec3Batch w_cross_a = cross(w, a);
  const FloatBatch sin_gamma =
      xsimd::select(geometric, sin_gamma_geo, xsimd::sqrt(dot(w_cross_a, w_cross_a)));
  const FloatBatch cos_gamma = xsimd::select(geometric, neg(cos_pmg), dot(w, a));
  const FloatBatch pi_minus_gamma =
      xsimd::select(geometric, pi_minus_gamma_geo, simd::atan2(sin_gamma, neg(cos_gamma)));

  // Equiangular step toward x_k along x_i + s w.
  const FloatBatch delta = d * cos_gamma, h = d * sin_gamma;
  const FloatBatch psi = (one - u3) * pi_minus_gamma;
  const auto [sin_psi, cos_psi] = lanewise_sincos(psi);
  const FloatBatch s = delta + h * cos_psi / sin_psi;
  JointImportanceSampleBatch out;
  out.x_j = add(j.x_i, scale(w, s));

  const FloatBatch inv_pi3(
      static_cast<float>(1.0 / (std::numbers::pi * std::numbers::pi * std::numbers::pi)));
  const FloatBatch direction_density =
      geometric_weight * pi_minus_gamma * inv_pi3 / sin_gamma +
      xsimd::select(geometric_weight < one,
                    (one - geometric_weight) * hg_phase(dot(j.omega_in, w), j.g), zero);
  out.pdf = direction_density * sin_psi * sin_psi / (pi_minus_gamma * h * s * s);
  const FloatBatch inf(std::numeric_limits<float>::infinity());
  const auto finite = [&](FloatBatch x) { return xsimd::abs(x) < inf; };
  out.valid = d > zero && sin_gamma > zero && pi_minus_gamma > zero && s > zero && finite(s) &&
              finite(out.x_j.x) && finite(out.x_j.y) && finite(out.x_j.z) && out.pdf > zero;
  return out;
}

}  // namespace snee::simd
