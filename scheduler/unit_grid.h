// The render's work units in the order they are handed out. Round-major (the default): sample
// chunk by sample chunk, and within a chunk tile by tile in raster order, so unit k is tile
// k % tiles of chunk k / tiles. Tile-major: tile by tile, each through all its chunks, so unit
// k is chunk k % chunks of tile k / chunks. Either is a pure function of image size, tile size,
// spp and chunk size, never of the thread count. A shard of a render split across processes
// keeps only the tiles whose raster index is `shard` modulo `shard_count`.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scheduler/work_unit.h"

namespace snee {

enum class UnitOrder {
  // Every round (a chunk over every tile) is whole before the next starts: what a time budget
  // needs (time_budget.h).
  kRoundMajor,
  // A tile's work comes together, so a process that claims tiles while it renders
  // (RenderHooks::tile_source) claims until the very end.
  kTileMajor,
};

class UnitGrid {
 public:
  UnitGrid(int width, int height, int tile_size, uint32_t spp, uint32_t samples_per_unit,
           int shard = 0, int shard_count = 1, UnitOrder order = UnitOrder::kRoundMajor)
      : spp_(spp),
        samples_per_unit_(samples_per_unit),
        shard_(static_cast<size_t>(shard)),
        shard_count_(static_cast<size_t>(shard_count)),
        order_(order) {
    int index = 0;
    for (int y = 0; y < height; y += tile_size) {
      for (int x = 0; x < width; x += tile_size, ++index) {
        ++raster_tiles_;
        if (index % shard_count != shard) continue;
        tiles_.push_back(
            {x, y, std::min(x + tile_size, width), std::min(y + tile_size, height), 0, 0});
      }
    }
    chunks_ = (spp + samples_per_unit - 1) / samples_per_unit;
  }

  size_t size() const { return tiles_.size() * chunks_; }
  size_t tile_count() const { return tiles_.size(); }
  size_t tile_of(size_t unit) const {
    return order_ == UnitOrder::kRoundMajor ? unit % tiles_.size() : unit / chunks_;
  }
  uint32_t chunk_of(size_t unit) const {
    return static_cast<uint32_t>(order_ == UnitOrder::kRoundMajor ? unit / tiles_.size()
                                                                  : unit % chunks_);
  }
  // Tile t's pixels (its sample range empty).
  const WorkUnit& tile(size_t t) const { return tiles_[t]; }
  // Tile t's index among all the image's tiles in raster order, whatever the shard.
  size_t raster_index(size_t t) const { return t * shard_count_ + shard_; }
  size_t raster_tile_count() const { return raster_tiles_; }
  uint32_t spp() const { return spp_; }
  uint32_t samples_per_unit() const { return samples_per_unit_; }
  uint32_t chunk_count() const { return static_cast<uint32_t>(chunks_); }
  // Pixel samples of all units together.
  int64_t sample_count() const {
    int64_t pixels = 0;
    for (const WorkUnit& t : tiles_) pixels += t.pixel_count();
    return pixels * spp_;
  }
  // The most samples (pixels times sample indices) any unit holds.
  size_t max_unit_samples() const {
    size_t most = 0;
    for (const WorkUnit& t : tiles_) most = std::max(most, static_cast<size_t>(t.pixel_count()));
    return most * std::min(spp_, samples_per_unit_);
  }

  WorkUnit unit(size_t k) const {
    WorkUnit u = tiles_[tile_of(k)];
    u.sample_begin = chunk_of(k) * samples_per_unit_;
    u.sample_end = std::min(spp_, u.sample_begin + samples_per_unit_);
    return u;
  }

 private:
  std::vector<WorkUnit> tiles_;
  uint32_t spp_, samples_per_unit_;
  size_t chunks_;
  size_t shard_, shard_count_;
  size_t raster_tiles_ = 0;
  UnitOrder order_;
};

}  // namespace snee
