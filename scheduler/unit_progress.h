// Progress of a render, advanced by whichever worker finishes a work unit.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>

#include "scheduler/render.h"
#include "scheduler/work_unit.h"

namespace snee {

class UnitProgress {
 public:
  UnitProgress(const ProgressCallback& callback, int64_t samples_total,
               std::chrono::steady_clock::time_point start)
      : callback_(callback), samples_total_(samples_total), start_(start) {}
  // `ws` has just finished its current unit; thread-safe.
  void unit_finished(const UnitWorkspace& ws);

 private:
  const ProgressCallback& callback_;
  int64_t samples_total_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<int64_t> samples_done_{0};
  std::atomic<uint64_t> rays_done_{0};
};

}  // namespace snee
