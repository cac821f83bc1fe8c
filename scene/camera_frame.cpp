#include "scene/camera_frame.h"

#include <cmath>

namespace snee {

float tan_half_angle(float degrees) {
  return std::tan(0.5f * degrees * kPi / 180.0f);
}

HalfExtents image_half_extents(const Camera& c) {
  const float tan_half = tan_half_angle(c.fov_degrees);
  const float aspect = static_cast<float>(c.width) / static_cast<float>(c.height);
  switch (c.fov_axis) {
    case FovAxis::kHorizontal:
      return {tan_half, tan_half / aspect};
    case FovAxis::kDiagonal: {
      const float y = tan_half / std::sqrt(1.0f + aspect * aspect);
      return {y * aspect, y};
    }
    case FovAxis::kVertical:
      break;
  }
  return {tan_half * aspect, tan_half};
}

float effective_focus_distance(const Camera& c) {
  return c.focus_distance > 0 ? c.focus_distance : length(c.look_at - c.position);
}

CameraFrame camera_frame(const Camera& c) {
  const Vec3 forward = normalize(c.look_at - c.position);
  const Vec3 right = normalize(cross(forward, c.up));
  const Vec3 up = cross(right, forward);
  const HalfExtents half = image_half_extents(c);
  const float a = c.aperture_radius;
  const float a_over_f = a / effective_focus_distance(c);
  return {c.position, forward,          right * half.x, up * half.y, right * a,
          up * a,     right * a_over_f, up * a_over_f,  a > 0};
}

}  // namespace snee
