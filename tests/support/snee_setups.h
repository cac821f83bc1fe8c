// What the SNEE sampler tests set up: a scene with one distant light, a medium vertex below the
// plane z = 0 with an exit point on it (as the probe finds them), and blocks of uniforms.
#pragma once

#include <array>
#include <cmath>

#include "kernels/physics/snee/snee_strategies.h"
#include "scene/scene.h"
#include "tests/support/chi2.h"

namespace snee::test {

inline Scene light_scene(LightKind kind, Rgb radiance = Rgb(1.0f)) {
  Scene scene;
  Light light;
  light.kind = kind;
  light.direction = normalize(Vec3(0.5f, 0.2f, 1.0f));
  light.half_angle = 0.3f;
  light.radiance = radiance;
  light.irradiance = radiance;
  scene.lights.push_back(light);
  return scene;
}

// An interface and a light, one of the measures A-D of docs/method.md 3.7.
struct SneeCase {
  const char* name;
  DielectricParams interface;
  LightKind light;
};

struct ExitSetup {
  SneeOrigin origin;
  ExitPoint exit;
};
// x_i at depth z_near + z_range u below the plane, near the origin; x_k on the plane within
// [-1, 1]^2 with the outward normal +z; a uniformly random incoming direction. With tilt > 0 the
// shading normal at x_k leans from +z by a uniform angle up to tilt radians in a uniform azimuth
// (a smooth-shaded boundary, docs/method.md 4.9); otherwise it is +z.
inline ExitSetup random_setup(TestRng& rng, DielectricParams interface, float z_near = 0.1f,
                              float z_range = 0.6f, float tilt = 0.0f) {
  const Vec3 x_i(0.3f * rng.uniform(), 0.3f * rng.uniform(), -z_near - z_range * rng.uniform());
  const Vec3 x_k(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 0.0f);
  const Vec3 omega_in = sample_uniform_sphere(rng.uniform2());
  Vec3 ns(0, 0, 1);
  if (tilt > 0) {
    const float a = tilt * rng.uniform(), phi = 6.2831853f * rng.uniform();
    ns = Vec3(std::sin(a) * std::cos(phi), std::sin(a) * std::sin(phi), std::cos(a));
  }
  return {{x_i, omega_in}, {x_k, Vec3(0, 0, 1), ns, interface}};
}

template <int N>
std::array<float, N> uniforms(TestRng& rng) {
  std::array<float, N> u;
  for (float& x : u) x = rng.uniform();
  return u;
}

}  // namespace snee::test
