// Per-pixel sums of samples and of squared samples, filled as work units finish, in whatever
// order they finish. Each tile's units are added in sample order: a unit that finishes before
// an earlier unit of its tile stays parked in its buffer until that one is added. Every pixel
// therefore adds its samples in index order, and the sums are bitwise the same for any thread
// count or schedule. With a noise target, a tile whose pixels have met it after a chunk is
// converged: its later chunks are dropped, so what it holds depends on its own samples only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "core/math.h"
#include "scene/film.h"
#include "scheduler/film_state.h"
#include "scheduler/unit_grid.h"

namespace snee {

class FilmAccumulator {
 public:
  // `buffers` sample buffers are kept, one per position of the unit window (unit_window.h):
  // unit k writes to buffer k % buffers, so at most `buffers` units may be unfinished at once.
  // `noise_target` > 0 stops each tile once it is met (noise_target.h); 0 never does.
  FilmAccumulator(const UnitGrid& grid, int width, int height, size_t buffers,
                  double noise_target = 0);

  // Where unit k writes its samples: (sample - sample_begin) * pixel_count + local_pixel.
  Rgb* buffer(size_t unit);
  // Keeps the denoiser AOVs too (kernels/stages/first_hit_aovs.h): their sums follow the
  // radiance's, sample order included, and resolve() fills Film::albedo, normal and depth. Call it
  // before any unit is added.
  void keep_aovs();
  // Where unit k writes its samples' AOVs, kAovFloats per sample in the order of buffer();
  // null unless keep_aovs() was called.
  float* aov_buffer(size_t unit);
  // Unit k has finished writing its buffer; adds it (and any parked successors of its tile) to
  // the sums, or parks it. Thread-safe; call it before the window learns the unit finished.
  void add(size_t unit);
  // Whether unit k's tile still takes unit k: it has not met the noise target and does not hold
  // the unit's chunk already (restored from a checkpoint). Thread-safe.
  bool wants(size_t unit) const;
  // Whether every tile holds its first `chunks` chunks or has met the noise target; with
  // `counts`, only the tiles it says true for (a process's own, RenderHooks::tile_source).
  bool tiles_done(uint32_t chunks, const std::function<bool(size_t tile)>& counts = {}) const;
  // Mean and variance of the mean per pixel over the samples added so far (a tile's chunks up
  // to its first missing one), with `meta` and its spp and min_spp filled in. Once every unit
  // is in, that is the image; before, a snapshot in which every pixel is an unbiased estimate
  // with its own sample count (Film::pixel_spp). Thread-safe: locks one tile at a time.
  Film resolve(const FilmMetadata& meta = {}) const;
  // The exact state of the sums and tiles (film_state.h), its `seconds` left 0. Each tile is
  // copied under its lock, so every tile is whole; units in flight or parked are not in it
  // and run again after a resume. Thread-safe.
  FilmState state() const;
  // Before any unit is added: takes over `state`'s tiles and sums, so that the render goes on
  // from them. Throws std::invalid_argument when it does not fit this grid (tile count, sum
  // count, or a tile holding more chunks than the grid has).
  void restore(const FilmState& state);

 private:
  struct Tile {
    std::mutex mutex;
    uint32_t next_chunk = 0;     // chunks before it are in the sums
    std::vector<size_t> parked;  // finished units waiting for an earlier chunk
    bool converged = false;      // met the noise target: takes no more chunks
  };
  void add_to_sums(size_t unit);
  void add_aovs_to_sums(size_t unit);
  void resolve_aovs(size_t pixel, uint32_t spp, Film& film) const;
  uint32_t tile_spp(const Tile& tile) const;
  // Mean and variance of the mean of pixel p over its first n samples (n >= 1).
  void estimate(size_t p, uint32_t n, double mean[3], double variance_of_mean[3]) const;
  bool meets_noise_target(size_t tile) const;

  const UnitGrid grid_;
  const int width_, height_;
  const size_t buffer_count_, buffer_size_;
  const double noise_target_;
  std::vector<Rgb> buffers_;
  std::unique_ptr<Tile[]> tiles_;
  std::vector<double> sum_, sum_sq_;  // 3 per pixel
  std::vector<float> aov_buffers_;    // empty without keep_aovs()
  std::vector<double> aov_sum_;       // kAovFloats per pixel
};

}  // namespace snee
