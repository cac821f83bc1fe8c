#include <tbb/parallel_for.h>

#include "scheduler/threading.h"
#include "scheduler/unit_schedules.h"

namespace snee {

void run_units_breadth_first(const KernelContext& ctx, const UnitSource& source,
                             const std::vector<std::unique_ptr<UnitWorkspace>>& lanes) {
  std::vector<WorkUnit> lane_units(lanes.size());
  std::vector<size_t> lane_unit_index(lanes.size());
  std::vector<size_t> busy, idle;
  for (size_t i = lanes.size(); i-- > 0;) idle.push_back(i);
  // Never waits: the oldest unfinished unit is always in a lane, so a full window only leaves
  // lanes idle until that unit is done.
  const auto refill = [&] {
    while (!idle.empty()) {
      const std::optional<size_t> k = source.take(/*wait=*/false);
      if (!k) return;
      const size_t lane = idle.back();
      idle.pop_back();
      lane_units[lane] = source.grid.unit(*k);
      lane_unit_index[lane] = *k;
      start_work_unit(lane_units[lane], source.film.buffer(*k), *lanes[lane],
                      source.film.aov_buffer(*k));
      busy.push_back(lane);
    }
  };
  refill();
  // A stop drops the units in the lanes at the next turn (render.h, RenderHooks).
  while (!busy.empty() && !source.progress.stop_requested()) {
    for (const Stage stage : kStageLoop) {
      tbb::parallel_for(size_t{0}, busy.size(), [&](size_t i) {
        set_flush_to_zero();
        run_stage(ctx, stage, *lanes[busy[i]]);
      });
    }
    size_t kept = 0;
    for (const size_t lane : busy) {
      if (!work_unit_finished(*lanes[lane])) {
        busy[kept++] = lane;
        continue;
      }
      source.unit_done(lane_unit_index[lane], *lanes[lane]);
      idle.push_back(lane);
    }
    busy.resize(kept);
    refill();
  }
}

}  // namespace snee
