// Light sampling: every sample's pdf agrees with the pdf used for MIS (escaped_pdf, area_pdf),
// sampled directions follow that pdf (chi-square), and irradiance estimated from the samples
// matches closed forms or an independent estimator, under uniform and power light selection;
// power selection follows the documented estimates (docs/lights.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <optional>
#include <vector>

#include "kernels/physics/lights/light_table.h"
#include "tests/support/chi2.h"
#include "tests/support/form_factor.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::MeanEstimator;
using test::TestRng;

constexpr double kMinPValue = 1e-4;
constexpr double kMaxZ = 4;
constexpr int kSamples = 1'000'000;
// Recomputing a pdf from the sampled point takes a handful of float operations.
constexpr float kPdfRelativeTolerance = 64 * FLT_EPSILON;
constexpr LightSelection kSelections[] = {LightSelection::kUniform, LightSelection::kPower};

Light directional_light(Vec3 direction, Rgb irradiance) {
  Light l;
  l.kind = LightKind::kDirectional;
  l.direction = normalize(direction);
  l.irradiance = irradiance;
  return l;
}

Light cone_light(Vec3 direction, float half_angle, Rgb radiance) {
  Light l;
  l.kind = LightKind::kCone;
  l.direction = normalize(direction);
  l.half_angle = half_angle;
  l.radiance = radiance;
  return l;
}

Light constant_env(Rgb radiance) {
  Light l;
  l.kind = LightKind::kConstantEnv;
  l.radiance = radiance;
  return l;
}

Light point_light(Vec3 position, Rgb intensity) {
  Light l;
  l.kind = LightKind::kPoint;
  l.position = position;
  l.intensity = intensity;
  return l;
}

Light spot_light(Vec3 position, Vec3 look_at, Rgb intensity, float cone_degrees,
                 float falloff_start_degrees) {
  Light l;
  l.kind = LightKind::kSpot;
  l.position = position;
  l.spot_axis = normalize(look_at - position);
  l.intensity = intensity;
  l.spot_cos_outer = std::cos(cone_degrees * kPi / 180);
  l.spot_cos_inner = std::cos(falloff_start_degrees * kPi / 180);
  return l;
}

// Adds shape as an area light and returns its shape index.
int add_area_light(Scene& scene, Shape shape) {
  scene.shapes.push_back(std::move(shape));
  Light l;
  l.kind = LightKind::kArea;
  l.shape = static_cast<int>(scene.shapes.size() - 1);
  scene.lights.push_back(l);
  return l.shape;
}

// Unit square in the plane z = height, centred on the z axis, emitting downward (-z).
Shape square_emitter(float height, Rgb emission) {
  Shape s;
  s.kind = ShapeKind::kMesh;
  s.mesh.positions = {
      {-0.5f, -0.5f, height}, {0.5f, -0.5f, height}, {0.5f, 0.5f, height}, {-0.5f, 0.5f, height}};
  s.mesh.indices = {0, 2, 1, 0, 3, 2};  // clockwise seen from above: the normal is -z
  s.emission = emission;
  s.closed = false;
  return s;
}

Shape sphere_emitter(Vec3 center, float radius, Rgb emission) {
  Shape s;
  s.kind = ShapeKind::kSphere;
  s.center = center;
  s.radius = radius;
  s.emission = emission;
  return s;
}

// Irradiance (luminance) on a plane through p with normal n, from light samples.
MeanEstimator estimate_irradiance(const LightTable& lights, Vec3 p, Vec3 n, uint64_t seed,
                                  int samples = kSamples) {
  TestRng rng(seed);
  MeanEstimator e;
  for (int k = 0; k < samples; ++k) {
    const float u_select = rng.uniform();
    const LightSample s = lights.sample(p, u_select, rng.uniform2());
    const float cos_theta = dot(n, s.wi);
    e.add(s.valid && cos_theta > 0 ? luminance(s.radiance) * cos_theta / s.pdf : 0.0);
  }
  return e;
}

// Pearson's test of counts against expected counts (all expected counts are large here).
double pearson_p_value(const std::vector<double>& observed, const std::vector<double>& expected) {
  double statistic = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
  }
  return test::chi2_survival(statistic, static_cast<double>(observed.size() - 1));
}

