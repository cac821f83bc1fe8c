#include "scheduler/film_accumulator.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "kernels/stages/first_hit_aovs.h"
#include "scheduler/noise_target.h"

namespace snee {

FilmAccumulator::FilmAccumulator(const UnitGrid& grid, int width, int height, size_t buffers,
                                 double noise_target)
    : grid_(grid),
      width_(width),
      height_(height),
      buffer_count_(buffers),
      buffer_size_(grid.max_unit_samples()),
      noise_target_(noise_target),
      buffers_(buffers * buffer_size_),
      tiles_(new Tile[grid.tile_count()]),
      sum_(static_cast<size_t>(width) * height * 3, 0.0),
      sum_sq_(static_cast<size_t>(width) * height * 3, 0.0) {}

Rgb* FilmAccumulator::buffer(size_t unit) {
  return buffers_.data() + (unit % buffer_count_) * buffer_size_;
}

void FilmAccumulator::keep_aovs() {
  aov_buffers_.assign(buffers_.size() * kAovFloats, 0.0f);
  aov_sum_.assign(sum_.size() / 3 * kAovFloats, 0.0);
}

float* FilmAccumulator::aov_buffer(size_t unit) {
  if (aov_buffers_.empty()) return nullptr;
  return aov_buffers_.data() + (unit % buffer_count_) * buffer_size_ * kAovFloats;
}

void FilmAccumulator::add(size_t unit) {
  const size_t t = grid_.tile_of(unit);
  Tile& tile = tiles_[t];
  std::lock_guard<std::mutex> lock(tile.mutex);
  // A unit taken before its tile converged (the window ran ahead of the tile) is dropped.
  if (tile.converged) return;
  if (grid_.chunk_of(unit) != tile.next_chunk) {
    tile.parked.push_back(unit);
    return;
  }
  add_to_sums(unit);
  ++tile.next_chunk;
  // Parked units of this tile are later chunks; add them while they follow on without a gap.
  for (;;) {
    if (noise_target_ > 0 && meets_noise_target(t)) {
      tile.converged = true;
      tile.parked.clear();
      return;
    }
    const auto next = std::find_if(tile.parked.begin(), tile.parked.end(),
                                   [&](size_t u) { return grid_.chunk_of(u) == tile.next_chunk; });
    if (next == tile.parked.end()) break;
    add_to_sums(*next);
    ++tile.next_chunk;
    tile.parked.erase(next);
  }
}

bool FilmAccumulator::wants(size_t unit) const {
  Tile& tile = tiles_[grid_.tile_of(unit)];
  std::lock_guard<std::mutex> lock(tile.mutex);
  return !tile.converged && grid_.chunk_of(unit) >= tile.next_chunk;
}

bool FilmAccumulator::tiles_done(uint32_t chunks,
                                 const std::function<bool(size_t tile)>& counts) const {
  for (size_t t = 0; t < grid_.tile_count(); ++t) {
    if (counts && !counts(t)) continue;
    Tile& tile = tiles_[t];
    std::lock_guard<std::mutex> lock(tile.mutex);
    if (!tile.converged && tile.next_chunk < chunks) return false;
  }
  return true;
}

void FilmAccumulator::add_to_sums(size_t k) {
  const WorkUnit u = grid_.unit(k);
  const Rgb* samples = buffer(k);
  const int tile_w = u.x1 - u.x0;
  const size_t pixels = static_cast<size_t>(u.pixel_count());
  for (uint32_t s = 0; s < u.sample_end - u.sample_begin; ++s) {
    for (int y = u.y0; y < u.y1; ++y) {
      for (int x = u.x0; x < u.x1; ++x) {
        const Rgb v = samples[s * pixels + static_cast<size_t>((y - u.y0) * tile_w + (x - u.x0))];
        const size_t pixel = static_cast<size_t>(y) * width_ + x;
        for (int c = 0; c < 3; ++c) {
          sum_[3 * pixel + c] += v[c];
          sum_sq_[3 * pixel + c] += static_cast<double>(v[c]) * v[c];
        }
      }
    }
  }
  if (!aov_sum_.empty()) add_aovs_to_sums(k);
}

void FilmAccumulator::add_aovs_to_sums(size_t k) {
  const WorkUnit u = grid_.unit(k);
  const float* samples = aov_buffer(k);
  const int tile_w = u.x1 - u.x0;
  const size_t pixels = static_cast<size_t>(u.pixel_count());
  for (uint32_t s = 0; s < u.sample_end - u.sample_begin; ++s) {
    for (int y = u.y0; y < u.y1; ++y) {
      for (int x = u.x0; x < u.x1; ++x) {
        const float* v =
            samples +
            (s * pixels + static_cast<size_t>((y - u.y0) * tile_w + (x - u.x0))) * kAovFloats;
        double* sum = aov_sum_.data() + (static_cast<size_t>(y) * width_ + x) * kAovFloats;
        for (size_t c = 0; c < kAovFloats; ++c) sum[c] += v[c];
      }
    }
  }
}

void FilmAccumulator::resolve_aovs(size_t p, uint32_t spp, Film& film) const {
  const double* sum = aov_sum_.data() + p * kAovFloats;
  const auto mean = [&](size_t c) { return static_cast<float>(sum[c] / spp); };
  film.albedo[p] = {mean(0), mean(1), mean(2)};
  film.normal[p] = {mean(3), mean(4), mean(5)};
  film.depth[p] = mean(6);
}

uint32_t FilmAccumulator::tile_spp(const Tile& tile) const {
  return std::min(grid_.spp(), tile.next_chunk * grid_.samples_per_unit());
}

void FilmAccumulator::estimate(size_t p, uint32_t spp, double mean[3],
                               double variance_of_mean[3]) const {
  const double n = spp;
  for (int c = 0; c < 3; ++c) {
    mean[c] = sum_[3 * p + c] / n;
    const double var =
        spp > 1 ? std::max(0.0, (sum_sq_[3 * p + c] - n * mean[c] * mean[c]) / (n - 1)) : 0.0;
    variance_of_mean[c] = var / n;
  }
}

bool FilmAccumulator::meets_noise_target(size_t t) const {
  const uint32_t spp = tile_spp(tiles_[t]);
  if (spp < std::min(grid_.spp(), kMinAdaptiveSpp)) return false;
  const WorkUnit u = grid_.tile(t);
  for (int y = u.y0; y < u.y1; ++y) {
    for (int x = u.x0; x < u.x1; ++x) {
      double mean[3], variance_of_mean[3];
      estimate(static_cast<size_t>(y) * width_ + x, spp, mean, variance_of_mean);
      if (relative_standard_error(mean, variance_of_mean) > noise_target_) return false;
    }
  }
  return true;
}

Film FilmAccumulator::resolve(const FilmMetadata& meta) const {
  Film film;
  film.meta = meta;
  film.width = width_;
  film.height = height_;
  const size_t pixel_count = static_cast<size_t>(width_) * height_;
  film.mean.assign(pixel_count, Rgb(0.0f));
  film.variance_of_mean.assign(pixel_count, Rgb(0.0f));
  film.pixel_spp.assign(pixel_count, 0);
  if (!aov_sum_.empty()) {
    film.albedo.assign(pixel_count, Rgb(0.0f));
    film.normal.assign(pixel_count, Vec3{});
    film.depth.assign(pixel_count, 0.0f);
  }
  uint32_t min_spp = grid_.spp();
  for (size_t t = 0; t < grid_.tile_count(); ++t) {
    Tile& tile = tiles_[t];
    std::lock_guard<std::mutex> lock(tile.mutex);
    const uint32_t spp = tile_spp(tile);
    min_spp = std::min(min_spp, spp);
    if (spp == 0) continue;
    const WorkUnit u = grid_.tile(t);
    for (int y = u.y0; y < u.y1; ++y) {
      for (int x = u.x0; x < u.x1; ++x) {
        const size_t p = static_cast<size_t>(y) * width_ + x;
        double mean[3], variance_of_mean[3];
        estimate(p, spp, mean, variance_of_mean);
        for (int c = 0; c < 3; ++c) {
          film.mean[p][c] = static_cast<float>(mean[c]);
          film.variance_of_mean[p][c] = static_cast<float>(variance_of_mean[c]);
        }
        film.pixel_spp[p] = spp;
        if (!aov_sum_.empty()) resolve_aovs(p, spp, film);
      }
    }
  }
  film.meta.spp = static_cast<int>(grid_.spp());
  film.meta.min_spp = static_cast<int>(min_spp);
  return film;
}

FilmState FilmAccumulator::state() const {
  FilmState state;
  state.tiles.resize(grid_.tile_count());
  state.sums.reserve(kSumsPerPixel * sum_.size() / 3);
  for (size_t t = 0; t < grid_.tile_count(); ++t) {
    Tile& tile = tiles_[t];
    std::lock_guard<std::mutex> lock(tile.mutex);
    state.tiles[t] = {tile.next_chunk, tile.converged};
    const WorkUnit u = grid_.tile(t);
    for (int y = u.y0; y < u.y1; ++y) {
      for (int x = u.x0; x < u.x1; ++x) {
        const size_t p = 3 * (static_cast<size_t>(y) * width_ + x);
        state.sums.insert(state.sums.end(), sum_.begin() + p, sum_.begin() + p + 3);
        state.sums.insert(state.sums.end(), sum_sq_.begin() + p, sum_sq_.begin() + p + 3);
      }
    }
  }
  return state;
}

void FilmAccumulator::restore(const FilmState& state) {
  if (state.tiles.size() != grid_.tile_count())
    throw std::invalid_argument("the state has " + std::to_string(state.tiles.size()) +
                                " tiles, the render " + std::to_string(grid_.tile_count()));
  size_t pixels = 0;
  for (size_t t = 0; t < grid_.tile_count(); ++t)
    pixels += static_cast<size_t>(grid_.tile(t).pixel_count());
  if (state.sums.size() != kSumsPerPixel * pixels)
    throw std::invalid_argument("the state has " + std::to_string(state.sums.size()) +
                                " sums, the render's tiles need " +
                                std::to_string(kSumsPerPixel * pixels));
  const double* sums = state.sums.data();
  for (size_t t = 0; t < grid_.tile_count(); ++t) {
    if (state.tiles[t].chunks > grid_.chunk_count())
      throw std::invalid_argument("tile " + std::to_string(t) + " of the state holds " +
                                  std::to_string(state.tiles[t].chunks) +
                                  " chunks, the render has " + std::to_string(grid_.chunk_count()));
    Tile& tile = tiles_[t];
    std::lock_guard<std::mutex> lock(tile.mutex);
    tile.next_chunk = state.tiles[t].chunks;
    tile.converged = state.tiles[t].converged;
    const WorkUnit u = grid_.tile(t);
    for (int y = u.y0; y < u.y1; ++y) {
      for (int x = u.x0; x < u.x1; ++x, sums += kSumsPerPixel) {
        const size_t p = 3 * (static_cast<size_t>(y) * width_ + x);
        std::copy(sums, sums + 3, sum_.begin() + p);
        std::copy(sums + 3, sums + 6, sum_sq_.begin() + p);
      }
    }
  }
}

}  // namespace snee
