// Inputs shared by the micro-benchmarks: every benchmark processes one queue's worth of items
// per iteration, with random numbers drawn before timing starts.
#pragma once

#include <cstddef>
#include <random>
#include <vector>

#include "scene/scene.h"

namespace snee::bench {

// Items per iteration: a large queue (the renderer's default unit holds 256 slots; this many
// keeps the per-iteration overhead out of the per-item figures).
inline constexpr size_t kItems = 4096;

// n uniform numbers in [0, 1), reproducible per seed.
inline std::vector<float> uniforms(size_t n, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> u(n);
  for (float& x : u) x = unit(engine);
  return u;
}

// One distant cone light (half angle 0.3 rad, unit radiance) toward (0.5, 0.2, 1): the SNEE
// benchmarks' light.
inline Scene cone_light_scene() {
  Scene scene;
  Light light;
  light.kind = LightKind::kCone;
  light.direction = normalize(Vec3(0.5f, 0.2f, 1.0f));
  light.half_angle = 0.3f;
  light.radiance = Rgb(1.0f);
  scene.lights.push_back(light);
  return scene;
}

}  // namespace snee::bench
