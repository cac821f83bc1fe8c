// The environment-map light: its samples follow the pdf MIS uses (chi-square in the map's
// (u, v) space, the pdf of every pixel), that pdf and the radiance integrate as the image does,
// lookups are bilinear, and every direction with radiance can be sampled (docs/lights.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "kernels/physics/lights/light_table.h"
#include "tests/support/chi2.h"
#include "tests/support/light_checks.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::expect_agrees;
using test::expect_round_trip;
using test::kMaxZ;
using test::kMinPValue;
using test::kSamples;
using test::MeanEstimator;
using test::pearson_p_value;
using test::TestRng;

constexpr int kEnvWidth = 32, kEnvHeight = 16;

Vec3 map_direction(float u, float v) {
  const float theta = v * kPi, phi = 2 * kPi * (u - 0.5f);
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// The RgbImage convention of scene.h, inverted.
Vec2 map_uv(Vec3 m) {
  return {static_cast<float>(std::atan2(m.x, -m.z) / (2 * M_PI) + 0.5),
          static_cast<float>(std::acos(std::clamp(m.y, -1.0f, 1.0f)) / M_PI)};
}

// A coloured gradient plus a bright blob; every pixel well above the sampling floor.
RgbImage procedural_env() {
  RgbImage image;
  image.width = kEnvWidth;
  image.height = kEnvHeight;
  const Vec3 blob = map_direction(0.7f, 0.3f);
  for (int y = 0; y < kEnvHeight; ++y) {
    for (int x = 0; x < kEnvWidth; ++x) {
      const float u = (x + 0.5f) / kEnvWidth, v = (y + 0.5f) / kEnvHeight;
      const float c = dot(map_direction(u, v), blob);
      const float b = 40.0f * std::exp(-(1 - c) / 0.02f);
      image.pixels.push_back(Rgb(0.2f + 0.5f * u, 0.3f + 0.4f * v, 0.6f - 0.3f * v) + Rgb(b));
    }
  }
  return image;
}

struct EnvScene {
  Scene scene;
  Transform rotation = Transform::rotate(Vec3(1, 2, 0.5f), 0.7f);
  Rgb scale{1.5f, 1.0f, 0.5f};
  EnvScene() {
    scene.env_images.push_back(procedural_env());
    Light l;
    l.kind = LightKind::kEnvMap;
    l.env_image = 0;
    l.env_rotation = rotation;
    l.radiance = scale;
    scene.lights.push_back(l);
  }
  Vec3 to_map(Vec3 w) const {
    // Inverse of a rotation: its transpose.
    const auto& m = rotation.m;
    return {m[0][0] * w.x + m[1][0] * w.y + m[2][0] * w.z,
            m[0][1] * w.x + m[1][1] * w.y + m[2][1] * w.z,
            m[0][2] * w.x + m[1][2] * w.y + m[2][2] * w.z};
  }
  const Rgb& pixel(int x, int y) const { return scene.env_images[0].pixels[y * kEnvWidth + x]; }
};

// Adds kSamples light samples from the origin to `counts`, binned bins_u x bins_v in map (u, v)
// space (row-major, v down).
void bin_samples(const EnvScene& env, const LightTable& lights, int bins_u, int bins_v,
                 uint64_t seed, std::vector<double>& counts) {
  TestRng rng(seed);
  for (int k = 0; k < kSamples; ++k) {
    const float u_select = rng.uniform();
    const LightSample s = lights.sample(Vec3(0.0f), u_select, rng.uniform2());
    ASSERT_TRUE(s.valid);
    const Vec2 uv = map_uv(env.to_map(s.wi));
    const int x = std::clamp(static_cast<int>(uv.x * bins_u), 0, bins_u - 1);
    const int y = std::clamp(static_cast<int>(uv.y * bins_v), 0, bins_v - 1);
    counts[y * bins_u + x] += 1;
  }
}

// Samples binned in map (u,v) space, two by two bins per pixel, against escaped_pdf: a bin's
// probability is its (u,v) area times escaped_pdf * 2 pi^2 sin(theta), the Jacobian of the
// lat-long mapping. Within a pixel that product is constant, so one interior node per bin is
// exact, and pixel edges (where the pdf jumps) never fall inside a bin, as they would in a
// quadrature over a rotated sphere grid.
TEST(Lights, EnvMapChi2) {
  const EnvScene env;
  const LightTable lights(env.scene);
  constexpr int kSub = 2, kBinsU = kEnvWidth * kSub, kBinsV = kEnvHeight * kSub;
  std::vector<double> counts(kBinsU * kBinsV, 0), expected(kBinsU * kBinsV);
  double total = 0;
  for (int y = 0; y < kBinsV; ++y) {
    for (int x = 0; x < kBinsU; ++x) {
      const float u = (x + 0.5f) / kBinsU, v = (y + 0.5f) / kBinsV;
      const Vec3 world = env.rotation.vector(map_direction(u, v));
      const double jacobian = 2 * M_PI * M_PI * std::sin(v * M_PI);
      expected[y * kBinsU + x] =
          kSamples * lights.escaped_pdf(world) * jacobian / (kBinsU * kBinsV);
      total += expected[y * kBinsU + x];
    }
  }
  EXPECT_NEAR(total / kSamples, 1.0, 1e-5) << "escaped_pdf does not integrate to one";
  ASSERT_NO_FATAL_FAILURE(bin_samples(env, lights, kBinsU, kBinsV, 21, counts));
  EXPECT_GT(pearson_p_value(counts, expected), kMinPValue);
  expect_round_trip(env.scene, lights, Vec3(0.0f), 22);
}

// Per pixel of the map, the sampling probability is proportional to luminance * sin(theta),
// computed here from the image alone (the fixture keeps every pixel above the floor).
TEST(Lights, EnvMapPixelProbabilities) {
  const EnvScene env;
  const LightTable lights(env.scene);
  std::vector<double> weight(kEnvWidth * kEnvHeight);
  double total = 0;
  for (int y = 0; y < kEnvHeight; ++y) {
    for (int x = 0; x < kEnvWidth; ++x) {
      weight[y * kEnvWidth + x] =
          luminance(env.pixel(x, y)) * std::sin((y + 0.5) * M_PI / kEnvHeight);
      total += weight[y * kEnvWidth + x];
    }
  }
  std::vector<double> counts(weight.size(), 0), expected(weight.size());
  for (size_t i = 0; i < weight.size(); ++i) expected[i] = kSamples * weight[i] / total;
  ASSERT_NO_FATAL_FAILURE(bin_samples(env, lights, kEnvWidth, kEnvHeight, 23, counts));
  EXPECT_GT(pearson_p_value(counts, expected), kMinPValue);
}

// Integral of luminance over the sphere of the bilinearly filtered map, against light
// sampling; a cosine-weighted one against uniform sampling. Interpolation in u is linear and
// periodic, so a row's integral over u is the mean of its pixels; in v it is linear between
// row centres (constant within half a pixel of the poles), and the integral over v of that
// times the Jacobian 2 pi^2 sin(pi v) is summed here on a grid fine enough to be exact to 1e-9.
TEST(Lights, EnvMapIntegrals) {
  const EnvScene env;
  const LightTable lights(env.scene);
  std::vector<double> row_mean(kEnvHeight, 0.0);
  for (int y = 0; y < kEnvHeight; ++y) {
    for (int x = 0; x < kEnvWidth; ++x)
      row_mean[y] += luminance(env.scale * env.pixel(x, y)) / kEnvWidth;
  }
  double exact = 0;
  constexpr int kSteps = 1 << 20;
  for (int k = 0; k < kSteps; ++k) {
    const double v = (k + 0.5) / kSteps;
    const double fy = std::clamp(v * kEnvHeight - 0.5, 0.0, kEnvHeight - 1.0);
    const int y0 = std::min(static_cast<int>(fy), kEnvHeight - 2);
    const double t = fy - y0;
    const double f = (1 - t) * row_mean[y0] + t * row_mean[y0 + 1];
    exact += 2 * M_PI * M_PI * std::sin(M_PI * v) * f / kSteps;
  }
  const Vec3 n = normalize(Vec3(0.3f, -0.4f, 1));
  TestRng rng(24);
  MeanEstimator total, irradiance_light, irradiance_uniform;
  for (int k = 0; k < kSamples; ++k) {
    const float u_select = rng.uniform();
    const LightSample s = lights.sample(Vec3(0.0f), u_select, rng.uniform2());
    ASSERT_TRUE(s.valid);
    total.add(luminance(s.radiance) / s.pdf);
    irradiance_light.add(luminance(s.radiance) * std::max(0.0f, dot(n, s.wi)) / s.pdf);
    const Vec3 w = sample_uniform_sphere(rng.uniform2());
    irradiance_uniform.add(luminance(lights.escaped_radiance(w)) * std::max(0.0f, dot(n, w)) /
                           uniform_sphere_pdf());
  }
  expect_agrees(total, exact, "total radiant flux per area");
  EXPECT_LT(test::z_score(irradiance_light.mean(), irradiance_light.standard_error(),
                          irradiance_uniform.mean(), irradiance_uniform.standard_error()),
            kMaxZ)
      << irradiance_light.mean() << " vs " << irradiance_uniform.mean();
}

// The lookup interpolates between pixel centres: at a centre it is the pixel, halfway between
// two neighbours (across the u seam too) their mean, and between four their mean.
TEST(Lights, EnvMapLookupIsBilinear) {
  EnvScene env;
  env.rotation = Transform();
  env.scene.lights[0].env_rotation = env.rotation;
  const LightTable lights(env.scene);
  const auto radiance = [&](float u, float v) {
    return lights.escaped_radiance(map_direction(u, v)) / env.scale;
  };
  const auto expect_rgb_near = [](Rgb a, Rgb b, const char* what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-4f * (1 + b[c])) << what;
  };
  const float du = 1.0f / kEnvWidth, dv = 1.0f / kEnvHeight;
  expect_rgb_near(radiance(5.5f * du, 3.5f * dv), env.pixel(5, 3), "pixel centre");
  expect_rgb_near(radiance(6 * du, 3.5f * dv), (env.pixel(5, 3) + env.pixel(6, 3)) * 0.5f,
                  "between two columns");
  expect_rgb_near(radiance(6 * du, 4 * dv),
                  (env.pixel(5, 3) + env.pixel(6, 3) + env.pixel(5, 4) + env.pixel(6, 4)) * 0.25f,
                  "between four pixels");
  expect_rgb_near(radiance(1e-6f, 7.5f * dv),
                  (env.pixel(0, 7) + env.pixel(kEnvWidth - 1, 7)) * 0.5f, "across the u seam");
  expect_rgb_near(radiance(9.5f * du, 0.2f * dv), env.pixel(9, 0), "within half a pixel of a pole");
}

