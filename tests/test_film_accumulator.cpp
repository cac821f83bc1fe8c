// The film adds each tile's units in sample order whatever order they finish in, so its sums
// equal a plain sample-index-order sum bit for bit, also when sample buffers are reused.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "scheduler/film_accumulator.h"
#include "scheduler/unit_window.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

// Sample values whose double sums depend on the order they are added in: sample 0 is huge,
// sample 1 is lost against it, sample 2 cancels sample 0, and later samples are small, so the
// index-order sum keeps the small samples and other orders lose them.
Rgb sample_value(int pixel, uint32_t sample) {
  const float huge = 1e17f * (1.0f + 0.01f * static_cast<float>(pixel % 5));
  if (sample == 0) return Rgb(huge);
  if (sample == 2) return Rgb(-huge);
  std::mt19937 rng(static_cast<uint32_t>(pixel) * 7919u + sample);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  return Rgb(u(rng), u(rng), u(rng));
}

// Mean and variance exactly as the film defines them, adding samples in index order.
Film reference_film(int width, int height, uint32_t spp) {
  FilmAccumulator one_unit(UnitGrid(width, height, std::max(width, height), spp, spp), width,
                           height, 1);
  Rgb* samples = one_unit.buffer(0);
  for (uint32_t s = 0; s < spp; ++s) {
    for (int p = 0; p < width * height; ++p) samples[s * width * height + p] = sample_value(p, s);
  }
  one_unit.add(0);
  return one_unit.resolve();
}

void fill(const UnitGrid& grid, size_t k, int width, Rgb* buffer) {
  const WorkUnit u = grid.unit(k);
  const int tile_w = u.x1 - u.x0;
  for (uint32_t s = u.sample_begin; s < u.sample_end; ++s) {
    for (int y = u.y0; y < u.y1; ++y) {
      for (int x = u.x0; x < u.x1; ++x) {
        buffer[(s - u.sample_begin) * u.pixel_count() + (y - u.y0) * tile_w + (x - u.x0)] =
            sample_value(y * width + x, s);
      }
    }
  }
}

TEST(FilmAccumulator, UnitsAddedInAnyOrderGiveTheSampleOrderSums) {
  const int width = 7, height = 5;
  const uint32_t spp = 9;
  const Film reference = reference_film(width, height, spp);
  const UnitGrid grid(width, height, 3, spp, 2);  // 6 tiles (edge tiles clipped) x 5 chunks
  ASSERT_EQ(grid.size(), 30u);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    FilmAccumulator film(grid, width, height, grid.size());
    std::vector<size_t> order(grid.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    if (trial > 0) std::shuffle(order.begin(), order.end(), rng);  // trial 0: in order
    for (const size_t k : order) {
      fill(grid, k, width, film.buffer(k));
      film.add(k);
    }
    EXPECT_TRUE(test::bitwise_identical(reference, film.resolve())) << "trial " << trial;
  }
  // The test would notice an accumulator that ignored the order: summing these samples in
  // reverse index order gives other bits.
  std::vector<double> sum(width * height * 3, 0.0);
  for (uint32_t s = spp; s-- > 0;) {
    for (int p = 0; p < width * height; ++p) {
      for (int c = 0; c < 3; ++c) sum[3 * p + c] += sample_value(p, s)[c];
    }
  }
  bool differs = false;
  for (int p = 0; p < width * height; ++p) {
    for (int c = 0; c < 3; ++c) {
      differs |= static_cast<float>(sum[3 * p + c] / spp) != reference.mean[p][c];
    }
  }
  EXPECT_TRUE(differs) << "these samples must make the summation order visible";
}

// The render's protocol with fewer buffers than units: take from the window, fill the unit's
// buffer, add, finish, in random finish orders. A buffer reused before its unit was added
// would change the sums.
TEST(FilmAccumulator, ReusedBuffersUnderTheWindowKeepTheSums) {
  const int width = 10, height = 6;
  const uint32_t spp = 12;
  const Film reference = reference_film(width, height, spp);
  const UnitGrid grid(width, height, 4, spp, 1);  // 6 tiles x 12 chunks
  std::mt19937 rng(11);
  for (const size_t lead : {1, 3, 6, 7, 20}) {
    UnitWindow window(grid.size(), lead);
    FilmAccumulator film(grid, width, height, lead);
    std::set<size_t> running;
    size_t taken = 0;
    while (taken < grid.size() || !running.empty()) {
      if (std::uniform_int_distribution<int>(0, 1)(rng) == 0) {
        if (const auto k = window.take(false)) {
          fill(grid, *k, width, film.buffer(*k));
          running.insert(*k);
          ++taken;
        }
      } else if (!running.empty()) {
        auto it = running.begin();
        std::advance(it, std::uniform_int_distribution<size_t>(0, running.size() - 1)(rng));
        film.add(*it);
        window.finish(*it);
        running.erase(it);
      }
    }
    EXPECT_TRUE(test::bitwise_identical(reference, film.resolve())) << "lead " << lead;
  }
}

// Before every unit is in, each pixel is resolved over its own tile's added samples: the
// pixels of a tile with k chunks in are bitwise those of a complete k-sample film, and a tile
// with none is black; min_spp is the fewest.
TEST(FilmAccumulator, APartialFilmResolvesEachTileOverItsOwnSamples) {
  const int width = 8, height = 4;
  const uint32_t spp = 6;
  const UnitGrid grid(width, height, 4, spp, 2);  // 2 tiles x 3 chunks
  FilmAccumulator film(grid, width, height, grid.size());
  // Tile 0 gets chunks 0 and 1 (4 samples); tile 1 only chunk 1, which stays parked.
  for (const size_t k : {size_t{0}, size_t{2}, size_t{3}}) {
    fill(grid, k, width, film.buffer(k));
    film.add(k);
  }
  const Film partial = film.resolve();
  EXPECT_EQ(partial.meta.spp, 6);
  EXPECT_EQ(partial.meta.min_spp, 0);
  const Film four = reference_film(width, height, 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t p = static_cast<size_t>(y) * width + x;
      const Rgb expected_mean = x < 4 ? four.mean[p] : Rgb(0.0f);
      const Rgb expected_variance = x < 4 ? four.variance_of_mean[p] : Rgb(0.0f);
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(partial.mean[p][c], expected_mean[c]) << x << "," << y;
        EXPECT_EQ(partial.variance_of_mean[p][c], expected_variance[c]) << x << "," << y;
      }
    }
  }
  // Tile 1's chunk 0 arrives: its parked chunk 1 follows, and tile 1 now has 4 samples too.
  fill(grid, 1, width, film.buffer(1));
  film.add(1);
  const Film both = film.resolve();
  EXPECT_EQ(both.meta.min_spp, 4);
  EXPECT_TRUE(test::bitwise_identical(four, both));
}

}  // namespace
}  // namespace snee
