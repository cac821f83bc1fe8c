// The time budget of a render (RenderOptions::time_seconds), asked as each round of units is
// about to start: rounds are all or nothing, so every pixel holds whole rounds of samples.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>

namespace snee {

class TimeBudget {
 public:
  // `seconds` 0 is no budget. A resumed render passes the start of the render it continues
  // (its own start less the seconds already spent) and the rounds some tile had begun there:
  // those are finished whatever the clock says, so that every tile again holds whole rounds.
  TimeBudget(double seconds, std::chrono::steady_clock::time_point start, uint32_t rounds_begun = 0)
      : seconds_(seconds), start_(start), first_stoppable_(std::max<uint32_t>(1, rounds_begun)) {}
  // Whether round `round` must not start: the budget is spent. Remembers that it stopped the
  // render. Thread-safe.
  bool stops(uint32_t round) {
    if (seconds_ <= 0 || round < first_stoppable_) return false;
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
  const uint32_t first_stoppable_;
  std::atomic<uint32_t> stopped_before_{kNone};
};

}  // namespace snee
