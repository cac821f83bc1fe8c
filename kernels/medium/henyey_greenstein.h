// Henyey-Greenstein phase function over *propagation* directions (g > 0 scatters forward),
// docs/method.md 1.1.
#pragma once

#include "kernels/lane_math.h"
#include "kernels/sampling.h"

namespace snee {

// cos_theta = dot(w_before, w_after).
// 1 + g^2 - 2 g mu is written as (1 - |g|)^2 + 2|g|(1 -+ mu): a sum of non-negative terms, so
// strongly peaked lobes do not lose their peak to cancellation. F is the lane type
// (kernels/lane_math.h); both forms are computed and selected by the sign of g.
template <class F>
F hg_phase(F cos_theta, F g) {
  using namespace lane;
  const F one(1.0f), two(2.0f);
  const F forward = (one - g) * (one - g) + two * g * (one - cos_theta);
  const F backward = (one + g) * (one + g) - two * g * (one + cos_theta);
  const F denom = select(g >= F(0.0f), forward, backward);
  return F(kInv4Pi) * (one - g * g) / (denom * sqrt(denom));
}

// The scalar form, which also takes arguments that convert to float.
inline float hg_phase(float cos_theta, float g) {
  return hg_phase<float>(cos_theta, g);
}

// Samples a propagation direction after scattering, given the direction before. *pdf = hg_phase.
Vec3 hg_sample(Vec3 w_before, float g, Vec2 u, float* pdf);

}  // namespace snee
