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
#include "tests/support/light_checks.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::expect_agrees;
using test::expect_round_trip;
using test::kMinPValue;
using test::kSamples;
using test::MeanEstimator;
using test::TestRng;

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

using test::corner_form_factor;

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
