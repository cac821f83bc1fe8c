#include <tbb/parallel_for.h>

#include "scheduler/pass_schedules.h"
#include "scheduler/threading.h"

namespace snee {

void run_pass_breadth_first(const KernelContext& ctx, const Pass& pass, Rgb* samples,
                            const std::vector<std::unique_ptr<UnitWorkspace>>& lanes,
                            UnitProgress& progress) {
  size_t next_unit = 0;
  std::vector<UnitWorkspace*> busy;
  for (const auto& lane : lanes) {
    if (next_unit == pass.units.size()) break;
    start_work_unit(pass.units[next_unit], samples + pass.offsets[next_unit], *lane);
    ++next_unit;
    busy.push_back(lane.get());
  }
  while (!busy.empty()) {
    for (const Stage stage : kStageLoop) {
      tbb::parallel_for(size_t{0}, busy.size(), [&](size_t i) {
        set_flush_to_zero();
        run_stage(ctx, stage, *busy[i]);
      });
    }
    size_t kept = 0;
    for (UnitWorkspace* ws : busy) {
      if (work_unit_finished(*ws)) {
        progress.unit_finished(*ws);
        if (next_unit == pass.units.size()) continue;
        start_work_unit(pass.units[next_unit], samples + pass.offsets[next_unit], *ws);
        ++next_unit;
      }
      busy[kept++] = ws;
    }
    busy.resize(kept);
  }
}

}  // namespace snee
