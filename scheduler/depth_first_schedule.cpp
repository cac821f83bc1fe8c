#include <tbb/parallel_for.h>

#include "scheduler/threading.h"
#include "scheduler/unit_schedules.h"

namespace snee {

void run_units_depth_first(const KernelContext& ctx, const UnitSource& source, int threads,
                           ThreadWorkspaces& workspaces) {
  // One long-running loop per thread, each taking units in order: a unit queue, not a range
  // split, so the units in flight stay inside the window whatever the thread count.
  tbb::parallel_for(
      0, threads,
      [&](int) {
        set_flush_to_zero();
        UnitWorkspace& ws = workspaces.local();
        try {
          while (const std::optional<size_t> k = source.take(/*wait=*/true)) {
            const WorkUnit unit = source.grid.unit(*k);
            // A stop drops the unit in flight rather than waiting for it: with many threads
            // per core, or costly units, finishing them could take minutes.
            if (!run_work_unit(
                    ctx, unit, ws, source.film.buffer(*k),
                    [&] { return source.progress.stop_requested(); }, source.film.aov_buffer(*k))) {
              source.window.abort();
              break;
            }
            source.unit_done(*k, ws);
          }
        } catch (...) {
          // The failed unit never finishes; without this the others would wait for it.
          source.window.abort();
          throw;
        }
      },
      tbb::simple_partitioner());
}

}  // namespace snee
