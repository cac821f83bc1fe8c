// A work unit is a tile of pixels times a range of sample indices. It is run to completion by
// one thread through the stage loop of the local wavefront, with its path state and queues in
// a per-thread workspace, so nothing in the loop is shared or atomic.
#pragma once

#include <array>
#include <chrono>
#include <vector>

#include "kernels/kernel_context.h"
#include "kernels/path_state.h"
#include "kernels/stages.h"
#include "scheduler/render.h"

namespace snee {

struct WorkUnit {
  int x0, y0, x1, y1;  // pixel rectangle [x0, x1) x [y0, y1)
  uint32_t sample_begin, sample_end;
  int pixel_count() const { return (x1 - x0) * (y1 - y0); }
  size_t sample_count() const {
    return static_cast<size_t>(pixel_count()) * (sample_end - sample_begin);
  }
};

// Per-thread state reused by every unit the thread runs.
struct UnitWorkspace {
  explicit UnitWorkspace(size_t slots);
  PathState state;
  StageQueues queues;
  std::vector<uint32_t> free_slots;
  std::vector<uint32_t> new_slots, new_pixels, new_samples;
  KernelCounters counters;
  std::array<double, static_cast<int>(Stage::kCount)> stage_seconds{};
};

// Runs the unit; writes each finished sample's radiance to
// out[(sample - sample_begin) * pixel_count + local_pixel].
void run_work_unit(const KernelContext& ctx, const WorkUnit& unit, UnitWorkspace& ws, Rgb* out);

}  // namespace snee
