// Running the work units of one pass under a schedule (schedule.h). Each is called inside the
// render's task arena and writes unit i's samples to samples + offsets[i].
#pragma once

#include <memory>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "scheduler/unit_progress.h"
#include "scheduler/work_unit.h"

namespace snee {

struct Pass {
  std::vector<WorkUnit> units;
  std::vector<size_t> offsets;
};

using ThreadWorkspaces = tbb::enumerable_thread_specific<UnitWorkspace>;

// Local wavefront and megakernel: a worker takes a unit and runs its whole stage loop in the
// worker's own workspace (the megakernel's has one slot).
void run_pass_depth_first(const KernelContext& ctx, const Pass& pass, Rgb* samples,
                          ThreadWorkspaces& workspaces, UnitProgress& progress);

// Global: every lane holds a unit; each stage runs over all lanes (in parallel) before the next
// stage starts, and a lane whose unit is done takes the pass's next one. Memory is bounded by
// the number of lanes, not by the pass.
void run_pass_breadth_first(const KernelContext& ctx, const Pass& pass, Rgb* samples,
                            const std::vector<std::unique_ptr<UnitWorkspace>>& lanes,
                            UnitProgress& progress);

}  // namespace snee
