// The time budget of a render (RenderOptions::time_seconds), asked as each round of units is
// about to start: rounds are all or nothing, so every pixel holds whole rounds of samples.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>

namespace snee {

class TimeBudget {
 public:
  // `seconds` 0 is no budget.
  TimeBudget(double seconds, std::chrono::steady_clock::time_point start)
      : seconds_(seconds), start_(start) {}
  // Whether round `round` (> 0) must not start: the budget is spent. Remembers that it stopped
  // the render. Thread-safe.
  bool stops(uint32_t round) {
    if (seconds_ <= 0 || round == 0) return false;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (elapsed < seconds_) return false;
    uint32_t none = kNone;
    stopped_before_.compare_exchange_strong(none, round);
    return true;
  }
  bool spent() const { return stopped_before_.load() != kNone; }
  // The rounds every tile holds once the units in flight are in: all of them, unless the
  // budget stopped the render.
  uint32_t rounds(uint32_t all) const { return spent() ? stopped_before_.load() : all; }

 private:
  static constexpr uint32_t kNone = UINT32_MAX;
  const double seconds_;
  const std::chrono::steady_clock::time_point start_;
  std::atomic<uint32_t> stopped_before_{kNone};
};

}  // namespace snee