void expect_agrees(const MeanEstimator& e, double expected, const char* what) {
  EXPECT_LT(test::z_score(e.mean(), e.standard_error(), expected, 0), kMaxZ)
      << what << ": estimate " << e.mean() << " +- " << e.standard_error() << ", expected "
      << expected;
}

using test::corner_form_factor;

// The pdf of every sample agrees with the pdf MIS uses for the same direction or point.
void expect_round_trip(const Scene& scene, const LightTable& lights, Vec3 p, uint64_t seed) {
  TestRng rng(seed);
  int valid = 0;
  for (int k = 0; k < 100000; ++k) {
    const float u_select = rng.uniform();
    const LightSample s = lights.sample(p, u_select, rng.uniform2());
    if (!s.valid) continue;
    ++valid;
    ASSERT_NEAR(length(s.wi), 1.0f, 4 * FLT_EPSILON);
    if (s.delta) {
      // The pdf of a delta light is its selection probability.
      bool found = false;
      for (size_t i = 0; i < scene.lights.size(); ++i) {
        const LightKind kind = scene.lights[i].kind;
        const bool delta = kind == LightKind::kDirectional || kind == LightKind::kPoint ||
                           kind == LightKind::kSpot;
        found = found || (delta && s.pdf == lights.selection_pmf(static_cast<int>(i)));
      }
      ASSERT_TRUE(found) << "delta pdf " << s.pdf << " is no delta light's selection pmf";
    } else if (std::isinf(s.distance)) {
      ASSERT_EQ(s.pdf, lights.escaped_pdf(s.wi));
      ASSERT_EQ(s.radiance, lights.escaped_radiance(s.wi));
    } else {
      // Find the emitter the point lies on.
      const Vec3 hit = p + s.wi * s.distance;
      int shape = -1;
      Vec3 n;
      for (size_t i = 0; i < scene.shapes.size() && shape < 0; ++i) {
        const Shape& sh = scene.shapes[i];
        if (sh.kind == ShapeKind::kSphere) {
          if (std::fabs(length(hit - sh.center) - sh.radius) < 1e-4f * sh.radius) {
            shape = static_cast<int>(i);
            n = normalize(hit - sh.center);
          }
        } else if (std::fabs(hit.z - sh.mesh.positions[0].z) < 1e-5f) {
          shape = static_cast<int>(i);
          n = Vec3(0, 0, -1);
        }
      }
      ASSERT_GE(shape, 0) << "sampled point on no emitter";
      ASSERT_NEAR(s.pdf, lights.area_pdf(shape, p, hit, n), kPdfRelativeTolerance * s.pdf);
      ASSERT_EQ(s.radiance, lights.area_radiance(shape, n, s.wi));
    }
  }
  EXPECT_GT(valid, 0);
}

// ---- environment map fixture ----

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

// ---- tests ----

TEST(Lights, DirectionalIsDeltaAndNotSeenByEscapedRays) {
  Scene scene;
  scene.lights.push_back(directional_light(Vec3(1, 2, 3), Rgb(2.0f)));
  const LightTable lights(scene);
  EXPECT_TRUE(lights.has_delta_lights());
  const LightSample s = lights.sample(Vec3(0.0f), 0.3f, {0.2f, 0.7f});
  ASSERT_TRUE(s.valid);
  EXPECT_TRUE(s.delta);
  EXPECT_EQ(s.pdf, 1.0f);
  EXPECT_TRUE(std::isinf(s.distance));
  EXPECT_EQ(s.radiance, Rgb(2.0f));
  EXPECT_EQ(s.wi, normalize(Vec3(1, 2, 3)));
  EXPECT_EQ(lights.escaped_radiance(s.wi), Rgb(0.0f));
  EXPECT_EQ(lights.escaped_pdf(s.wi), 0.0f);
}

TEST(Lights, PointLightFallsOffWithSquaredDistance) {
  Scene scene;
  scene.lights.push_back(point_light(Vec3(0, 0, 2), Rgb(8.0f)));
  scene.lights.push_back(constant_env(Rgb(0.0f)));
  const LightTable lights(scene);
  const LightSample s = lights.sample(Vec3(0, 0, -2), 0.25f, {0.5f, 0.5f});
  ASSERT_TRUE(s.valid);
  EXPECT_TRUE(s.delta);
  EXPECT_EQ(s.pdf, 0.5f);
  EXPECT_FLOAT_EQ(s.distance, 4.0f);
  EXPECT_FLOAT_EQ(s.radiance.x, 0.5f);
  EXPECT_EQ(s.wi, Vec3(0, 0, 1));
}

