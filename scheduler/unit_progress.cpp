#include "scheduler/unit_progress.h"

namespace snee {

void UnitProgress::unit_finished(const UnitWorkspace& ws) {
  const uint64_t rays = rays_done_ += rays_traced(ws.counters) - ws.rays_at_start;
  const int64_t done = samples_done_ += static_cast<int64_t>(ws.unit->sample_count());
  if (!callback_) return;
  Progress p;
  p.samples_done = done;
  p.samples_total = samples_total_;
  p.fraction = static_cast<double>(done) / static_cast<double>(samples_total_);
  p.elapsed_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  p.mrays_per_second =
      p.elapsed_seconds > 0 ? static_cast<double>(rays) / p.elapsed_seconds * 1e-6 : 0;
  callback_(p);
}

}  // namespace snee
