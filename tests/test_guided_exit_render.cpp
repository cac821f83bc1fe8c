// Whole-image checks of the guided exit (docs/method.md 3.15): it changes only the variance, so
// snee with it renders the image of snee without it where both converge (the rough sphere under
// the cone, the glossy sphere under the directional light, where the walk's light samples work,
// and the smooth sphere under a wide cone, where the walk's refracted exits find it), inside the
// bunny's flat-shaded mesh, and with an area light and a point light, whose hits the guided exit
// shares only in part; its rate changes nothing either; and its images are bitwise the same on any
// number of threads and queue size. Tolerances are multiples of the standard error measured from
// the films' per-pixel variance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

Scene sphere_scene(const std::string& name) {
  Scene scene = load_builtin_scene(name).scene;
  scene.camera.width = scene.camera.height = 32;
  return scene;
}

Film render_guided(const Scene& scene, float guide_rate, int spp, uint32_t seed,
                   int max_depth = 1024) {
  RenderOptions options;
  options.integrator = "snee";
  options.snee.light_limit_degrees = 180;  // SNEE and its targets under any light
  options.snee.guide_rate = guide_rate;
  options.max_depth = max_depth;
  options.spp = spp;
  options.seed = seed;
  return render(scene, options).film;
}

void expect_guide_changes_nothing(const Scene& scene, const std::string& what, int spp,
                                  uint32_t seed, int max_depth = 1024) {
  const Film without = render_guided(scene, 0.0f, spp, seed, max_depth);
  const Film with = render_guided(scene, 1.0f, spp, seed + 1, max_depth);
  ASSERT_GT(test::region_mean(with, test::sphere_mask(scene)).mean, 0.005)
      << what << ": a black image proves nothing";
  EXPECT_GE(test::expect_same_image(without, with, what), 4)
      << what << ": too few converged blocks";
}

// The four strategies of a glossy boundary under a distant light, and single scattering alone
// (--max-depth 3), where the guided exit carries most of the light.
TEST(GuidedExit, MatchesTheWalkUnderTheCone) {
  const Scene scene = sphere_scene("sphere-cone-r0.2");
  expect_guide_changes_nothing(scene, "sphere-cone-r0.2", 256, 11);
  expect_guide_changes_nothing(scene, "sphere-cone-r0.2, single scattering", 2048, 13, 3);
}

// A closed flat-shaded mesh: the axes come from its facets' refracted beams and the exit point
// from a ray.
TEST(GuidedExit, MatchesTheWalkInsideAMesh) {
  Scene scene = load_builtin_scene("bunny-cone-r0.2").scene;
  scene.camera.width = scene.camera.height = 48;
  const Film without = render_guided(scene, 0.0f, 256, 61);
  const Film with = render_guided(scene, 1.0f, 256, 62);
  const std::vector<bool> all(with.mean.size(), true);
  ASSERT_GT(test::region_mean(with, all).mean, 0.005) << "a black image proves nothing";
  EXPECT_GE(test::expect_same_image(without, with, "bunny-cone-r0.2"), 4);
}

// A delta light: the walk's and the guided exit's light samples share the paths.
TEST(GuidedExit, MatchesTheWalkUnderTheDirectionalLight) {
  expect_guide_changes_nothing(sphere_scene("sphere-directional-r0.04"), "sphere-directional-r0.04",
                               256, 21);
}

// A smooth boundary: only refracted exits reach the light, the walk's and the guided exit's;
// under a 10-degree cone the walk finds it often enough to converge.
TEST(GuidedExit, MatchesTheWalkBehindASmoothBoundary) {
  Scene scene = sphere_scene("sphere-cone-smooth");
  Light& light = scene.lights[0];
  const Rgb irradiance = light.radiance * (2.0f * kPi * (1.0f - std::cos(light.half_angle)));
  light.half_angle = 10.0f * kPi / 180.0f;
  light.radiance = irradiance / (2.0f * kPi * (1.0f - std::cos(light.half_angle)));
  expect_guide_changes_nothing(scene, "smooth sphere, 10-degree cone", 512, 31);
}

// An area light (whose hits after the walk's exit the guided exit does not share) and a point
// light (a positional target) over the rough sphere.
TEST(GuidedExit, MatchesTheWalkUnderAreaAndPointLights) {
  Scene scene = sphere_scene("sphere-cone-r0.2");
  test::light_by_panel_and_bulb(scene);
  expect_guide_changes_nothing(scene, "area and point lights", 256, 41);
}

// The rate is in the guided exit's density, so running it at a quarter of the vertices renders
// the same image as running it at every one, here behind the glossy boundary under the cone
// where the walk alone does not converge at a test's sample count.
TEST(GuidedExit, RateChangesNothing) {
  const Scene scene = sphere_scene("sphere-cone-r0.04");
  const Film always = render_guided(scene, 1.0f, 256, 51);
  const Film quarter = render_guided(scene, 0.25f, 256, 52);
  EXPECT_GE(test::expect_same_image(always, quarter, "sphere-cone-r0.04, rate 1 vs 0.25"), 4);
}

TEST(GuidedExit, IsDeterministic) {
  Scene scene = sphere_scene("sphere-cone-r0.04");
  scene.camera.width = scene.camera.height = 24;
  const auto film = [&](int threads, int queue_capacity) {
    RenderOptions options;
    options.integrator = "snee";
    options.snee.guide_rate = 0.5f;
    options.spp = 8;
    options.threads = threads;
    if (queue_capacity > 0) options.queue_capacity = queue_capacity;
    return render(scene, options).film;
  };
  EXPECT_TRUE(test::bitwise_identical(film(1, 0), film(2, 37)));
}

}  // namespace
}  // namespace snee