// The spot's intensity in a direction at angle theta from its axis: pbrt's smoothstep in
// cos(theta) between the cone's cosine and the falloff start's, written out here.
double spot_falloff(double cos_theta, double cone_degrees, double falloff_start_degrees) {
  const double cos_outer = std::cos(cone_degrees * M_PI / 180);
  const double cos_inner = std::cos(falloff_start_degrees * M_PI / 180);
  const double t = std::clamp((cos_theta - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// A spot above a plane, mixed with a point light so that light selection is random: the
// irradiance at points inside, within the falloff and outside the cone is the spot's
// intensity * falloff * cos / r^2 plus the point light's I cos / r^2.
TEST(Lights, SpotIrradianceOnAPlane) {
  Scene scene;
  const Vec3 spot(0, 0, 2), bulb(0, 3, 3);
  scene.lights.push_back(spot_light(spot, Vec3(0.0f), Rgb(5.0f), 40, 20));
  scene.lights.push_back(point_light(bulb, Rgb(2.0f)));
  const LightTable lights(scene, LightSelection::kPower);
  const Vec3 n(0, 0, 1);
  for (const float x : {0.0f, 0.5f, 0.9f, 1.3f, 2.0f}) {
    const Vec3 p(x, 0, 0);
    const Vec3 to_spot = spot - p, to_bulb = bulb - p;
    const double r2 = dot(to_spot, to_spot), cos_plane = to_spot.z / std::sqrt(r2);
    // The spot points straight down, so the angle off its axis is the angle off the normal.
    const double from_spot = 5.0 * spot_falloff(cos_plane, 40, 20) * cos_plane / r2;
    const double from_bulb =
        2.0 * to_bulb.z / std::sqrt(dot(to_bulb, to_bulb)) / dot(to_bulb, to_bulb);
    const MeanEstimator e =
        estimate_irradiance(lights, p, n, 51 + static_cast<int>(10 * x), 200000);
    expect_agrees(e, from_spot + from_bulb, "spot + point");
  }
  // On the axis and at full intensity, one sample gives the exact value.
  const Scene alone = [&] {
    Scene s1;
    s1.lights.push_back(scene.lights[0]);
    return s1;
  }();
  const LightSample s = LightTable(alone).sample(Vec3(0.3f, 0, 0), 0.5f, {0.5f, 0.5f});
  ASSERT_TRUE(s.valid);
  EXPECT_TRUE(s.delta);
  EXPECT_FLOAT_EQ(s.radiance.x, 5.0f / (4.0f + 0.09f));
}

// With a 180-degree cone (and falloff start) nothing is cut off: bit for bit a point light,
// selection probability included.
TEST(Lights, SpotWithFullConeIsAPointLight) {
  Scene with_spot, with_point;
  const Vec3 position(0.5f, 1, -2);
  with_spot.lights.push_back(spot_light(position, Vec3(1, 0, 0), Rgb(3, 2, 1), 180, 180));
  with_point.lights.push_back(point_light(position, Rgb(3, 2, 1)));
  for (Scene* scene : {&with_spot, &with_point}) {
    scene->lights.push_back(cone_light(Vec3(0, 1, 0), 0.4f, Rgb(2.0f)));
  }
  for (const LightSelection selection : kSelections) {
    const LightTable spot(with_spot, selection), point(with_point, selection);
    TestRng rng(61);
    for (int k = 0; k < 10000; ++k) {
      const Vec3 p = sample_uniform_sphere(rng.uniform2()) * 3.0f;
      const float u_select = rng.uniform();
      const Vec2 u = rng.uniform2();
      const LightSample a = spot.sample(p, u_select, u), b = point.sample(p, u_select, u);
      ASSERT_EQ(a.valid, b.valid);
      ASSERT_EQ(a.wi, b.wi);
      ASSERT_EQ(a.distance, b.distance);
      ASSERT_EQ(a.radiance, b.radiance);
      ASSERT_EQ(a.pdf, b.pdf);
      ASSERT_EQ(a.delta, b.delta);
    }
  }
}

TEST(Lights, ConeChi2) {
  Scene scene;
  const Vec3 axis = normalize(Vec3(1, 1, 1));
  const float half_angle = 20.0f * kPi / 180.0f;
  scene.lights.push_back(cone_light(axis, half_angle, Rgb(3.0f)));
  const LightTable lights(scene);
  TestRng rng(11);
  const auto r = test::chi2_sphere(
      [&]() -> std::optional<Vec3> {
        const float u_select = rng.uniform();
        const LightSample s = lights.sample(Vec3(0.0f), u_select, rng.uniform2());
        if (!s.valid) return std::nullopt;
        return s.wi;
      },
      [&](Vec3 w) { return lights.escaped_pdf(w); },
      {.axis = axis, .cos_min = 2.0 * std::cos(half_angle) - 1.0});
  EXPECT_GT(r.p_value, kMinPValue) << r.report;
}

// Cone and constant environment overlap; sample() is their mixture, with pdf escaped_pdf.
TEST(Lights, OverlappingEscapedLightsChi2) {
  Scene scene;
  const Vec3 axis = normalize(Vec3(0, 1, -1));
  scene.lights.push_back(cone_light(axis, 0.5f, Rgb(3.0f)));
  scene.lights.push_back(constant_env(Rgb(0.5f)));
  // A sphere to give the distant lights a scene radius; its power estimates then weight the
  // mixture unevenly.
  add_area_light(scene, sphere_emitter(Vec3(0, 0, 5), 1.0f, Rgb(1.0f)));
  for (const LightSelection selection : kSelections) {
    const LightTable lights(scene, selection);
    TestRng rng(12);
    const auto r = test::chi2_sphere(
        [&]() -> std::optional<Vec3> {
          const float u_select = rng.uniform();
          const LightSample s = lights.sample(Vec3(0.0f), u_select, rng.uniform2());
          // The sphere's samples are the failure cell, of probability 1 - its selection pmf.
          if (!s.valid || !std::isinf(s.distance)) return std::nullopt;
          return s.wi;
        },
        [&](Vec3 w) { return lights.escaped_pdf(w); }, {.axis = axis});
    EXPECT_GT(r.p_value, kMinPValue) << r.report;
    expect_round_trip(scene, lights, Vec3(0.0f), 13);
  }
}

TEST(Lights, ConeIrradiance) {
  Scene scene;
  const Vec3 axis = normalize(Vec3(-1, 0.5f, 2));
  const float half_angle = 0.6f;
  scene.lights.push_back(cone_light(axis, half_angle, Rgb(2.0f)));
  const LightTable lights(scene);
  const MeanEstimator e = estimate_irradiance(lights, Vec3(0.0f), axis, 14);
  expect_agrees(e, 2.0 * M_PI * std::pow(std::sin(half_angle), 2), "cone facing the plane");
}

TEST(Lights, ConstantEnvIrradiance) {
  Scene scene;
  scene.lights.push_back(constant_env(Rgb(0.7f)));
  const LightTable lights(scene);
  const MeanEstimator e = estimate_irradiance(lights, Vec3(0.0f), normalize(Vec3(1, -2, 1)), 15);
  expect_agrees(e, 0.7 * M_PI, "constant environment");
}

TEST(Lights, DirectionalIrradianceWithSelection) {
  Scene scene;
  const Vec3 n = normalize(Vec3(0, 1, 0.3f));
  scene.lights.push_back(directional_light(Vec3(0.2f, 1, 0), Rgb(4.0f)));
  scene.lights.push_back(constant_env(Rgb(0.5f)));
  const double expected = 4.0 * dot(n, normalize(Vec3(0.2f, 1, 0))) + 0.5 * M_PI;
  for (const LightSelection selection : kSelections) {
    const LightTable lights(scene, selection);
    expect_agrees(estimate_irradiance(lights, Vec3(0.0f), n, 16), expected,
                  light_selection_name(selection));
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
  TestRng rng(21);
  for (int k = 0; k < kSamples; ++k) {
    const float u_select = rng.uniform();
    const LightSample s = lights.sample(Vec3(0.0f), u_select, rng.uniform2());
    ASSERT_TRUE(s.valid);
    const Vec2 uv = map_uv(env.to_map(s.wi));
    const int x = std::clamp(static_cast<int>(uv.x * kBinsU), 0, kBinsU - 1);
    const int y = std::clamp(static_cast<int>(uv.y * kBinsV), 0, kBinsV - 1);
    counts[y * kBinsU + x] += 1;
  }
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
  TestRng rng(23);
  for (int k = 0; k < kSamples; ++k) {
    const float u_select = rng.uniform();
    const LightSample s = lights.sample(Vec3(0.0f), u_select, rng.uniform2());
    ASSERT_TRUE(s.valid);
    const Vec2 uv = map_uv(env.to_map(s.wi));
    const int x = std::clamp(static_cast<int>(uv.x * kEnvWidth), 0, kEnvWidth - 1);
    const int y = std::clamp(static_cast<int>(uv.y * kEnvHeight), 0, kEnvHeight - 1);
    counts[y * kEnvWidth + x] += 1;
  }
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

TEST(Lights, SquareEmitterIrradiance) {
  Scene scene;
  add_area_light(scene, square_emitter(1.0f, Rgb(2.0f)));
  const LightTable lights(scene);
  const double expected = 2.0 * M_PI * 4 * corner_form_factor(0.5, 0.5, 1.0);
  expect_agrees(estimate_irradiance(lights, Vec3(0.0f), Vec3(0, 0, 1), 31), expected,
                "square emitter");
  expect_round_trip(scene, lights, Vec3(0.1f, -0.2f, 0.0f), 32);
}

TEST(Lights, SquareEmitterBackSideIsDark) {
  Scene scene;
  const int shape = add_area_light(scene, square_emitter(1.0f, Rgb(2.0f)));
  const LightTable lights(scene);
  TestRng rng(33);
  for (int k = 0; k < 10000; ++k) {
    const float u_select = rng.uniform();
    EXPECT_FALSE(lights.sample(Vec3(0.1f, 0.2f, 2.0f), u_select, rng.uniform2()).valid);
  }
  EXPECT_EQ(lights.area_radiance(shape, Vec3(0, 0, -1), Vec3(0, 0, -1)), Rgb(0.0f));
  EXPECT_EQ(lights.area_radiance(shape, Vec3(0, 0, -1), Vec3(0, 0, 1)), Rgb(2.0f));
}

// A sphere of radius R at distance d subtends sin(alpha) = R / d: E = L pi (R / d)^2 on a plane
// facing it (the same cap as a cone light).
TEST(Lights, SphereEmitterIrradiance) {
  Scene scene;
  add_area_light(scene, sphere_emitter(Vec3(0, 0, 3), 1.0f, Rgb(2.0f)));
  const LightTable lights(scene);
  expect_agrees(estimate_irradiance(lights, Vec3(0.0f), Vec3(0, 0, 1), 34), 2.0 * M_PI / 9.0,
                "sphere emitter");
  expect_round_trip(scene, lights, Vec3(0.2f, 0.1f, -0.5f), 35);
  // From inside, only the sphere's back side is visible.
  TestRng rng(36);
  for (int k = 0; k < 1000; ++k) {
    const float u_select = rng.uniform();
    EXPECT_FALSE(lights.sample(Vec3(0, 0.3f, 3), u_select, rng.uniform2()).valid);
  }
}

// Every kind at once: the selection probability enters each pdf, and the irradiance is the sum
// of the closed forms (cone and sphere both subtend caps).
TEST(Lights, AllKindsTogether) {
  Scene scene;
  const Vec3 n(0, 0, 1);
  scene.lights.push_back(directional_light(Vec3(0.5f, 0, 1), Rgb(1.5f)));
  scene.lights.push_back(cone_light(Vec3(0, 0, 1), 0.3f, Rgb(4.0f)));
  scene.lights.push_back(point_light(Vec3(0, 2, 2), Rgb(3.0f)));
  add_area_light(scene, square_emitter(1.0f, Rgb(2.0f)));
  add_area_light(scene, sphere_emitter(Vec3(3, 0, 3), 1.0f, Rgb(5.0f)));
  for (const LightSelection selection : kSelections) {
    const LightTable lights(scene, selection);
    expect_round_trip(scene, lights, Vec3(0.0f), 41);

    const double directional = 1.5 * dot(n, normalize(Vec3(0.5f, 0, 1)));
    const double cone = 4.0 * M_PI * std::pow(std::sin(0.3), 2);
    const double point = 3.0 * (2.0 / std::sqrt(8.0)) / 8.0;
    const double square = 2.0 * M_PI * 4 * corner_form_factor(0.5, 0.5, 1.0);
    // The sphere's axis is 45 degrees off the normal but its cap stays above the horizon, where
    // the cosine-weighted integral over a cap is pi sin^2(alpha) cos(axis angle).
    const double sphere = 5.0 * M_PI * (1.0 / 18.0) * std::cos(M_PI / 4);
    expect_agrees(estimate_irradiance(lights, Vec3(0.0f), n, 42),
                  directional + cone + point + square + sphere, light_selection_name(selection));
  }
}

// Power selection: probabilities in proportion to the estimates of docs/lights.md, written
// out here. The square emitter (the only shape) gives the distant lights a scene radius of
// half its bounding box's diagonal, sqrt(2) / 2.
TEST(Lights, PowerSelectionFollowsTheEstimates) {
  Scene scene;
  scene.lights.push_back(directional_light(Vec3(0, 0, 1), Rgb(1.0f)));
  scene.lights.push_back(cone_light(Vec3(0, 0, 1), 0.3f, Rgb(4.0f)));
  scene.lights.push_back(constant_env(Rgb(0.1f)));
  scene.lights.push_back(point_light(Vec3(0, 2, 2), Rgb(3.0f)));
  scene.lights.push_back(spot_light(Vec3(0, 0, 2), Vec3(0.0f), Rgb(5.0f), 40, 20));
  add_area_light(scene, square_emitter(1.0f, Rgb(2.0f)));
  const double disk = M_PI * 0.5;  // pi R^2
  const double cos_outer = std::cos(40 * M_PI / 180), cos_inner = std::cos(20 * M_PI / 180);
  const std::vector<double> power = {
      1.0 * disk,     4.0 * 2 * M_PI * (1 - std::cos(0.3)) * disk,        0.1 * 4 * M_PI * disk,
      3.0 * 4 * M_PI, 5.0 * 2 * M_PI * (1 - (cos_outer + cos_inner) / 2), 2.0 * 1.0 * M_PI,
  };
  double total = 0;
  for (const double p : power) total += p;
  const LightTable lights(scene, LightSelection::kPower);
  for (size_t i = 0; i < power.size(); ++i) {
    EXPECT_NEAR(lights.selection_pmf(static_cast<int>(i)), power[i] / total, 1e-6) << "light " << i;
  }
  const LightTable uniform(scene);
  for (size_t i = 0; i < power.size(); ++i) {
    EXPECT_EQ(uniform.selection_pmf(static_cast<int>(i)), 1.0f / 6) << "light " << i;
  }
}

// A light whose estimate is 0 (a distant light with no shape to give a scene radius, a black
// light) still gets a selection probability: the mean of the others' estimates.
TEST(Lights, PowerSelectionNeverStarvesALight) {
  Scene scene;
  scene.lights.push_back(directional_light(Vec3(0, 0, 1), Rgb(1.0f)));
  scene.lights.push_back(point_light(Vec3(0, 0, 2), Rgb(1.0f)));
  scene.lights.push_back(point_light(Vec3(0, 0, 2), Rgb(3.0f)));
  scene.lights.push_back(point_light(Vec3(0, 0, 2), Rgb(0.0f)));
  const LightTable lights(scene, LightSelection::kPower);
  // Estimates 0, 4 pi, 12 pi, 0: the two zeros get the mean 8 pi; 32 pi in all.
  EXPECT_NEAR(lights.selection_pmf(0), 0.25f, 1e-6f);
  EXPECT_NEAR(lights.selection_pmf(1), 0.125f, 1e-6f);
  EXPECT_NEAR(lights.selection_pmf(2), 0.375f, 1e-6f);
  EXPECT_NEAR(lights.selection_pmf(3), 0.25f, 1e-6f);
  const Vec3 n(0, 0, 1);
  expect_agrees(estimate_irradiance(lights, Vec3(0.0f), n, 43, 100000), 1.0 + 4.0 / 4.0,
                "directional + points");
}

}  // namespace
}  // namespace snee
