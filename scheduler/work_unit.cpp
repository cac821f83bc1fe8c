#include "scheduler/work_unit.h"

#include <algorithm>
#include <chrono>
#include <type_traits>

#include "kernels/stages/first_hit_aovs.h"

namespace snee {

namespace {

using Clock = std::chrono::steady_clock;

// About this many path-stage visits share one clock reading: rare enough that a one-slot
// workspace spends ~1% on the clock, often enough that a thread preempted during a timed turn
// (the time is scaled by the period) does not swamp the estimate on a shared machine.
constexpr size_t kSlotsPerTimedTurn = 32;

// A measured interval also holds one clock reading; that is subtracted, or a one-slot stage of
// a few hundred nanoseconds would be overstated by a fifth.
double clock_overhead_seconds() {
  static const double overhead = [] {
    constexpr int kReads = 1000;
    const auto start = Clock::now();
    for (int i = 0; i < kReads; ++i) Clock::now();
    return std::chrono::duration<double>(Clock::now() - start).count() / (kReads + 1);
  }();
  return overhead;
}

// A sampled stage of a small workspace takes microseconds; a sample this long is a thread that
// was preempted (or a page fault), and scaled by the period it would swamp the estimate, so it
// is dropped and its time left to the unattributed rest.
constexpr double kLongestSample = 1e-3;

template <typename F>
void timed(UnitWorkspace& ws, Stage stage, F&& f) {
  const int i = static_cast<int>(stage);
  ++ws.stage_calls[i];
  if (!ws.timing_turn) {
    f();
    return;
  }
  const auto start = Clock::now();
  f();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (ws.timing_period > 1 && seconds > kLongestSample) return;
  ws.stage_seconds[i] += std::max(0.0, seconds - clock_overhead_seconds()) * ws.timing_period;
}

// Opens a turn and starts new paths in free slots (regeneration): the generate row of the stage
// table, whose input, the unit's samples not yet started while a slot is free, is checked here.
void generate(const KernelContext& ctx, UnitWorkspace& ws) {
  ws.timing_turn = ws.turns % ws.timing_period == 0;
  ++ws.turns;
  const WorkUnit& unit = *ws.unit;
  const size_t total = unit.sample_count();
  if (ws.next_sample < total && !ws.free_slots.empty()) {
    timed(ws, Stage::kGenerate, [&] {
      const int tile_w = unit.x1 - unit.x0;
      const size_t pixels = static_cast<size_t>(unit.pixel_count());
      ws.new_slots.clear();
      ws.new_pixels.clear();
      ws.new_samples.clear();
      while (ws.next_sample < total && !ws.free_slots.empty()) {
        const size_t local_pixel = ws.next_sample % pixels;
        const uint32_t sample = unit.sample_begin + static_cast<uint32_t>(ws.next_sample / pixels);
        const int x = unit.x0 + static_cast<int>(local_pixel % static_cast<size_t>(tile_w));
        const int y = unit.y0 + static_cast<int>(local_pixel / static_cast<size_t>(tile_w));
        ws.new_slots.push_back(ws.free_slots.back());
        ws.free_slots.pop_back();
        ws.new_pixels.push_back(static_cast<uint32_t>(row_major_index(x, y, ctx.width)));
        ws.new_samples.push_back(sample);
        ++ws.next_sample;
      }
      ws.active += ws.new_slots.size();
      generate_camera_rays(ctx, ws.state, ws.new_slots.data(), ws.new_pixels.data(),
                           ws.new_samples.data(), ws.new_slots.size(), ws.queues, ws.counters);
    });
  }
  ws.active_slot_turns += ws.active;
}

// The retire row of the stage table.
void retire(const KernelContext& ctx, UnitWorkspace& ws) {
  const WorkUnit& unit = *ws.unit;
  const int tile_w = unit.x1 - unit.x0;
  const size_t pixels = static_cast<size_t>(unit.pixel_count());
  PathState& state = ws.state;
  SlotQueue& retired = ws.queues.retire;
  for (const uint32_t s : retired) {
    Rgb l = state.radiance(s);
    if (!is_finite(l)) {
      // A non-finite sample would poison the pixel forever; it is dropped and counted.
      ++ws.counters.nonfinite_samples;
      l = Rgb(0.0f);
    }
    if (ctx.sample_clamp > 0.0f)
      for (int c = 0; c < 3; ++c) l[c] = std::min(l[c], ctx.sample_clamp);
    const uint32_t pixel = state.pixel[s];
    const int x = static_cast<int>(pixel % static_cast<uint32_t>(ctx.width)) - unit.x0;
    const int y = static_cast<int>(pixel / static_cast<uint32_t>(ctx.width)) - unit.y0;
    const size_t index =
        (state.sample[s] - unit.sample_begin) * pixels + row_major_index(x, y, tile_w);
    ws.out[index] = l;
    if (ws.aov_out && ctx.record_aovs) {
      const std::array<float, kAovFloats> aovs = aov_sample(state, s);
      std::copy(aovs.begin(), aovs.end(), ws.aov_out + index * kAovFloats);
    }
    ws.free_slots.push_back(s);
  }
  ws.active -= retired.size();
  retired.clear();
}

// Calls a stage table row's `run` with what it takes: generate and retire the workspace, the
// kernels its path state, queues and counters (shade_escaped counts nothing).
template <typename Run>
void call_stage(Run& run, const KernelContext& ctx, UnitWorkspace& ws) {
  if constexpr (std::is_invocable_v<Run&, const KernelContext&, UnitWorkspace&>) {
    run(ctx, ws);
  } else if constexpr (std::is_invocable_v<Run&, const KernelContext&, PathState&, StageQueues&,
                                           KernelCounters&>) {
    run(ctx, ws.state, ws.queues, ws.counters);
  } else {
    run(ctx, ws.state, ws.queues);
  }
}

// A row whose input queue is empty is skipped (and not counted as a call); generate (no input
// queue) always runs, since it also opens the turn, and times its own work.
template <typename Input, typename Run>
void run_row(const KernelContext& ctx, Stage stage, Input input, Run& run, UnitWorkspace& ws) {
  if constexpr (std::is_null_pointer_v<Input>) {
    call_stage(run, ctx, ws);
  } else if (!(ws.queues.*input).empty()) {
    timed(ws, stage, [&] { call_stage(run, ctx, ws); });
  }
}

}  // namespace

UnitWorkspace::UnitWorkspace(size_t slot_count, bool snee_memory)
    : slots(slot_count),
      state(slot_count, snee_memory),
      queues(slot_count),
      timing_period(static_cast<uint32_t>(std::max<size_t>(1, kSlotsPerTimedTurn / slot_count))) {
  free_slots.reserve(slots);
  new_slots.reserve(slots);
  new_pixels.reserve(slots);
  new_samples.reserve(slots);
}

void start_work_unit(const WorkUnit& unit, Rgb* out, UnitWorkspace& ws, float* aov_out) {
  ws.unit = &unit;
  ws.out = out;
  ws.aov_out = aov_out;
  ws.next_sample = 0;
  ws.active = 0;
  ws.rays_at_start = rays_traced(ws.counters);
  ws.nonfinite_at_start = ws.counters.nonfinite_samples;
  ws.stage_seconds_at_start = stage_seconds_total(ws);
  ws.free_slots.resize(ws.slots);
  // Slots are handed out from the back, so start with slot 0 there.
  for (size_t i = 0; i < ws.slots; ++i) ws.free_slots[i] = static_cast<uint32_t>(ws.slots - 1 - i);
}

double stage_seconds_total(const UnitWorkspace& ws) {
  double total = 0;
  for (const double s : ws.stage_seconds) total += s;
  return total;
}

bool work_unit_finished(const UnitWorkspace& ws) {
  return ws.next_sample == ws.unit->sample_count() && ws.active == 0;
}

void run_stage(const KernelContext& ctx, Stage stage, UnitWorkspace& ws) {
  switch (stage) {
#define SNEE_RUN_STAGE(id, name, label, report, input, run) \
  case Stage::id:                                           \
    run_row(ctx, stage, input, run, ws);                    \
    break;
    SNEE_STAGES(SNEE_RUN_STAGE)
#undef SNEE_RUN_STAGE
    case Stage::kCount:
      break;
  }
}

bool run_work_unit(const KernelContext& ctx, const WorkUnit& unit, UnitWorkspace& ws, Rgb* out,
                   const std::function<bool()>& give_up, float* aov_out) {
  start_work_unit(unit, out, ws, aov_out);
  while (!work_unit_finished(ws)) {
    if (give_up()) return false;
    for (const Stage stage : kStageLoop) run_stage(ctx, stage, ws);
  }
  return true;
}

uint64_t rays_traced(const KernelCounters& counters) {
  uint64_t total = 0;
  for (const uint64_t r : counters.rays) total += r;
  return total;
}

}  // namespace snee
