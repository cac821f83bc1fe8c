// The camera's rays as the renderer makes them, derived once from the scene's Camera for the
// kernels and the Embree throughput benchmark alike. Film position (x, y) in [-1, 1]^2, x to the
// right and y up, looks along forward + x right + y up: right and up span the image plane at
// unit distance, scaled by its half extents. A thin lens moves the origin to position +
// lx lens_right + ly lens_up for a point (lx, ly) of the unit disk, and aims the ray at the point
// that film position sees on the focal plane.
#pragma once

#include "scene/scene.h"

namespace snee {

struct CameraFrame {
  Vec3 origin, forward, right, up;
  // Unit right and up times the aperture radius (zero for a pinhole).
  Vec3 lens_right, lens_up;
  // lens_right and lens_up over the focus distance: the offset from a lens point to the focal
  // plane point, in units of the focus distance, so directions stay finite for any focus
  // distance float can hold.
  Vec3 lens_right_over_focus, lens_up_over_focus;
  bool thin_lens;  // aperture radius > 0
};

// tan(degrees / 2), as the frame computes it in float.
float tan_half_angle(float degrees);

// Half the image plane's width and height at unit distance, for the camera's fov, axis and
// resolution: the tangents of the half-angles the image spans across and down.
struct HalfExtents {
  float x, y;
};
HalfExtents image_half_extents(const Camera& c);

// The focus distance in effect: the given one, or the distance from position to look_at.
float effective_focus_distance(const Camera& c);

CameraFrame camera_frame(const Camera& c);

}  // namespace snee
