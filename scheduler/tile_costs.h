// What each tile cost the threads of this process: the seconds of the stages of its units,
// summed (RenderStats::tile_seconds), the measured cost map from which the load balance of a
// render split across processes is simulated (docs/performance.md).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace snee {

class TileCosts {
 public:
  explicit TileCosts(size_t tiles)
      : tiles_(tiles),
        seconds_(new std::atomic<double>[tiles]),
        units_(new std::atomic<uint32_t>[tiles]) {
    for (size_t t = 0; t < tiles; ++t) {
      seconds_[t] = 0;
      units_[t] = 0;
    }
  }
  // A unit of tile t (raster index) has run for `seconds`. Thread-safe.
  void add(size_t t, double seconds) {
    seconds_[t].fetch_add(seconds, std::memory_order_relaxed);
    units_[t].fetch_add(1, std::memory_order_relaxed);
  }
  std::vector<double> seconds() const {
    std::vector<double> all(tiles_);
    for (size_t t = 0; t < tiles_; ++t) all[t] = seconds_[t].load();
    return all;
  }
  // Tiles at least one unit of which ran here.
  uint64_t tiles_run() const {
    uint64_t run = 0;
    for (size_t t = 0; t < tiles_; ++t) run += units_[t].load() > 0;
    return run;
  }

 private:
  const size_t tiles_;
  std::unique_ptr<std::atomic<double>[]> seconds_;
  std::unique_ptr<std::atomic<uint32_t>[]> units_;
};

}  // namespace snee
