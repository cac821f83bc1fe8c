// Light sampling and evaluation for every light kind in a scene. Built once per render from the
// scene description (precomputing the environment-map distribution and emissive-triangle
// tables); then read-only and shared by all threads. Dispatch is a switch on LightKind.
//
// A light sample first picks one of scene.lights from an alias table, uniformly or in
// proportion to an estimate of each light's power (LightSelection; the estimates are listed in
// docs/lights.md). Every pdf returned here includes the picked light's selection probability,
// and the same function is used wherever a light pdf enters a weight.
//
// Lights seen by escaped rays (cone, constant, env map) overlap in direction, so sample() treats
// them as one mixture: whichever of them is picked, the returned radiance is escaped_radiance(wi)
// and the pdf escaped_pdf(wi), the sum over all of them of selection probability times their
// own pdf. That keeps light sampling consistent with the escaped-ray MIS weights, which only
// ever see the summed radiance.
#pragma once

#include <cmath>
#include <vector>

#include "kernels/physics/alias_table.h"
#include "kernels/physics/sampling.h"
#include "scene/scene.h"

namespace snee {

struct LightSample {
  Vec3 wi;                     // unit direction from the shading point toward the light
  float distance = kInfinity;  // to the sampled light point (infinity for distant lights)
  Rgb radiance{0.0f};          // incident radiance (delta lights: irradiance / intensity/r^2)
  float pdf = 0;               // solid angle (delta lights: the selection probability)
  bool delta = false;
  bool valid = false;
  int light = -1;  // the index in scene.lights of the light it sampled
};

// The shadow ray of a light sample taken at shading point p, starting from `origin` (p moved
// off its surface). For a finite light it aims at the sampled point itself and stops just short
// of it: keeping the direction and distance measured from p would, from the moved origin, end
// past the light's own surface and count the light as its own occluder.
struct ShadowRay {
  Vec3 direction;
  float t_max;
};
inline ShadowRay shadow_ray_to_light(const LightSample& s, Vec3 p, Vec3 origin) {
  if (std::isinf(s.distance)) return {s.wi, kInfinity};
  const Vec3 to_light = p + s.wi * s.distance - origin;
  const float length_to_light = length(to_light);
  return {to_light / length_to_light, length_to_light * (1.0f - 1e-4f)};
}

class LightTable {
 public:
  explicit LightTable(const Scene& scene, LightSelection selection = LightSelection::kUniform);

  bool empty() const { return lights_.empty(); }
  // u_select picks the light, u the point/direction on it. p is the shading point.
  LightSample sample(Vec3 p, float u_select, Vec2 u) const;

  // Radiance arriving along a ray that escaped the scene in direction d (environment + cone
  // lights), and the solid-angle pdf with which sample() would have produced d (for MIS).
  Rgb escaped_radiance(Vec3 d) const;
  float escaped_pdf(Vec3 d) const;

  // An emissive shape hit at point `hit` (normal n) from `p` along unit wi: emitted radiance
  // toward p (front side only) and the solid-angle pdf of sample() producing that point.
  Rgb area_radiance(int shape, Vec3 n, Vec3 wi) const;
  float area_pdf(int shape, Vec3 p, Vec3 hit, Vec3 n) const;

  // The probability that sample() picks scene.lights[light].
  float selection_pmf(int light) const { return selection_.pmf(light); }

  bool has_delta_lights() const { return has_delta_; }
  // Whether any light is seen by escaped rays (cone, constant, env map).
  bool has_escaped_lights() const { return !escaping_.empty(); }

 private:
  struct AreaLight {
    int shape = -1;
    Distribution1D triangles;  // by area (meshes only)
    float total_area = 0;
  };
  struct EnvMap {
    const RgbImage* image = nullptr;
    Distribution2D distribution;  // luminance * sin(theta), with a floor for dim pixels
    Transform to_world, to_map;
  };

  // Emitted power (luminance) of scene.lights[light], for power-proportional selection;
  // radius bounds the scene, which distant lights are assumed to cover.
  double estimated_power(int light, double radius) const;
  // One light's share, without the selection probability.
  Rgb escaped_radiance_of(int light, Vec3 d) const;
  float escaped_pdf_of(int light, Vec3 d) const;
  Vec3 sample_escaping(int light, Vec2 u) const;
  LightSample sample_area(int light, float selection_pmf, Vec3 p, float u_triangle, Vec2 u) const;
  float area_pdf_of(const AreaLight& area, Vec3 p, Vec3 hit, Vec3 n) const;

  const Scene* scene_;
  std::vector<Light> lights_;
  AliasTable selection_;             // over lights_
  std::vector<int> escaping_;        // lights seen by escaped rays (cone, constant, env map)
  std::vector<float> cone_cos_;      // light index -> cos(half_angle) (cone lights)
  std::vector<int> area_of_light_;   // light index -> index into areas_ (or -1)
  std::vector<int> light_of_shape_;  // shape index -> light index (or -1)
  std::vector<AreaLight> areas_;
  std::vector<int> env_of_light_;  // light index -> index into envs_ (or -1)
  std::vector<EnvMap> envs_;
  bool has_delta_ = false;
};

}  // namespace snee
