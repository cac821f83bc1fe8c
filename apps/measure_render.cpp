#include "apps/measure_render.h"

#include <algorithm>
#include <cstdio>

#include "apps/peak_memory.h"

namespace snee {

void Measurement::repeat(const Scene& scene, const RenderOptions& options) {
  reset_peak_memory();
  runs_.push_back(render(scene, options).stats);
  peak_memory_mib_ = std::max(peak_memory_mib_, peak_memory_since_reset_mib());
}

const RenderStats& Measurement::median() const {
  std::vector<const RenderStats*> order;
  for (const RenderStats& r : runs_) order.push_back(&r);
  std::sort(order.begin(), order.end(), [](const RenderStats* a, const RenderStats* b) {
    return a->sampling_seconds < b->sampling_seconds;
  });
  return *order[order.size() / 2];
}

std::vector<double> Measurement::sampling_seconds() const {
  std::vector<double> s;
  for (const RenderStats& r : runs_) s.push_back(r.sampling_seconds);
  return s;
}

std::vector<double> Measurement::sampling_cpu_seconds() const {
  std::vector<double> s;
  for (const RenderStats& r : runs_) s.push_back(r.sampling_cpu_seconds);
  return s;
}

Measurement measure_render(const Scene& scene, const RenderOptions& options, int repeats) {
  Measurement m;
  for (int r = 0; r < repeats; ++r) m.repeat(scene, options);
  return m;
}

MeasurementCheck check_measurement(double wall_seconds, double cpu_seconds, int threads) {
  MeasurementCheck check;
  check.cpu_share = wall_seconds > 0 ? cpu_seconds / (wall_seconds * threads) : 0;
  char text[256];
  if (check.cpu_share < kFairCpuShare) {
    std::snprintf(text, sizeof text,
                  "got %.0f%% of the CPU it asked for (%.3g CPU-s over %.3g s x %d threads): "
                  "other work or too few cores, so its rates understate the renderer",
                  100 * check.cpu_share, cpu_seconds, wall_seconds, threads);
    check.warnings.emplace_back(text);
  }
  if (wall_seconds < kShortestFairSeconds) {
    std::snprintf(text, sizeof text,
                  "ran for %.3g s, under %.0f s: start-up and timer resolution weigh in; use "
                  "more spp or a larger resolution for figures to compare",
                  wall_seconds, kShortestFairSeconds);
    check.warnings.emplace_back(text);
  }
  return check;
}

}  // namespace snee
