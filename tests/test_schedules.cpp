// The three schedules (megakernel, local and global wavefront) run the same kernels on the same
// work units, so the image must not depend on which one ran it, nor on the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

Scene small_scene(const std::string& name, int resolution) {
  Scene scene = load_scene(name).scene;
  scene.camera.width = resolution;
  scene.camera.height = resolution;
  return scene;
}

RenderOptions small_options(const char* integrator) {
  RenderOptions o;
  o.spp = 4;
  o.seed = 5;
  o.integrator = integrator;
  o.threads = 1;
  // Small units and queues, so every schedule interleaves several units and refills slots.
  o.tile_size = 8;
  o.samples_per_pass = 2;
  o.queue_capacity = 64;
  return o;
}

class Schedules : public ::testing::TestWithParam<const char*> {};

// On triangle meshes Embree's single-ray and stream traversals return the same bits, so the
// megakernel's one-ray queries reproduce the wavefront's image exactly.
TEST_P(Schedules, EveryScheduleAndThreadCountGivesIdenticalBytesOnAMesh) {
  const Scene scene = small_scene("builtin:bunny-cone-r0.04", 32);
  const RenderOptions base = small_options(GetParam());
  const RenderResult reference = render(scene, base);
  ASSERT_GT(reference.stats.rays[static_cast<int>(RayKind::kShadow)], 0u);
  for (const char* schedule : {"megakernel", "local", "global"}) {
    for (const int threads : {1, 2}) {
      RenderOptions o = base;
      o.schedule = schedule;
      o.threads = threads;
      const RenderResult result = render(scene, o);
      EXPECT_TRUE(test::bitwise_identical(reference.film, result.film))
          << schedule << " with " << threads << " threads";
      EXPECT_EQ(result.stats.paths, reference.stats.paths) << schedule;
      EXPECT_EQ(result.stats.total_rays(), reference.stats.total_rays()) << schedule;
    }
  }
}

// Embree's sphere primitive rounds differently in its single-ray and packet intersectors (about
// one ray in ten differs in the last bits of its hit distance), so there the megakernel traces
// the same estimator along slightly different paths: the wavefront schedules must agree
// bitwise, the megakernel within noise.
TEST_P(Schedules, WavefrontSchedulesAgreeBitwiseAndTheMegakernelWithinNoiseOnASphere) {
  const Scene scene = small_scene("builtin:sphere-cone-r0.04", 32);
  RenderOptions base = small_options(GetParam());
  base.spp = 8;
  const RenderResult reference = render(scene, base);
  for (const int threads : {1, 2}) {
    RenderOptions o = base;
    o.schedule = "global";
    o.threads = threads;
    EXPECT_TRUE(test::bitwise_identical(reference.film, render(scene, o).film))
        << threads << " threads";
  }
  RenderOptions o = base;
  o.schedule = "megakernel";
  o.threads = 2;
  const RenderResult mega = render(scene, o);
  EXPECT_EQ(mega.stats.paths, reference.stats.paths);
  const std::vector<bool> all(reference.film.mean.size(), true);
  const test::RegionStats a = test::region_mean(reference.film, all);
  const test::RegionStats b = test::region_mean(mega.film, all);
  ASSERT_GT(a.standard_error, 0.0);
  EXPECT_LT(std::fabs(a.mean - b.mean), 4 * std::sqrt(a.standard_error * a.standard_error +
                                                      b.standard_error * b.standard_error))
      << a.mean << " vs " << b.mean;
}

TEST(ScheduleStats, MegakernelHoldsOnePathAtATimeAndTheWavefrontBatches) {
  const Scene scene = small_scene("builtin:bunny-cone-r0.04", 16);
  RenderOptions o;
  o.spp = 2;
  o.threads = 1;
  o.schedule = "megakernel";
  const RenderStats mega = render(scene, o).stats;
  EXPECT_DOUBLE_EQ(mega.queue_occupancy, 1.0);
  // One path at a time: the extend stage runs once per traced camera or extension ray.
  const int extend = static_cast<int>(Stage::kExtend);
  EXPECT_EQ(mega.stage_calls[extend], mega.rays[static_cast<int>(RayKind::kCamera)] +
                                          mega.rays[static_cast<int>(RayKind::kExtension)]);
  o.schedule = "local";
  const RenderStats local = render(scene, o).stats;
  EXPECT_GT(local.queue_occupancy, 0.0);
  EXPECT_LT(local.queue_occupancy, 1.0);
  EXPECT_LT(local.stage_calls[extend] * 10, mega.stage_calls[extend]);
}

TEST(ScheduleStats, UnknownScheduleIsRejected) {
  const Scene scene = small_scene("builtin:sphere-cone-r0.04", 8);
  RenderOptions o;
  o.schedule = "sideways";
  EXPECT_THROW(render(scene, o), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Integrators, Schedules, ::testing::Values("pt", "snee"));

}  // namespace
}  // namespace snee
