#include "scheduler/work_unit.h"

#include <numeric>

namespace snee {

namespace {

using Clock = std::chrono::steady_clock;

template <typename F>
void timed(UnitWorkspace& ws, Stage stage, F&& f) {
  const auto start = Clock::now();
  f();
  ws.stage_seconds[static_cast<int>(stage)] +=
      std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

UnitWorkspace::UnitWorkspace(size_t slots) : state(slots), queues(slots) {
  free_slots.reserve(slots);
  new_slots.reserve(slots);
  new_pixels.reserve(slots);
  new_samples.reserve(slots);
}

void run_work_unit(const KernelContext& ctx, const WorkUnit& unit, UnitWorkspace& ws, Rgb* out) {
  PathState& state = ws.state;
  StageQueues& q = ws.queues;
  const size_t slots = state.capacity();
  ws.free_slots.resize(slots);
  // Slots are handed out from the back, so start with slot 0 there.
  for (size_t i = 0; i < slots; ++i) ws.free_slots[i] = static_cast<uint32_t>(slots - 1 - i);
  const int tile_w = unit.x1 - unit.x0;
  const size_t pixels = static_cast<size_t>(unit.pixel_count());
  const size_t total = unit.sample_count();
  size_t next = 0, active = 0;

  while (next < total || active > 0) {
    timed(ws, Stage::kGenerate, [&] {
      ws.new_slots.clear();
      ws.new_pixels.clear();
      ws.new_samples.clear();
      while (next < total && !ws.free_slots.empty()) {
        const size_t local_pixel = next % pixels;
        const uint32_t sample = unit.sample_begin + static_cast<uint32_t>(next / pixels);
        const int x = unit.x0 + static_cast<int>(local_pixel) % tile_w;
        const int y = unit.y0 + static_cast<int>(local_pixel) / tile_w;
        ws.new_slots.push_back(ws.free_slots.back());
        ws.free_slots.pop_back();
        ws.new_pixels.push_back(static_cast<uint32_t>(y * ctx.width + x));
        ws.new_samples.push_back(sample);
        ++next;
      }
      active += ws.new_slots.size();
      generate_camera_rays(ctx, state, ws.new_slots.data(), ws.new_pixels.data(),
                           ws.new_samples.data(), ws.new_slots.size(), q, ws.counters);
    });
    timed(ws, Stage::kExtend, [&] { extend(ctx, state, q, ws.counters); });
    if (!q.medium.empty())
      timed(ws, Stage::kMediumEvent, [&] { medium_event(ctx, state, q, ws.counters); });
    if (!q.probe.empty())
      timed(ws, Stage::kSneeProbe, [&] { snee_probe_and_subdivide(ctx, state, q, ws.counters); });
    if (!q.surface.empty())
      timed(ws, Stage::kShadeSurface, [&] { shade_surface(ctx, state, q, ws.counters); });
    if (!q.escaped.empty()) timed(ws, Stage::kShadeEscaped, [&] { shade_escaped(ctx, state, q); });
    if (!q.shadow.empty())
      timed(ws, Stage::kShadowConnect, [&] { shadow_connect(ctx, state, q, ws.counters); });
    timed(ws, Stage::kRetire, [&] {
      for (const uint32_t s : q.retire) {
        Rgb l = state.radiance(s);
        if (!is_finite(l)) {
          // A non-finite sample would poison the pixel forever; it is dropped and counted.
          ++ws.counters.nonfinite_samples;
          l = Rgb(0.0f);
        }
        const uint32_t pixel = state.pixel[s];
        const int x = static_cast<int>(pixel % static_cast<uint32_t>(ctx.width)) - unit.x0;
        const int y = static_cast<int>(pixel / static_cast<uint32_t>(ctx.width)) - unit.y0;
        out[(state.sample[s] - unit.sample_begin) * pixels + static_cast<size_t>(y * tile_w + x)] =
            l;
        ws.free_slots.push_back(s);
      }
      active -= q.retire.size();
      q.retire.clear();
    });
  }
}

}  // namespace snee
