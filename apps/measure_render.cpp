#include "apps/measure_render.h"

#include <algorithm>

#include "apps/peak_memory.h"

namespace snee {

Measurement measure_render(const Scene& scene, const RenderOptions& options, int repeats) {
  Measurement m;
  reset_peak_memory();
  std::vector<RenderStats> runs;
  for (int r = 0; r < repeats; ++r) {
    runs.push_back(render(scene, options).stats);
    m.pass_seconds.push_back(runs.back().pass_seconds);
    m.pass_cpu_seconds.push_back(runs.back().pass_cpu_seconds);
  }
  m.peak_memory_mib = peak_memory_mib();
  std::vector<size_t> order(runs.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return runs[a].pass_seconds < runs[b].pass_seconds; });
  m.median = runs[order[order.size() / 2]];
  return m;
}

}  // namespace snee
