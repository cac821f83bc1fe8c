// Resuming a render from the film's exact state (scheduler/film_state.h, docs/resume.md): a
// render stopped after any number of units and resumed, once or several times, with any thread
// count or schedule, ends bitwise the uninterrupted render, with or without a noise target; a
// complete render's state goes on to a larger spp as if that spp had been asked for at first.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <optional>
#include <stdexcept>

#include "scene/scene_loader.h"
#include "scheduler/film_accumulator.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

Scene small_scene() {
  Scene scene = load_scene("builtin:sphere-directional-r0.2").scene;
  scene.camera.width = 32;
  scene.camera.height = 32;
  return scene;
}

RenderOptions base_options() {
  RenderOptions o;
  o.spp = 48;
  o.seed = 7;
  o.threads = 2;
  o.tile_size = 8;
  o.samples_per_unit = 4;
  o.queue_capacity = 64;
  return o;
}

// Renders from `from` (none: the start) and asks to stop once `units` units have finished
// (0: never); returns the result, whose state is always kept.
RenderResult run(const Scene& scene, const RenderOptions& o, const FilmState* from, int units) {
  std::atomic<int> finished{0};
  RenderHooks hooks;
  hooks.checkpoint_state = [](const FilmState&) {};
  hooks.progress = [&](const Progress&) { ++finished; };
  hooks.stop_requested = [&] { return units > 0 && finished.load() >= units; };
  return render(scene, o, hooks, from);
}

void expect_same_image(const Film& a, const Film& b) {
  EXPECT_TRUE(test::bitwise_identical(a, b));
  EXPECT_EQ(a.pixel_spp, b.pixel_spp);
  EXPECT_EQ(a.meta.min_spp, b.meta.min_spp);
}

// The grid has 4 x 4 tiles x 12 chunks = 192 units; stops fall early, in the middle and late.
TEST(Resume, StoppedAndResumedRendersEndBitwiseTheUninterruptedOne) {
  const Scene scene = small_scene();
  for (const double target : {0.0, 0.4}) {
    RenderOptions o = base_options();
    o.noise_target = target;
    const RenderResult reference = run(scene, o, nullptr, 0);
    ASSERT_TRUE(reference.complete);
    for (const int stop : {1, 90, 180}) {
      const RenderResult stopped = run(scene, o, nullptr, stop);
      ASSERT_FALSE(stopped.complete) << "stop after " << stop;
      ASSERT_TRUE(stopped.state);
      // Stopped again, then resumed with other threads and another schedule.
      RenderOptions other = o;
      other.threads = 1;
      other.schedule = "global";
      const RenderResult again = run(scene, other, &*stopped.state, stop + 5);
      ASSERT_TRUE(again.state);
      RenderOptions third = o;
      third.threads = 3;
      const RenderResult resumed = run(scene, third, &*again.state, 0);
      EXPECT_TRUE(resumed.complete);
      expect_same_image(resumed.film, reference.film);
      // Resumed once, straight to the end.
      expect_same_image(run(scene, other, &*stopped.state, 0).film, reference.film);
    }
  }
}

// The noise target's per-tile decisions survive: a tile that had converged takes nothing more.
TEST(Resume, ConvergedTilesStayConverged) {
  const Scene scene = small_scene();
  RenderOptions o = base_options();
  o.noise_target = 0.4;
  const RenderResult reference = run(scene, o, nullptr, 0);
  uint32_t fewest = UINT32_MAX, most = 0;
  for (const uint32_t n : reference.film.pixel_spp) {
    fewest = std::min(fewest, n);
    most = std::max(most, n);
  }
  ASSERT_LT(fewest, most) << "the target must stop some tiles early for this test to mean much";
  const RenderResult stopped = run(scene, o, nullptr, 120);
  size_t converged = 0;
  for (const TileState& t : stopped.state->tiles) converged += t.converged ? 1 : 0;
  EXPECT_GT(converged, 0u);
  expect_same_image(run(scene, o, &*stopped.state, 0).film, reference.film);
}

TEST(Resume, ACompleteRenderGoesOnToALargerSpp) {
  const Scene scene = small_scene();
  RenderOptions o = base_options();
  const RenderResult done = run(scene, o, nullptr, 0);
  RenderOptions more = o;
  more.spp = 70;  // not a multiple of samples_per_unit: the last chunk is short
  expect_same_image(run(scene, more, &*done.state, 0).film, run(scene, more, nullptr, 0).film);
}

// A time budget already spent when the render resumes still finishes the rounds some tile had
// begun, so every tile holds the same whole rounds.
TEST(Resume, ASpentTimeBudgetFinishesTheRoundsBegun) {
  const Scene scene = small_scene();
  RenderOptions o = base_options();
  const RenderResult stopped = run(scene, o, nullptr, 20);
  FilmState state = *stopped.state;
  state.seconds = 1e6;
  RenderOptions timed = o;
  timed.time_seconds = 1;
  const RenderResult resumed = run(scene, timed, &state, 0);
  EXPECT_TRUE(resumed.time_budget_spent);
  uint32_t begun = 0;
  for (const TileState& t : state.tiles) begun = std::max(begun, t.chunks);
  EXPECT_EQ(resumed.film.meta.min_spp, static_cast<int>(begun) * o.samples_per_unit);
  for (const TileState& t : resumed.state->tiles) EXPECT_EQ(t.chunks, begun);
}

TEST(Resume, AStateOfAnotherShapeIsRefused) {
  const Scene scene = small_scene();
  const RenderOptions o = base_options();
  const RenderResult done = run(scene, o, nullptr, 0);
  RenderOptions other_tiles = o;
  other_tiles.tile_size = 4;
  EXPECT_THROW(run(scene, other_tiles, &*done.state, 0), std::invalid_argument);
  FilmState short_sums = *done.state;
  short_sums.sums.pop_back();
  EXPECT_THROW(run(scene, o, &short_sums, 0), std::invalid_argument);
  FilmState too_many = *done.state;
  too_many.tiles[0].chunks = 1000;
  EXPECT_THROW(run(scene, o, &too_many, 0), std::invalid_argument);
}

}  // namespace
}  // namespace snee
