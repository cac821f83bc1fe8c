// Camera rays (scene/camera_frame.h), written once over the lane type: the scalar functions and
// the batched generation kernel (generate.cpp) run the same templates, so the pinhole rays agree
// bit for bit and the thin lens's within the bound of lanewise_sincos (lane_batch.h).
#pragma once

#include <cstdint>

#include "kernels/physics/rng.h"
#include "kernels/physics/sampling.h"
#include "scene/camera_frame.h"

namespace snee {

struct FilmCamera {
  CameraFrame frame;
  uint32_t width;
  float inv_width, inv_height;
};

// The camera of a width x height film (KernelContext::camera, width and height).
inline FilmCamera film_camera(const CameraFrame& frame, int width, int height) {
  return {frame, static_cast<uint32_t>(width), 1.0f / static_cast<float>(width),
          1.0f / static_cast<float>(height)};
}

// forward + x right + y up through film position (px + u0, py + u1), not normalized: its
// component along forward is 1, so times the focus distance it reaches the focal plane.
template <lane::Lane F>
lane::Vec3Of<F> film_offset(const FilmCamera& c, F px, F py, F u0, F u1) {
  const F x = F(2.0f) * (px + u0) * F(c.inv_width) - F(1.0f);
  const F y = F(1.0f) - F(2.0f) * (py + u1) * F(c.inv_height);
  return splat<F>(c.frame.forward) + splat<F>(c.frame.right) * x + splat<F>(c.frame.up) * y;
}

// The pinhole's unit direction through film position (px + u0, py + u1) for any lane type F
// (core/lane_math.h); u0, u1 in [0, 1) jitter x and y.
template <lane::Lane F>
lane::Vec3Of<F> camera_direction(const FilmCamera& c, F px, F py, F u0, F u1) {
  return normalize(film_offset(c, px, py, u0, u1));
}

template <lane::Lane F>
struct CameraRayOf {
  lane::Vec3Of<F> origin, direction;
};

// The thin lens's ray through film position (px + u0, py + u1) from the lens point that u2, u3
// pick (uniform over the aperture disk): it passes the focal plane where the pinhole ray
// through the same film position does. Only for frame.thin_lens; a pinhole needs no u2, u3.
template <lane::Lane F>
CameraRayOf<F> thin_lens_ray(const FilmCamera& c, F px, F py, F u0, F u1, F u2, F u3) {
  const CameraFrame& f = c.frame;
  const auto [lx, ly] = sample_concentric_disk(u2, u3);
  const lane::Vec3Of<F> to_focus = film_offset(c, px, py, u0, u1) -
                                   splat<F>(f.lens_right_over_focus) * lx -
                                   splat<F>(f.lens_up_over_focus) * ly;
  return {splat<F>(f.origin) + splat<F>(f.lens_right) * lx + splat<F>(f.lens_up) * ly,
          normalize(to_focus)};
}

// The camera ray of a pixel with the kCamera block r: u[0], u[1] jitter, u[2], u[3] the lens.
inline CameraRayOf<float> camera_ray(const FilmCamera& c, uint32_t pixel, const RandomBlock& r) {
  const float px = static_cast<float>(pixel % c.width), py = static_cast<float>(pixel / c.width);
  if (c.frame.thin_lens) return thin_lens_ray(c, px, py, r.u[0], r.u[1], r.u[2], r.u[3]);
  return {c.frame.origin, camera_direction(c, px, py, r.u[0], r.u[1])};
}

}  // namespace snee
