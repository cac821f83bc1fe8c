// The exact state of a render's film (FilmAccumulator) between two of its units: what a
// checkpoint keeps so that a stopped render can go on as if it had never stopped. A tile's
// chunks are added in sample order, so a tile is fully described by how many chunks its sums
// hold, whether it met the noise target, and the sums themselves, in the doubles they are kept
// in: continuing from them adds the later chunks to the very same numbers.
#pragma once

#include <cstdint>
#include <vector>

namespace snee {

struct TileState {
  uint32_t chunks = 0;     // chunks 0 .. chunks-1 are in the sums
  bool converged = false;  // met the noise target: takes no more chunks
};

struct FilmState {
  // The unit grid's tiles in its order (unit_grid.h): a shard's own tiles only.
  std::vector<TileState> tiles;
  // Per tile in the same order, per pixel of the tile in raster order: the sums of the
  // samples' R, G, B, then of their squares (kSumsPerPixel doubles a pixel).
  std::vector<double> sums;
  // Seconds the render had run (from the start of render()) when the state was taken, those of
  // earlier runs it resumed included: a time budget goes on counting from there.
  double seconds = 0;
};

inline constexpr int kSumsPerPixel = 6;

}  // namespace snee
