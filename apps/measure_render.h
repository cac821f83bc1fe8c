// Repeated renders for throughput studies (`snee bench`, `snee scale`): the same scene and
// options rendered several times, summarised by the run with the median sample-pass time,
// which is robust against the odd run slowed by other work on a shared machine.
#pragma once

#include <vector>

#include "scene/scene.h"
#include "scheduler/render.h"

namespace snee {

struct Measurement {
  RenderStats median;                    // statistics of the median run
  std::vector<double> pass_seconds;      // every repeat, in run order
  std::vector<double> pass_cpu_seconds;  // every repeat, in run order
  double peak_memory_mib = 0;            // over the repeats (peak_memory.h)
};

Measurement measure_render(const Scene& scene, const RenderOptions& options, int repeats);

}  // namespace snee
