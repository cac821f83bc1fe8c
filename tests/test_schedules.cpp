// The three schedules (megakernel, local and global wavefront) run the same kernels on the same
// work units, so the image must not depend on which one ran it, nor on the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"
#include "tests/support/test_size.h"

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
  o.samples_per_unit = 2;
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

// Two translucent objects in different media (one rough, one smooth) on a diffuse floor: the
// wavefront's SIMD chunks mix media and interface kinds (the lane-by-lane medium lookup, the
// mixed smooth/rough dielectric path, diffuse lanes beside dielectric ones), while the
// megakernel's one-lane chunks never do. Every lane is its own function, so the bytes agree.
TEST_P(Schedules, MixedMediaAndMaterialsInOneChunkGiveIdenticalBytes) {
  Scene scene = small_scene("builtin:default", 40);
  size_t object = scene.shapes.size();
  for (size_t i = 0; i < scene.shapes.size(); ++i)
    if (scene.shapes[i].interior_medium >= 0) object = i;
  ASSERT_LT(object, scene.shapes.size()) << "the default scene has a translucent object";
  Shape twin = scene.shapes[object];
  twin.name = "twin";
  // A smaller copy beside the original, resting on the same floor.
  float bottom = kInfinity;
  for (const Vec3& p : twin.mesh.positions) bottom = std::min(bottom, p.y);
  for (Vec3& p : twin.mesh.positions) p = p * 0.6f + Vec3(1.3f, 0.4f * bottom, 0.3f);
  Material smooth = scene.materials[static_cast<size_t>(twin.material)];
  smooth.name = "smooth";
  smooth.roughness = 0.0f;
  smooth.ior = 1.33f;
  scene.materials.push_back(smooth);
  twin.material = static_cast<int>(scene.materials.size()) - 1;
  Medium denser = scene.media[static_cast<size_t>(twin.interior_medium)];
  denser.name = "denser";
  denser.sigma_s = denser.sigma_s * 3.0f;
  denser.g = 0.4f;
  scene.media.push_back(denser);
  twin.interior_medium = static_cast<int>(scene.media.size()) - 1;
  scene.shapes.push_back(twin);

  RenderOptions o = small_options(GetParam());
  o.tile_size = 40;  // one tile: every queue holds paths of both objects and of the floor
  o.queue_capacity = 256;
  const RenderResult local = render(scene, o);
  EXPECT_GT(local.stats.simd_lanes[static_cast<int>(BatchedKernel::kMediumFlights)].active, 0u);
  o.schedule = "megakernel";
  EXPECT_TRUE(test::bitwise_identical(local.film, render(scene, o).film));
}

// Embree's sphere primitive rounds differently in its single-ray, packet and stream intersectors
// (about one ray in ten differs in the last bits of its hit distance), and which one a ray meets
// depends on its batch; the distance to a sphere is recomputed from the ray and the sphere alone
// (EmbreeScene::intersect), so every schedule and batch size gives the same bits there too. The
// second scene runs SNEE's manifold strategy and its reflection chains.
TEST_P(Schedules, EveryScheduleAndBatchSizeAgreesBitwiseOnASphere) {
  for (const char* name : {"builtin:sphere-cone-r0.04", "builtin:sphere-directional-smooth"}) {
    const Scene scene = small_scene(name, 32);
    RenderOptions base = small_options(GetParam());
    base.spp = test::sanitized_share(8);
    const RenderResult reference = render(scene, base);
    for (const char* schedule : {"global", "megakernel"}) {
      for (const int threads : {1, 2}) {
        RenderOptions o = base;
        o.schedule = schedule;
        o.threads = threads;
        EXPECT_TRUE(test::bitwise_identical(reference.film, render(scene, o).film))
            << name << " " << schedule << ", " << threads << " threads";
      }
    }
    for (const int capacity : {16, 37, 1024}) {
      RenderOptions o = base;
      o.queue_capacity = capacity;
      EXPECT_TRUE(test::bitwise_identical(reference.film, render(scene, o).film))
          << name << " queue capacity " << capacity;
    }
  }
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
