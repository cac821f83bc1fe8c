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
#pragma once

#include <span>

#include "core/math.h"

namespace snee {

struct JointImportance {
  Vec3 x_i;       // medium vertex the connection starts from
  Vec3 omega_in;  // propagation direction arriving at x_i
  Vec3 x_k;       // exit point the connection ends at
  float g = 0;    // Henyey-Greenstein asymmetry at x_i
  float c_joint = 0.5f;
};

struct JointImportanceSample {
  Vec3 x_j;
  float pdf = 0;  // volume density, computed from the sampling variables
  bool valid = false;
};

// Random numbers: u[0] picks the direction technique (ignored when g == 0), u[1], u[2] the
// direction, u[3] the distance.
inline constexpr int kJointImportanceDimensions = 4;
JointImportanceSample joint_importance_sample(const JointImportance& j,
                                              std::span<const float, kJointImportanceDimensions> u);
// Volume density of joint_importance_sample at x_j; 0 where the sampler cannot produce x_j.
float joint_importance_pdf(const JointImportance& j, Vec3 x_j);

}  // namespace snee
