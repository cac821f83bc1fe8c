// Checkpoints and stop requests (RenderHooks): a snapshot or a stopped render holds, in every
// pixel, exactly the estimate of a complete render with that pixel's sample count, and taking
// checkpoints does not change the final image.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

constexpr int kSpp = 4;

Scene small_scene() {
  Scene scene = load_builtin_scene("bunny-cone-r0.04").scene;
  scene.camera.width = 48;
  scene.camera.height = 32;
  return scene;
}

RenderOptions small_options() {
  RenderOptions o;
  o.spp = kSpp;
  o.seed = 9;
  o.integrator = "snee";
  o.threads = 2;
  o.tile_size = 8;
  o.samples_per_unit = 1;  // a unit per sample index, so partial films hold every count
  return o;
}

// complete[n] is the film of a complete render with n samples (n = 1..kSpp). Each pixel of a
// partial film must equal, bit for bit, the same pixel of the complete film with as many
// samples as it holds (black if none), and no pixel may hold fewer than min_spp.
void expect_pixels_are_prefixes(const Film& partial, const std::vector<Film>& complete) {
  int fewest = kSpp;
  for (size_t p = 0; p < partial.mean.size(); ++p) {
    int held = -1;
    if (partial.mean[p] == Rgb(0.0f) && partial.variance_of_mean[p] == Rgb(0.0f)) held = 0;
    for (int n = kSpp; n >= 1 && held < 0; --n) {
      if (partial.mean[p] == complete[n].mean[p] &&
          partial.variance_of_mean[p] == complete[n].variance_of_mean[p])
        held = n;
    }
    ASSERT_GE(held, 0) << "pixel " << p << " matches no sample count";
    fewest = std::min(fewest, held);
  }
  // A black pixel might also be a real prefix of black samples, so min_spp may exceed it.
  EXPECT_LE(partial.meta.min_spp, kSpp);
  EXPECT_GE(partial.meta.min_spp, fewest > 0 ? fewest : 0);
}

std::vector<Film> complete_films(const Scene& scene) {
  std::vector<Film> films(kSpp + 1);
  for (int n = 1; n <= kSpp; ++n) {
    RenderOptions o = small_options();
    o.spp = n;
    films[n] = render(scene, o).film;
  }
  return films;
}

TEST(RenderHooks, AStoppedRenderKeepsEveryFinishedUnit) {
  const Scene scene = small_scene();
  const std::vector<Film> complete = complete_films(scene);
  RenderHooks hooks;
  std::atomic<int> units{0};
  // Progress comes after every finished unit: stop after the 10th of 24 tiles x 4 chunks = 96.
  hooks.progress = [&](const Progress&) { ++units; };
  hooks.stop_requested = [&] { return units >= 10; };
  const RenderOptions options = small_options();
  const RenderResult stopped = render(scene, options, hooks);
  EXPECT_FALSE(stopped.complete);
  EXPECT_EQ(stopped.film.meta.min_spp, 0) << "most tiles have not had their first unit";
  EXPECT_EQ(stopped.film.meta.spp, kSpp);
  // The units in flight when the stop came are dropped or, if they finished before their
  // thread saw it, kept: the 10 plus at most one per other thread, each 8 x 8 pixels x 1
  // sample (paths of dropped units count as traced).
  EXPECT_GE(units.load(), 10);
  EXPECT_LE(units.load(), 10 + options.threads - 1);
  EXPECT_GE(stopped.stats.paths, 10u * 64u);
  EXPECT_LE(stopped.stats.paths, static_cast<uint64_t>(10 + options.threads - 1) * 64u);
  expect_pixels_are_prefixes(stopped.film, complete);

  const RenderResult full = render(scene, small_options());
  EXPECT_TRUE(full.complete);
  EXPECT_EQ(full.film.meta.min_spp, kSpp);
}

// A stop is seen between turns of a unit, not only when one finishes: with one unit holding
// the whole image and every sample, the render still returns, with nothing in the film.
TEST(RenderHooks, AStopDropsTheUnitInFlight) {
  const Scene scene = small_scene();
  RenderOptions options = small_options();
  options.tile_size = 64;
  options.samples_per_unit = kSpp;
  options.threads = 1;
  std::atomic<int> asked{0};
  RenderHooks hooks;
  hooks.stop_requested = [&] { return ++asked > 3; };
  const RenderResult stopped = render(scene, options, hooks);
  EXPECT_FALSE(stopped.complete);
  EXPECT_EQ(stopped.film.meta.min_spp, 0);
  for (const Rgb& pixel : stopped.film.mean) ASSERT_EQ(pixel, Rgb(0.0f));
  // 48 x 32 x 4 paths in 256 slots: three turns start at most a fraction of them.
  EXPECT_LT(stopped.stats.paths, 48u * 32u * kSpp);
  for (const std::string schedule : {"megakernel", "global"}) {
    options.schedule = schedule;
    asked = 0;
    const RenderResult other = render(scene, options, hooks);
    EXPECT_FALSE(other.complete) << schedule;
    EXPECT_LT(other.stats.paths, 48u * 32u * kSpp) << schedule;
  }
}

TEST(RenderHooks, ThreadsAndQueueCapacityAreBounded) {
  const Scene scene = small_scene();
  RenderOptions options = small_options();
  options.threads = max_render_threads() + 1;
  EXPECT_THROW(render(scene, options), std::invalid_argument);
  options.threads = 1;
  for (const int capacity : {kMinQueueCapacity - 1, kMaxQueueCapacity + 1}) {
    options.queue_capacity = capacity;
    EXPECT_THROW(render(scene, options), std::invalid_argument) << capacity;
  }
  options.spp = 1;
  for (const int capacity : {kMinQueueCapacity, kMaxQueueCapacity}) {
    options.queue_capacity = capacity;
    EXPECT_TRUE(render(scene, options).complete) << capacity;
  }
}

TEST(RenderHooks, TileSizeAndSamplesPerUnitAreBounded) {
  const Scene scene = small_scene();
  RenderOptions options = small_options();
  for (const int tile : {0, kMaxTileSize + 1}) {
    options.tile_size = tile;
    EXPECT_THROW(render(scene, options), std::invalid_argument) << tile;
  }
  options.tile_size = kMaxTileSize;
  for (const int samples : {0, kMaxSamplesPerUnit + 1}) {
    options.samples_per_unit = samples;
    EXPECT_THROW(render(scene, options), std::invalid_argument) << samples;
  }
  options.samples_per_unit = kMaxSamplesPerUnit;
  EXPECT_TRUE(render(scene, options).complete);
}

TEST(RenderHooks, CheckpointsAreConsistentAndLeaveTheImageUnchanged) {
  const Scene scene = small_scene();
  const std::vector<Film> complete = complete_films(scene);
  RenderHooks hooks;
  std::vector<Film> checkpoints;
  hooks.checkpoint_seconds = 1e-9;  // after every unit, as far as the one-at-a-time rule allows
  hooks.checkpoint = [&](const Film& f) { checkpoints.push_back(f); };  // never concurrent
  const RenderResult result = render(scene, small_options(), hooks);
  ASSERT_GE(checkpoints.size(), 2u);
  for (const Film& f : checkpoints) {
    expect_pixels_are_prefixes(f, complete);
    EXPECT_EQ(f.meta.integrator, "snee");
    EXPECT_EQ(f.meta.spp, kSpp);
    EXPECT_GT(f.meta.render_seconds, 0.0);
  }
  EXPECT_TRUE(result.complete);
  EXPECT_TRUE(test::bitwise_identical(result.film, complete[kSpp]));
}

}  // namespace
}  // namespace snee