// A single lit pixel on a black map: its filtered radiance reaches into the neighbours, and
// light sampling must reach every direction that has radiance (escaped_pdf > 0 there).
TEST(Lights, EnvMapSamplesWhereverTheFilteredRadianceIsNonZero) {
  Scene scene;
  RgbImage image;
  image.width = 8;
  image.height = 4;
  image.pixels.assign(32, Rgb(0.0f));
  image.pixels[1 * 8 + 7] = Rgb(5.0f);  // beside the u seam
  scene.env_images.push_back(image);
  Light l;
  l.kind = LightKind::kEnvMap;
  l.env_image = 0;
  scene.lights.push_back(l);
  const LightTable lights(scene);
  TestRng rng(25);
  int lit = 0;
  for (int k = 0; k < 200000; ++k) {
    const Vec3 w = sample_uniform_sphere(rng.uniform2());
    if (is_black(lights.escaped_radiance(w))) continue;
    ++lit;
    ASSERT_GT(lights.escaped_pdf(w), 0.0f) << "radiance " << luminance(lights.escaped_radiance(w));
  }
  EXPECT_GT(lit, 0);
  // And the estimator over light samples agrees with one over uniform directions.
  MeanEstimator light_sampled, uniform;
  for (int k = 0; k < kSamples; ++k) {
    const LightSample s = lights.sample(Vec3(0.0f), rng.uniform(), rng.uniform2());
    light_sampled.add(s.valid ? luminance(s.radiance) / s.pdf : 0.0);
    const Vec3 w = sample_uniform_sphere(rng.uniform2());
    uniform.add(luminance(lights.escaped_radiance(w)) / uniform_sphere_pdf());
  }
  EXPECT_LT(test::z_score(light_sampled.mean(), light_sampled.standard_error(), uniform.mean(),
                          uniform.standard_error()),
            kMaxZ)
      << light_sampled.mean() << " vs " << uniform.mean();
}

}  // namespace
}  // namespace snee
