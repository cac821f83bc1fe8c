// Henyey-Greenstein phase function over *propagation* directions (g > 0 scatters forward),
// docs/method.md 1.1.
#pragma once

#include "core/lane_math.h"
#include "kernels/physics/sampling.h"

namespace snee {

// cos_theta = dot(w_before, w_after).
// 1 + g^2 - 2 g mu is written as (1 - |g|)^2 + 2|g|(1 -+ mu): a sum of non-negative terms, so
// strongly peaked lobes do not lose their peak to cancellation. F is the lane type
// (core/lane_math.h); both forms are computed and selected by the sign of g.
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

template <lane::Lane F>
struct HgSample {
  lane::Vec3Of<F> direction;
  F pdf;  // hg_phase of the sampled direction
};

// Samples a propagation direction after scattering, given the direction before; u0 and u1 are
// uniform in [0, 1). The inverse CDF of docs/method.md 1.1, mu = (1 + g^2 - r^2) / 2g with
// r = (1 - g^2) / (1 + g s) and s = 2u - 1, multiplied out so the division by g cancels. It is
// then exact as g -> 0 (mu = s, uniform) and needs no |g| < 1e-3 branch, whose uniform sampling
// would not match the pdf hg_phase reports. The azimuth's sine and cosine are lane::sincos.
template <lane::Lane F>
HgSample<F> hg_sample(const lane::Vec3Of<F>& w_before, F g, F u0, F u1) {
  const F one(1.0f), half(0.5f);
  const F s = F(2.0f) * u0 - one;
  const F num = s + g * (half * (F(3.0f) + s * s) + g * (s + half * g * (s * s - one)));
  const F den = one + g * s;
  const F cos_theta = lane::clamp(num / (den * den), F(-1.0f), one);
  const F sin_theta = safe_sqrt(one - cos_theta * cos_theta);
  const lane::Vec3Of<F> local = spherical_direction(sin_theta, cos_theta, F(2.0f * kPi) * u1);
  return {FrameT<lane::Vec3Of<F>>::from_normal(w_before).to_world(local), hg_phase(cos_theta, g)};
}

// The scalar form. *pdf = hg_phase.
inline Vec3 hg_sample(Vec3 w_before, float g, Vec2 u, float* pdf) {
  const HgSample<float> sample = hg_sample<float>(w_before, g, u.x, u.y);
  *pdf = sample.pdf;
  return sample.direction;
}

}  // namespace snee
