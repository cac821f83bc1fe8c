#include "scheduler/tile_claims.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>

namespace snee {

TileClaims::TileClaims(size_t tiles, std::function<TileRange()> source)
    : tiles_(tiles), source_(std::move(source)) {}

bool TileClaims::owns(size_t t) {
  if (!source_) return true;
  std::lock_guard<std::mutex> lock(mutex_);
  while (!exhausted_ && t >= decided_) {
    TileRange claim = source_();
    if (claim.begin >= claim.end || claim.begin >= tiles_) {
      exhausted_ = true;
      break;
    }
    // A tile handed out twice would be rendered twice and summed twice in the join.
    if (claim.begin < decided_)
      throw std::logic_error("the tile source handed out tile " + std::to_string(claim.begin) +
                             " after tile " + std::to_string(decided_ - 1));
    claim.end = std::min(claim.end, tiles_);
    claims_.push_back(claim);
    decided_ = claim.end;
  }
  return in_claims(t);
}

bool TileClaims::claimed(size_t t) const {
  if (!source_) return true;
  std::lock_guard<std::mutex> lock(mutex_);
  return in_claims(t);
}

bool TileClaims::in_claims(size_t t) const {
  // The last claim that begins at or before t.
  const auto after =
      std::upper_bound(claims_.begin(), claims_.end(), t,
                       [](size_t tile, const TileRange& c) { return tile < c.begin; });
  return after != claims_.begin() && t < std::prev(after)->end;
}

}  // namespace snee
