// Pinhole camera rays: the scalar reference that the batched generation kernel
// (simd/camera_batch.h) reproduces bit for bit.
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

// Unit direction through film position (pixel + jitter); u0, u1 in [0, 1) jitter x and y.
inline Vec3 camera_direction(const PinholeCamera& c, uint32_t pixel, float u0, float u1) {
  const float px = static_cast<float>(pixel % c.width);
  const float py = static_cast<float>(pixel / c.width);
  const float x = 2.0f * (px + u0) * c.inv_width - 1.0f;
  const float y = 1.0f - 2.0f * (py + u1) * c.inv_height;
  return normalize(c.forward + c.right * x + c.up * y);
}

}  // namespace snee
