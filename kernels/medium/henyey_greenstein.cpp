#include "kernels/medium/henyey_greenstein.h"

namespace snee {

Vec3 hg_sample(Vec3 w_before, float g, Vec2 u, float* pdf) {
  // The inverse CDF of docs/method.md 1.1, mu = (1 + g^2 - r^2) / 2g with r = (1 - g^2) / (1 + g s)
  // and s = 2u - 1, multiplied out so the division by g cancels. It is then exact as g -> 0
  // (mu = s, uniform) and needs no |g| < 1e-3 branch, whose uniform sampling would not match
  // the pdf hg_phase reports.
  const float s = 2.0f * u.x - 1.0f;
  const float num = s + g * (0.5f * (3.0f + s * s) + g * (s + 0.5f * g * (s * s - 1.0f)));
  const float den = 1.0f + g * s;
  const float cos_theta = std::clamp(num / (den * den), -1.0f, 1.0f);
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  const Vec3 local = spherical_direction(sin_theta, cos_theta, 2.0f * kPi * u.y);
  *pdf = hg_phase(cos_theta, g);
  return Frame::from_normal(w_before).to_world(local);
}

}  // namespace snee
