// SNEE runs only where some light is small (docs/method.md 3.11): the apparent size of each kind
// of light; `snee` under only large lights is bitwise the path tracer's image, while a limit of
// 180 degrees (or a small light) keeps SNEE running; bottom-to-top runs only when an escaped
// light is wide.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/physics/snee/light_extent.h"
#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

Light light_of(LightKind kind) {
  Light light;
  light.kind = kind;
  return light;
}

TEST(LightExtent, DeltaLightsAreSmallestAndEnvironmentsFillTheSky) {
  const Scene scene;
  EXPECT_EQ(light_half_angle_degrees(scene, light_of(LightKind::kDirectional)), 0.0f);
  EXPECT_EQ(light_half_angle_degrees(scene, light_of(LightKind::kPoint)), 0.0f);
  EXPECT_EQ(light_half_angle_degrees(scene, light_of(LightKind::kSpot)), 0.0f);
  EXPECT_EQ(light_half_angle_degrees(scene, light_of(LightKind::kConstantEnv)), 180.0f);
  EXPECT_EQ(light_half_angle_degrees(scene, light_of(LightKind::kEnvMap)), 180.0f);
  Light cone = light_of(LightKind::kCone);
  cone.half_angle = 5.0f * kPi / 180.0f;
  EXPECT_NEAR(light_half_angle_degrees(scene, cone), 5.0f, 1e-5f);
  EXPECT_EQ(smallest_light_half_angle_degrees(scene), 180.0f);  // no light at all
}

// An emissive sphere of radius r at distance D from the medium's centre: its bounding box's
// half-diagonal is r sqrt(3), so it counts as asin(r sqrt(3) / D); from inside that, 180.
TEST(LightExtent, AreaLightIsItsBoundingSphereSeenFromTheMedia) {
  Scene scene;
  Shape medium_sphere;
  medium_sphere.kind = ShapeKind::kSphere;
  medium_sphere.center = {2, 0, 0};
  medium_sphere.interior_medium = 0;
  scene.shapes.push_back(medium_sphere);
  Shape emitter;
  emitter.kind = ShapeKind::kSphere;
  emitter.center = {2, 10, 0};
  emitter.radius = 0.5f;
  scene.shapes.push_back(emitter);
  Light area = light_of(LightKind::kArea);
  area.shape = 1;
  scene.lights.push_back(area);
  const double expected = std::asin(0.5 * std::sqrt(3.0) / 10.0) * 180.0 / std::acos(-1.0);
  EXPECT_NEAR(light_half_angle_degrees(scene, area), expected, 1e-4);
  scene.shapes[1].center = {2, 0.5f, 0};
  EXPECT_EQ(light_half_angle_degrees(scene, area), 180.0f);
  Light directional = light_of(LightKind::kDirectional);
  scene.lights.push_back(directional);
  EXPECT_EQ(smallest_light_half_angle_degrees(scene), 0.0f);
}

Scene small_grid_scene(const std::string& name) {
  Scene scene = load_builtin_scene(name).scene;
  scene.camera.width = scene.camera.height = 16;
  return scene;
}

RenderResult render_with(const Scene& scene, const std::string& integrator, float limit) {
  RenderOptions options;
  options.integrator = integrator;
  options.spp = 8;
  options.seed = 7;
  options.snee.light_limit_degrees = limit;
  return render(scene, options);
}

TEST(SneeEngagement, UnderOnlyAnEnvironmentSneeIsThePathTracer) {
  const Scene scene = small_grid_scene("sphere-env-r0.04");
  const RenderResult pt = render_with(scene, "pt", kDefaultLightLimitDegrees);
  const RenderResult snee = render_with(scene, "snee", kDefaultLightLimitDegrees);
  EXPECT_FALSE(snee.stats.snee_engaged);
  EXPECT_EQ(snee.stats.smallest_light_degrees, 180.0f);
  EXPECT_EQ(snee.stats.rays[static_cast<size_t>(RayKind::kProbe)], 0u);
  EXPECT_TRUE(test::bitwise_identical(pt.film, snee.film));
  EXPECT_EQ(snee.film.meta.integrator, "snee");  // what was asked for
}

TEST(SneeEngagement, LimitOf180OrASmallLightKeepsSneeRunning) {
  const RenderResult forced = render_with(small_grid_scene("sphere-env-r0.04"), "snee", 180.0f);
  EXPECT_TRUE(forced.stats.snee_engaged);
  EXPECT_GT(forced.stats.rays[static_cast<size_t>(RayKind::kProbe)], 0u);
  const Scene cone = small_grid_scene("sphere-cone-r0.04");
  const RenderResult small = render_with(cone, "snee", kDefaultLightLimitDegrees);
  EXPECT_TRUE(small.stats.snee_engaged);
  EXPECT_NEAR(small.stats.smallest_light_degrees, 2.67f, 1e-4f);
  EXPECT_FALSE(test::bitwise_identical(small.film, render_with(cone, "pt", 180.0f).film));
  // A limit below the cone's half-angle turns it off there too.
  EXPECT_FALSE(render_with(cone, "snee", 2.0f).stats.snee_engaged);
}

// Bottom-to-top looks up the light in the direction it refracts out along; under only small
// lights it is left out, which is exactly the render with the other strategies enabled.
TEST(SneeEngagement, BottomToTopRunsOnlyWhenAnEscapedLightIsWide) {
  const Scene cone = small_grid_scene("sphere-cone-r0.04");
  const RenderResult by_rule = render_with(cone, "snee", kDefaultLightLimitDegrees);
  EXPECT_FALSE(by_rule.stats.snee_strategies.contains(Strategy::kBottomToTop));
  EXPECT_EQ(by_rule.stats.snee[static_cast<size_t>(SneeCounter::kBottomToTopConnections)], 0u);
  RenderOptions explicit_set;
  explicit_set.integrator = "snee";
  explicit_set.spp = 8;
  explicit_set.seed = 7;
  explicit_set.snee.enabled = parse_strategy_set("tb,ub,ul,mn");
  EXPECT_TRUE(test::bitwise_identical(by_rule.film, render(cone, explicit_set).film));

  // A limit of 180 keeps every strategy, and a limit below the cone's half-angle makes it wide.
  EXPECT_TRUE(
      render_with(cone, "snee", 180.0f).stats.snee_strategies.contains(Strategy::kBottomToTop));
  Scene wide_cone = cone;
  wide_cone.lights.push_back(wide_cone.lights[0]);
  wide_cone.lights[1].half_angle = 20.0f * kPi / 180.0f;
  const RenderResult all = render_with(wide_cone, "snee", kDefaultLightLimitDegrees);
  EXPECT_TRUE(all.stats.snee_strategies.contains(Strategy::kBottomToTop));
  EXPECT_GT(all.stats.snee[static_cast<size_t>(SneeCounter::kBottomToTopPlacement)] +
                all.stats.snee[static_cast<size_t>(SneeCounter::kBottomToTopRefraction)],
            0u);
  // The default scene's sky is wide and its key light small: SNEE runs with all five.
  Scene key_and_sky = load_builtin_scene("default").scene;
  key_and_sky.camera.width = key_and_sky.camera.height = 8;
  RenderOptions one_sample;
  one_sample.integrator = "snee";
  one_sample.spp = 1;
  const RenderResult both = render(key_and_sky, one_sample);
  EXPECT_TRUE(both.stats.snee_engaged);
  EXPECT_TRUE(both.stats.snee_strategies.contains(Strategy::kBottomToTop));
}

}  // namespace
}  // namespace snee
