// A work unit is a tile of pixels times a range of sample indices. Its paths live in a
// workspace (path state and queues of a fixed number of slots) and advance by turns of the
// stage loop; how turns of different units interleave is the schedule's business, never the
// image's: every stage works slot by slot, so a path's arithmetic is the same in any company.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "kernels/stages/stage_table.h"
#include "kernels/stages/stages.h"
#include "kernels/wavefront/kernel_context.h"
#include "kernels/wavefront/path_state.h"
#include "scheduler/render.h"

namespace snee {

// Index of pixel (x, y) in a row-major image `width` pixels wide, formed in 64 bits: y * width
// overflows int from 2^31 pixels on (a 46341^2 image). Scenes are at most kMaxImageEdge (32768)
// pixels per edge (scene/scene.h), so a film index, below 2^30, fits the 32 bits path state
// keeps per pixel.
inline uint64_t row_major_index(int x, int y, int width) {
  return static_cast<uint64_t>(y) * static_cast<uint64_t>(width) + static_cast<uint64_t>(x);
}

struct WorkUnit {
  int x0, y0, x1, y1;  // pixel rectangle [x0, x1) x [y0, y1)
  uint32_t sample_begin, sample_end;
  int64_t pixel_count() const { return int64_t{x1 - x0} * (y1 - y0); }
  size_t sample_count() const {
    return static_cast<size_t>(pixel_count()) * (sample_end - sample_begin);
  }
};

// Path state, queues and statistics of `slots` path slots, reused by every unit run in it;
// SNEE's memory of each path only where the snee integrator runs (PathState).
struct UnitWorkspace {
  UnitWorkspace(size_t slots, bool snee_memory);
  size_t slots;  // PathState pads its arrays; only these slots hold paths
  PathState state;
  StageQueues queues;
  std::vector<uint32_t> free_slots;
  std::vector<uint32_t> new_slots, new_pixels, new_samples;

  // The unit in progress.
  const WorkUnit* unit = nullptr;
  Rgb* out = nullptr;
  float* aov_out = nullptr;  // kAovFloats per sample, laid out as `out`; null: no AOVs
  size_t next_sample = 0;    // samples of the unit started so far
  size_t active = 0;         // slots holding a path
  uint64_t rays_at_start = 0;
  uint64_t nonfinite_at_start = 0;
  double stage_seconds_at_start = 0;  // stage_seconds summed, when the unit started

  KernelCounters counters;
  std::array<double, kStageCount> stage_seconds{};
  std::array<uint64_t, kStageCount> stage_calls{};
  uint64_t turns = 0;
  uint64_t active_slot_turns = 0;  // sum over turns of `active` after the refill
  // Two clock readings cost a sizeable part of a one-slot stage, so small workspaces time one
  // turn in `timing_period` and scale it up; large ones time every turn.
  uint32_t timing_period;
  bool timing_turn = false;
};

// Makes `unit` the workspace's current unit; its samples go to
// out[(sample - sample_begin) * pixel_count + local_pixel], and their AOVs (when the context
// records them) to the kAovFloats floats from aov_out + that index * kAovFloats.
void start_work_unit(const WorkUnit& unit, Rgb* out, UnitWorkspace& ws, float* aov_out = nullptr);
bool work_unit_finished(const UnitWorkspace& ws);
// The workspace's stage seconds, summed over stages.
double stage_seconds_total(const UnitWorkspace& ws);
// Runs one stage of the current unit's loop (a turn is kStageLoop in order); a stage whose
// input is empty is skipped.
void run_stage(const KernelContext& ctx, Stage stage, UnitWorkspace& ws);
// Runs a unit turn after turn until it is complete (returns true) or `give_up`, asked before
// every turn, says true (returns false; the unit's samples so far are not usable).
bool run_work_unit(const KernelContext& ctx, const WorkUnit& unit, UnitWorkspace& ws, Rgb* out,
                   const std::function<bool()>& give_up, float* aov_out = nullptr);

uint64_t rays_traced(const KernelCounters& counters);

}  // namespace snee
