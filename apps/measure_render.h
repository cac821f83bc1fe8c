// Repeated renders for throughput studies (`snee bench`, `snee scale`): the same scene and
// options rendered several times, summarised by the run with the median sampling time,
// which is robust against the odd run slowed by other work on a shared machine. Repeats of
// configurations that are compared with each other can be interleaved (one repeat of each in
// turn), so a burst of other work slows them alike.
#pragma once

#include <string>
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

// Whether a timed run measured the renderer rather than the machine around it. A run that got
// less than kFairCpuShare of the CPU it asked for (CPU time / (wall time x threads)) shared its
// cores with other work or had fewer than it asked for; one under kShortestFairSeconds of
// sampling is dominated by thread start-up, the first touches of memory and timer resolution.
// Either way its rates understate (or misstate) the renderer, so they are reported with a
// warning rather than silently.
inline constexpr double kFairCpuShare = 0.9;
inline constexpr double kShortestFairSeconds = 1.0;
struct MeasurementCheck {
  double cpu_share = 0;               // CPU time / (wall time x threads); 0 without wall time
  std::vector<std::string> warnings;  // empty when the run is fair by both measures
};
MeasurementCheck check_measurement(double wall_seconds, double cpu_seconds, int threads);

}  // namespace snee
