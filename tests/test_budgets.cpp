// Sample budgets (docs/budgets.md): adaptive sampling to a noise target decides per tile from
// the tile's own samples, so its image is as deterministic as a plain render's; a time budget
// stops between rounds, so every pixel holds whole rounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "scene/scene_loader.h"
#include "scheduler/noise_target.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

// A translucent sphere lit by a directional light on a black background: the background is
// noiseless, the sphere is not.
Scene sphere_on_black(int resolution) {
  Scene scene = load_scene("builtin:sphere-directional-r0.2").scene;
  scene.camera.width = resolution;
  scene.camera.height = resolution;
  return scene;
}

RenderOptions adaptive_options() {
  RenderOptions o;
  o.spp = 128;
  o.seed = 3;
  o.threads = 1;
  o.tile_size = 8;
  o.samples_per_unit = 8;
  o.queue_capacity = 64;
  o.noise_target = 0.1;
  return o;
}

double pixel_error(const Film& film, size_t p) {
  double mean[3], variance_of_mean[3];
  for (int c = 0; c < 3; ++c) {
    mean[c] = film.mean[p][c];
    variance_of_mean[c] = film.variance_of_mean[p][c];
  }
  return relative_standard_error(mean, variance_of_mean);
}

// The megakernel is left out: on this analytic sphere its single-ray queries differ from the
// wavefront's in the last bits even without a noise target (tests/test_schedules.cpp).
TEST(NoiseTarget, ImageIsBitwiseTheSameForAnyThreadCountAndSchedule) {
  const Scene scene = sphere_on_black(32);
  const RenderResult reference = render(scene, adaptive_options());
  for (const char* schedule : {"local", "global"}) {
    for (const int threads : {1, 2}) {
      RenderOptions o = adaptive_options();
      o.schedule = schedule;
      o.threads = threads;
      const RenderResult result = render(scene, o);
      EXPECT_TRUE(test::bitwise_identical(reference.film, result.film))
          << schedule << " with " << threads << " threads";
      EXPECT_EQ(result.film.pixel_spp, reference.film.pixel_spp) << schedule;
      EXPECT_TRUE(result.complete);
    }
  }
}

// The black background meets the target at the first decision; the sphere's tiles take more,
// never more than spp, and every tile that stopped before spp meets the target.
TEST(NoiseTarget, NoisyTilesTakeMoreSamplesAndStoppedTilesMeetTheTarget) {
  const Scene scene = sphere_on_black(32);
  const RenderOptions o = adaptive_options();
  const Film film = render(scene, o).film;
  ASSERT_EQ(film.pixel_spp.size(), film.mean.size());
  uint32_t fewest = UINT32_MAX, most = 0;
  for (size_t p = 0; p < film.mean.size(); ++p) {
    const uint32_t n = film.pixel_spp[p];
    fewest = std::min(fewest, n);
    most = std::max(most, n);
    EXPECT_LE(n, static_cast<uint32_t>(o.spp));
    EXPECT_EQ(n % static_cast<uint32_t>(o.samples_per_unit), 0u) << "whole chunks";
    // Stopped before the cap: it met the target (float rounding of the stored film aside).
    if (n < static_cast<uint32_t>(o.spp)) {
      EXPECT_LE(pixel_error(film, p), o.noise_target * (1 + 1e-4)) << "pixel " << p;
    }
  }
  EXPECT_EQ(fewest, kMinAdaptiveSpp) << "the black corners stop at the first decision";
  EXPECT_GT(most, 2 * kMinAdaptiveSpp) << "the sphere needs more";
  EXPECT_EQ(film.meta.min_spp, static_cast<int>(fewest));
  EXPECT_EQ(film.pixel_spp.front(), fewest) << "the top-left corner is background";
  // The centre of the sphere is lit and noisy.
  EXPECT_GT(film.pixel_spp[16 * 32 + 16], fewest);
}

// With a target no tile can meet, every pixel gets exactly spp: the cap, and the same image as
// a plain render.
TEST(NoiseTarget, AnUnreachableTargetGivesThePlainRender) {
  const Scene scene = sphere_on_black(16);
  RenderOptions o = adaptive_options();
  o.spp = 24;
  o.noise_target = 1e-9;
  const RenderResult adaptive = render(scene, o);
  // The black background has no noise at all, so it meets any target; only the sphere's tiles
  // are capped.
  RenderOptions plain = o;
  plain.noise_target = 0;
  const RenderResult reference = render(scene, plain);
  for (size_t p = 0; p < adaptive.film.mean.size(); ++p) {
    if (adaptive.film.pixel_spp[p] == 24u) {
      EXPECT_EQ(adaptive.film.mean[p], reference.film.mean[p]) << p;
    }
  }
  EXPECT_EQ(*std::max_element(adaptive.film.pixel_spp.begin(), adaptive.film.pixel_spp.end()), 24u);
  EXPECT_TRUE(adaptive.complete);
}

// A time budget already spent when the second round would start: the first round finishes
// everywhere and nothing more starts, so the image is the plain render of one round's spp.
TEST(TimeBudget, StopsBetweenRoundsWithWholeRoundsEverywhere) {
  const Scene scene = sphere_on_black(16);
  RenderOptions o = adaptive_options();
  o.noise_target = 0;
  o.spp = 1000000;
  o.time_seconds = 1e-9;
  const RenderResult timed = render(scene, o);
  EXPECT_TRUE(timed.time_budget_spent);
  EXPECT_TRUE(timed.complete) << "a budget stop is not an interruption";
  EXPECT_EQ(timed.film.meta.spp, 1000000);
  EXPECT_EQ(timed.film.meta.min_spp, o.samples_per_unit);
  for (const uint32_t n : timed.film.pixel_spp) EXPECT_EQ(n, 8u);
  RenderOptions plain = o;
  plain.time_seconds = 0;
  plain.spp = 8;
  EXPECT_TRUE(test::bitwise_identical(timed.film, render(scene, plain).film));
}

TEST(Budgets, RenderRefusesBadValues) {
  const Scene scene = sphere_on_black(4);
  for (const double bad : {-1.0, std::nan(""), HUGE_VAL}) {
    RenderOptions o = adaptive_options();
    o.noise_target = bad;
    EXPECT_THROW(render(scene, o), std::invalid_argument) << bad;
    o = adaptive_options();
    o.time_seconds = bad;
    EXPECT_THROW(render(scene, o), std::invalid_argument) << bad;
  }
}

}  // namespace
}  // namespace snee
