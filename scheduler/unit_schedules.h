// Running a render's work units under a schedule (schedule.h). Each is called inside the
// render's task arena, takes units from the window in order and hands each finished unit's
// samples to the film, then to the window.
#pragma once

#include <memory>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "scheduler/film_accumulator.h"
#include "scheduler/tile_claims.h"
#include "scheduler/tile_costs.h"
#include "scheduler/time_budget.h"
#include "scheduler/unit_grid.h"
#include "scheduler/unit_progress.h"
#include "scheduler/unit_window.h"
#include "scheduler/work_unit.h"

namespace snee {

// What every schedule works on: the units, the order they are handed out in, and the film.
struct UnitSource {
  const UnitGrid& grid;
  UnitWindow& window;
  FilmAccumulator& film;
  UnitProgress& progress;
  TimeBudget& time_budget;
  TileClaims& claims;
  TileCosts& costs;

  // The next unit to run, from the window (UnitWindow::take). Units of other processes' tiles
  // (TileClaims) and of tiles that have met the noise target are finished unrun; once the time
  // budget is spent, the window closes at the first unit of the next round (nullopt) and the
  // units in flight finish.
  std::optional<size_t> take(bool wait) const;
  // Unit k has run in `ws`. Its samples go into the film before the window learns it finished:
  // only then may a later unit reuse its sample buffer. Stops the window if asked to.
  void unit_done(size_t k, const UnitWorkspace& ws) const {
    costs.add(grid.raster_index(grid.tile_of(k)),
              stage_seconds_total(ws) - ws.stage_seconds_at_start);
    film.add(k);
    window.finish(k);
    if (!progress.unit_finished(ws)) window.abort();
  }
};

using ThreadWorkspaces = tbb::enumerable_thread_specific<UnitWorkspace>;

// Local wavefront and megakernel: each of `threads` workers takes a unit, runs its whole stage
// loop in the worker's own workspace (the megakernel's has one slot) and takes the next.
void run_units_depth_first(const KernelContext& ctx, const UnitSource& source, int threads,
                           ThreadWorkspaces& workspaces);

// Global: every lane holds a unit; each stage runs over all lanes (in parallel) before the next
// stage starts, and a lane whose unit is done takes the next one.
void run_units_breadth_first(const KernelContext& ctx, const UnitSource& source,
                             const std::vector<std::unique_ptr<UnitWorkspace>>& lanes);

}  // namespace snee
