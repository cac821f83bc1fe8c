// Repeated renders for throughput studies (`snee bench`, `snee scale`): the same scene and
// options rendered several times, summarised by the run with the median sampling time,
// which is robust against the odd run slowed by other work on a shared machine. Repeats of
// configurations that are compared with each other can be interleaved (one repeat of each in
// turn), so a burst of other work slows them alike.
#pragma once

#include <vector>

#include "scene/scene.h"
#include "scheduler/render.h"

namespace snee {

class Measurement {
 public:
  // Renders once more and keeps the run's statistics and peak memory.
  void repeat(const Scene& scene, const RenderOptions& options);
  const RenderStats& median() const;                 // the run with the median sampling time
  std::vector<double> sampling_seconds() const;      // every repeat, in run order
  std::vector<double> sampling_cpu_seconds() const;  // every repeat, in run order
  double peak_memory_mib() const { return peak_memory_mib_; }  // highest over the repeats

 private:
  std::vector<RenderStats> runs_;
  double peak_memory_mib_ = 0;
};

Measurement measure_render(const Scene& scene, const RenderOptions& options, int repeats);

}  // namespace snee
