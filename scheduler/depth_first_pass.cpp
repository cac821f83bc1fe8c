#include <tbb/parallel_for.h>

#include "scheduler/pass_schedules.h"
#include "scheduler/threading.h"

namespace snee {

void run_pass_depth_first(const KernelContext& ctx, const Pass& pass, Rgb* samples,
                          ThreadWorkspaces& workspaces, UnitProgress& progress) {
  tbb::parallel_for(size_t{0}, pass.units.size(), [&](size_t i) {
    set_flush_to_zero();
    UnitWorkspace& ws = workspaces.local();
    run_work_unit(ctx, pass.units[i], ws, samples + pass.offsets[i]);
    progress.unit_finished(ws);
  });
}

}  // namespace snee
