#include "scheduler/unit_schedules.h"

namespace snee {

std::optional<size_t> UnitSource::take(bool wait) const {
  for (;;) {
    const std::optional<size_t> k = window.take(wait);
    if (!k) return k;
    if (grid.tile_of(*k) == 0 && time_budget.stops(grid.chunk_of(*k))) {
      // Unit k never runs; abort hands out nothing more and lets the units before it finish.
      window.abort();
      return std::nullopt;
    }
    // Asked tile by tile in the window's order, so claims follow the render (tile_claims.h).
    if (claims.owns(grid.tile_of(*k)) && film.wants(*k)) return k;
    window.finish(*k);
    progress.unit_skipped(static_cast<int64_t>(grid.unit(*k).sample_count()));
  }
}

}  // namespace snee
