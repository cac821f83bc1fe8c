#include "kernels/physics/snee/exit_guide.h"

#include <algorithm>
#include <cmath>

namespace snee {

ExitGuide exit_guide(const ProbeTargets& targets, Vec3 centre, float radius, float eta, Vec3 x) {
  ExitGuide guide;
  for (int t = 0; t < targets.count; ++t) {
    const ProbeTarget& target = targets.target[static_cast<size_t>(t)];
    add_exit_guide_axes(guide, target.share, x,
                        target.positional
                            ? sphere_exits_toward_point(centre, radius, eta, target.where, x)
                            : sphere_exits_toward_light(centre, radius, eta, target.where, x));
  }
  return guide;
}

float exit_guide_cap_cosine(float degrees) {
  return std::cos(degrees * kPi / 180.0f);
}

float exit_guide_pdf(const ExitGuide& guide, float cap_cosine, Vec3 w) {
  float inside = 0;
  for (int k = 0; k < guide.count; ++k) {
    if (dot(w, guide.axis[static_cast<size_t>(k)]) >= cap_cosine)
      inside += guide.probability[static_cast<size_t>(k)];
  }
  return inside * uniform_cone_pdf(cap_cosine);
}

bool exit_guide_sample(const ExitGuide& guide, float cap_cosine, float u_axis, Vec2 u, Vec3* w) {
  for (int k = 0; k < guide.count; ++k) {
    const float p = guide.probability[static_cast<size_t>(k)];
    if (u_axis < p) {
      const Frame frame = Frame::from_normal(guide.axis[static_cast<size_t>(k)]);
      *w = normalize(frame.to_world(sample_uniform_cone(u, cap_cosine)));
      return true;
    }
    u_axis -= p;
  }
  return false;
}

float sphere_exit_distance(Vec3 centre, float radius, Vec3 x, Vec3 w) {
  // |x + t w - c| = r with |x - c| < r: the positive root of t^2 + 2 b t + c = 0.
  const Vec3 o = x - centre;
  const float b = dot(o, w);
  const float c = dot(o, o) - radius * radius;
  const float disc = std::max(0.0f, b * b - c);
  const float root = std::sqrt(disc);
  // The larger root, written so it does not cancel when b > 0.
  return b > 0 ? -c / (b + root) : root - b;
}

}  // namespace snee
