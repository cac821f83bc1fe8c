// Bottom-to-top placement of the middle vertex x_j between a medium vertex x_i and an exit point
// x_k (docs/method.md 3.4 and Appendix A). The geometric lobe draws x_j over all of R^3 with
// density proportional to 1 / (r_ij^2 r_jk^2), the product of the two inverse-square geometry terms
// of the connection x_i -> x_j -> x_k:
//   p(x_j) = d / (pi^3 r_ij^2 r_jk^2),  d = |x_k - x_i|,
// by choosing the direction at x_i with density (pi - gamma) / (pi^3 sin gamma), gamma the angle
// to x_k, and then the distance equiangularly toward x_k along that half-line. For an anisotropic
// phase function the direction is instead a one-sample mixture of that lobe (weight c_joint) and
// the phase function at x_i; the distance step is unchanged. Points outside the medium are
// produced too; the caller rejects them with a visibility test.
//
// Written once over the lane type F (core/lane_math.h): double for the scalar functions, a float
// batch for the subdivision stage. It never forms pi - gamma or pi/2 - theta by cancellation,
// so float keeps its digits: the geometric lobe's pi - gamma = pi sqrt(1 - u) comes straight
// from the inverse CDF, the phase lobe's from atan2(sin gamma, -cos gamma), and the equiangular
// step uses psi = pi/2 - theta = (1 - u3)(pi - gamma) with tan(theta) = cot(psi); the density
// from the sampling variables uses r_jk = h / sin(psi), the density from the points has the
// geometric lobe's (pi - gamma) / sin(gamma) factors cancelled against r_jk^2.
#pragma once

#include <limits>
#include <numbers>
#include <span>

#include "core/math.h"
#include "kernels/physics/medium/henyey_greenstein.h"

