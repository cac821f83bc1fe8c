// Pinhole camera rays, written once over the lane type: the scalar function and the batched
// generation kernel (generate.cpp) run the same template, so they agree bit for bit.
#pragma once

#include <cstdint>

#include "kernels/kernel_context.h"

namespace snee {

struct PinholeCamera {
  Vec3 origin, forward, right, up;  // direction = forward + x right + y up, x, y in [-1, 1]
  uint32_t width;
  float inv_width, inv_height;
};

inline PinholeCamera pinhole_camera(const KernelContext& ctx) {
  return {ctx.camera_origin,
          ctx.camera_forward,
          ctx.camera_right,
          ctx.camera_up,
          static_cast<uint32_t>(ctx.width),
          1.0f / static_cast<float>(ctx.width),
          1.0f / static_cast<float>(ctx.height)};
}

// Unit direction through film position (px + u0, py + u1) for any lane type F
// (scene/lane_math.h); u0, u1 in [0, 1) jitter x and y.
template <lane::Lane F>
lane::Vec3Of<F> camera_direction(const PinholeCamera& c, F px, F py, F u0, F u1) {
  const F x = F(2.0f) * (px + u0) * F(c.inv_width) - F(1.0f);
  const F y = F(1.0f) - F(2.0f) * (py + u1) * F(c.inv_height);
  return normalize(splat<F>(c.forward) + splat<F>(c.right) * x + splat<F>(c.up) * y);
}

// Unit direction through pixel + jitter.
inline Vec3 camera_direction(const PinholeCamera& c, uint32_t pixel, float u0, float u1) {
  return camera_direction(c, static_cast<float>(pixel % c.width),
                          static_cast<float>(pixel / c.width), u0, u1);
}

}  // namespace snee
