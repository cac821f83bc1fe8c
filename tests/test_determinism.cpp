// Bitwise determinism: the image depends only on scene, seed and spp, never on the thread
// count, the queue capacity (batch size), the tile size or how samples are cut into passes.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

class Determinism : public ::testing::TestWithParam<const char*> {};

TEST_P(Determinism, ThreadsBatchSizesAndTilesGiveIdenticalBytes) {
  Scene scene = load_builtin_scene("default").scene;
  scene.camera.width = 40;
  scene.camera.height = 30;
  RenderOptions base;
  base.spp = 6;
  base.seed = 3;
  base.integrator = GetParam();
  base.threads = 1;
  base.queue_capacity = 1024;
  const Film reference = render(scene, base).film;

  RenderOptions two_threads = base;
  two_threads.threads = 2;
  RenderOptions small_batches = base;
  small_batches.queue_capacity = 37;
  small_batches.threads = 2;
  RenderOptions other_tiles = base;
  other_tiles.tile_size = 7;
  other_tiles.samples_per_unit = 2;
  // More threads than the machine has and units of one sample, so that several chunks of one
  // tile are in flight at once and finish out of order (the film parks the early finishers).
  RenderOptions many_threads = base;
  many_threads.threads = 8;
  many_threads.tile_size = 20;
  many_threads.samples_per_unit = 1;
  for (const RenderOptions& o : {two_threads, small_batches, other_tiles, many_threads}) {
    const Film film = render(scene, o).film;
    EXPECT_TRUE(test::bitwise_identical(reference, film))
        << "threads " << o.threads << " capacity " << o.queue_capacity << " tile " << o.tile_size;
  }
  // A different seed must change the image (guards against a test that compares constants).
  RenderOptions other_seed = base;
  other_seed.seed = 4;
  EXPECT_FALSE(test::bitwise_identical(reference, render(scene, other_seed).film));
}

// A render split into shards (disjoint tile sets, as the processes of a distributed render take
// them) gives each pixel to one shard, which computes it exactly as a single process would:
// the shards' films add up to the whole film bit for bit.
TEST_P(Determinism, ShardsAddUpToTheWholeImage) {
  Scene scene = load_builtin_scene("bunny-cone-r0.04").scene;
  scene.camera.width = 40;
  scene.camera.height = 24;
  RenderOptions o;
  o.spp = 3;
  o.seed = 2;
  o.integrator = GetParam();
  o.threads = 2;
  o.tile_size = 8;  // 15 tiles
  const Film whole = render(scene, o).film;
  for (const int shards : {2, 3, 16}) {  // 16: one shard gets no tile
    Film sum = whole;
    std::fill(sum.mean.begin(), sum.mean.end(), Rgb(0.0f));
    std::fill(sum.variance_of_mean.begin(), sum.variance_of_mean.end(), Rgb(0.0f));
    uint64_t paths = 0;
    for (int shard = 0; shard < shards; ++shard) {
      RenderOptions part = o;
      part.shard = shard;
      part.shard_count = shards;
      const RenderResult r = render(scene, part);
      EXPECT_TRUE(r.complete);
      paths += r.stats.paths;
      for (size_t p = 0; p < sum.mean.size(); ++p) {
        sum.mean[p] += r.film.mean[p];
        sum.variance_of_mean[p] += r.film.variance_of_mean[p];
      }
    }
    EXPECT_EQ(paths, 40u * 24u * 3u) << shards << " shards";
    EXPECT_TRUE(test::bitwise_identical(whole, sum)) << shards << " shards";
  }
  RenderOptions bad = o;
  bad.shard = 2;
  bad.shard_count = 2;
  EXPECT_THROW(render(scene, bad), std::invalid_argument);
}

// Processes that claim tiles while they render (RenderHooks::tile_source) take the tiles
// tile by tile rather than round by round, and each gets whatever ranges the shared counter
// gives it: whoever renders a tile computes it exactly as a single process would, so the
// processes' films add up to the whole film bit for bit, whichever schedule they run.
TEST_P(Determinism, ClaimedTilesAddUpToTheWholeImage) {
  Scene scene = load_builtin_scene("bunny-cone-r0.04").scene;
  scene.camera.width = 40;
  scene.camera.height = 24;
  RenderOptions o;
  o.spp = 5;
  o.seed = 2;
  o.integrator = GetParam();
  o.threads = 2;
  o.tile_size = 8;         // 15 tiles
  o.samples_per_unit = 2;  // 3 chunks a tile, the last one short
  const Film whole = render(scene, o).film;
  // The counter's claims in the order it handed them out, alternately to the two processes.
  const std::vector<TileRange> claims = {{0, 2}, {2, 3}, {3, 7}, {7, 8}, {8, 20}};
  for (const char* schedule : {"local", "global"}) {
    Film sum = whole;
    std::fill(sum.mean.begin(), sum.mean.end(), Rgb(0.0f));
    std::fill(sum.variance_of_mean.begin(), sum.variance_of_mean.end(), Rgb(0.0f));
    uint64_t paths = 0, tiles = 0;
    for (size_t process = 0; process < 2; ++process) {
      size_t next = process;
      RenderHooks hooks;
      hooks.tile_source = [&] {
        const TileRange claim = next < claims.size() ? claims[next] : TileRange{99, 100};
        next += 2;
        return claim;
      };
      RenderOptions part = o;
      part.schedule = schedule;
      const RenderResult r = render(scene, part, hooks);
      EXPECT_TRUE(r.complete) << schedule;
      paths += r.stats.paths;
      tiles += r.stats.tiles_rendered;
      for (size_t p = 0; p < sum.mean.size(); ++p) {
        sum.mean[p] += r.film.mean[p];
        sum.variance_of_mean[p] += r.film.variance_of_mean[p];
      }
    }
    EXPECT_EQ(paths, 40u * 24u * 5u) << schedule;
    EXPECT_EQ(tiles, 15u) << schedule;
    EXPECT_TRUE(test::bitwise_identical(whole, sum)) << schedule;
  }
  RenderHooks all;
  all.tile_source = [] { return TileRange{0, 100}; };
  RenderOptions timed = o;
  timed.time_seconds = 10;
  EXPECT_THROW(render(scene, timed, all), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Integrators, Determinism, ::testing::Values("pt", "snee", "sla"));

}  // namespace
}  // namespace snee