namespace snee {

template <lane::Lane F>
struct JointImportanceT {
  lane::Vec3Of<F> x_i;       // medium vertex the connection starts from
  lane::Vec3Of<F> omega_in;  // propagation direction arriving at x_i
  lane::Vec3Of<F> x_k;       // exit point the connection ends at
  F g;                       // Henyey-Greenstein asymmetry at x_i
  float c_joint = 0.5f;
};
using JointImportance = JointImportanceT<float>;

template <lane::Lane F>
struct JointImportanceSampleT {
  lane::Vec3Of<F> x_j;
  F pdf;  // volume density, computed from the sampling variables
  lane::MaskOf<F> valid;
};

namespace joint_importance_detail {

template <lane::Lane F>
F inv_pi_cubed() {
  return F(static_cast<float>(1.0 / (std::numbers::pi * std::numbers::pi * std::numbers::pi)));
}

// Probability of the geometric direction lobe; the phase lobe takes the rest.
template <lane::Lane F>
F geometric_lobe_weight(F g, float c_joint) {
  using namespace lane;
  return select(g == F(0.0f), F(1.0f), F(c_joint));
}

}  // namespace joint_importance_detail

// u0 picks the direction technique (ignored when g == 0), u1, u2 the direction, u3 the distance.
template <lane::Lane F>
JointImportanceSampleT<F> joint_importance_sample(const JointImportanceT<F>& j, F u0, F u1, F u2,
                                                  F u3) {
  using namespace lane;
  using V = Vec3Of<F>;
  const F zero(0.0f), one(1.0f), pi(kPi);
  const V ik = j.x_k - j.x_i;
  const F d = sqrt(dot(ik, ik));
  const V a = ik / d;
  const F geometric_weight = joint_importance_detail::geometric_lobe_weight(j.g, j.c_joint);
  const MaskOf<F> geometric = u0 < geometric_weight;

  // Geometric lobe: p(gamma) = 2 (pi - gamma) / pi^2 about the direction to x_k.
  const F pi_minus_gamma_geo = pi * sqrt(one - u1);
  const auto [sin_gamma_geo, cos_pmg] = lane::sincos(pi_minus_gamma_geo);
  const V around = FrameT<V>::from_normal(a).to_world(
      spherical_direction(sin_gamma_geo, neg(cos_pmg), F(2.0f * kPi) * u2));
  // Phase lobe: HG about the incoming direction.
  V phase = hg_sample(j.omega_in, j.g, u1, u2).direction;
  phase = phase / sqrt(dot(phase, phase));
  const V w = select(geometric, around, phase);

  const V w_cross_a = cross(w, a);
  const F sin_gamma = select(geometric, sin_gamma_geo, sqrt(dot(w_cross_a, w_cross_a)));
  const F cos_gamma = select(geometric, neg(cos_pmg), dot(w, a));
  const F pi_minus_gamma =
      select(geometric, pi_minus_gamma_geo, lane::atan2(sin_gamma, neg(cos_gamma)));

  // Equiangular step toward x_k along x_i + s w: closest approach at s = delta, distance h.
  const F delta = d * cos_gamma, h = d * sin_gamma;
  const F psi = (one - u3) * pi_minus_gamma;
  const auto [sin_psi, cos_psi] = lane::sincos(psi);
  const F s = delta + h * cos_psi / sin_psi;
  JointImportanceSampleT<F> out;
  out.x_j = j.x_i + w * s;

  const F direction_density =
      geometric_weight * pi_minus_gamma * joint_importance_detail::inv_pi_cubed<F>() / sin_gamma +
      select(geometric_weight < one, (one - geometric_weight) * hg_phase(dot(j.omega_in, w), j.g),
             zero);
  out.pdf = direction_density * sin_psi * sin_psi / (pi_minus_gamma * h * s * s);
  const F inf(std::numeric_limits<float>::infinity());
  const auto finite = [&](F x) { return abs(x) < inf; };
  out.valid = d > zero && sin_gamma > zero && pi_minus_gamma > zero && s > zero && finite(s) &&
              finite(out.x_j.x) && finite(out.x_j.y) && finite(out.x_j.z) && out.pdf > zero;
  return out;
}

// The density at x_j from the connection's geometry: d = |x_k - x_i|, the unit directions from
// x_i to x_j and to x_k, the phase function at x_i toward x_j and the squared lengths of both
// edges. `placed` is false where the sampler cannot produce x_j (on the line through x_i and
// x_k), and the density is then meaningless.
template <lane::Lane F>
struct JointImportanceDensity {
  F pdf;
  lane::MaskOf<F> placed;
};

template <lane::Lane F>
JointImportanceDensity<F> joint_importance_density(F g, float c_joint, F d,
                                                   const lane::Vec3Of<F>& omega_ij,
                                                   const lane::Vec3Of<F>& omega_ik, F phase_i,
                                                   F r_ij2, F r_jk2) {
  using namespace lane;
  const F zero(0.0f), one(1.0f);
  const Vec3Of<F> ij_cross_ik = cross(omega_ij, omega_ik);
  const F sin_gamma = sqrt(dot(ij_cross_ik, ij_cross_ik));
  const F pi_minus_gamma = lane::atan2(sin_gamma, neg(dot(omega_ij, omega_ik)));
  const F geometric = joint_importance_detail::geometric_lobe_weight(g, c_joint);
  const F pdf = (geometric * d * joint_importance_detail::inv_pi_cubed<F>() +
                 select(geometric < one,
                        (one - geometric) * phase_i * d * sin_gamma / pi_minus_gamma, zero)) /
                (r_jk2 * r_ij2);
  return {pdf, sin_gamma > zero && pi_minus_gamma > zero};
}

// Random numbers: u[0] picks the direction technique (ignored when g == 0), u[1], u[2] the
// direction, u[3] the distance.
inline constexpr int kJointImportanceDimensions = 4;
struct JointImportanceSample {
  Vec3 x_j;
  float pdf = 0;  // volume density, computed from the sampling variables
  bool valid = false;
};
// The scalar forms, in double.
JointImportanceSample joint_importance_sample(const JointImportance& j,
                                              std::span<const float, kJointImportanceDimensions> u);
// Volume density of joint_importance_sample at x_j; 0 where the sampler cannot produce x_j.
float joint_importance_pdf(const JointImportance& j, Vec3 x_j);

}  // namespace snee
