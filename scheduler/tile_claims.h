// Which tiles this process renders when processes claim tiles while they render
// (RenderHooks::tile_source): the union of the ranges the source has handed out so far. A
// source hands out every tile once over all processes and in increasing order, so once the
// claims here reach past a tile, whether it is this process's is settled for good: a tile
// between two claims was claimed by another process in the meantime.
#pragma once

#include <cstddef>
#include <functional>
#include <mutex>
#include <vector>

#include "scheduler/render.h"

namespace snee {

class TileClaims {
 public:
  // Unset `source`: every one of the `tiles` tiles is this process's, nothing is claimed.
  TileClaims(size_t tiles, std::function<TileRange()> source);

  // Whether tile t is this process's. Claims from the source while t lies past every claim so
  // far and the source has tiles left, so that asking for the tiles in increasing order claims
  // as the render reaches them. Thread-safe; the source is called under a lock.
  bool owns(size_t t);
  // Whether tile t is this process's by the claims so far, claiming nothing (at the end of a
  // render that stopped before it reached every tile). Thread-safe.
  bool claimed(size_t t) const;

 private:
  bool in_claims(size_t t) const;

  const size_t tiles_;
  const std::function<TileRange()> source_;
  mutable std::mutex mutex_;
  std::vector<TileRange> claims_;  // increasing, disjoint
  size_t decided_ = 0;             // every tile before it is settled
  bool exhausted_ = false;         // the source has no tile left
};

}  // namespace snee
