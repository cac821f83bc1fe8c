// Henyey-Greenstein phase function over *propagation* directions (g > 0 scatters forward),
// docs/method.md 1.1.
#pragma once

#include "kernels/sampling.h"

namespace snee {

// cos_theta = dot(w_before, w_after).
// 1 + g^2 - 2 g mu is written as (1 - |g|)^2 + 2|g|(1 -+ mu): a sum of non-negative terms, so
// strongly peaked lobes do not lose their peak to cancellation.
inline float hg_phase(float cos_theta, float g) {
  const float denom = g >= 0.0f ? sqr(1.0f - g) + 2.0f * g * (1.0f - cos_theta)
                                : sqr(1.0f + g) - 2.0f * g * (1.0f + cos_theta);
  return kInv4Pi * (1.0f - g * g) / (denom * std::sqrt(denom));
}

// Samples a propagation direction after scattering, given the direction before. *pdf = hg_phase.
Vec3 hg_sample(Vec3 w_before, float g, Vec2 u, float* pdf);

}  // namespace snee
