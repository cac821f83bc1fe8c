#include "scheduler/unit_window.h"

#include <stdexcept>

namespace snee {

UnitWindow::UnitWindow(size_t units, size_t lead) : units_(units), lead_(lead), finished_(lead) {
  if (lead == 0) throw std::invalid_argument("a unit window needs a lead of at least one unit");
}

std::optional<size_t> UnitWindow::take(bool wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (wait) window_moved_.wait(lock, [&] { return aborted_ || next_ == units_ || !full(); });
  if (aborted_ || next_ == units_ || full()) return std::nullopt;
  return next_++;
}

void UnitWindow::finish(size_t unit) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (unit < oldest_unfinished_ || unit >= next_ || finished_[unit % lead_])
      throw std::logic_error("unit finished twice or never taken");
    finished_[unit % lead_] = 1;
    if (unit != oldest_unfinished_) return;
    while (oldest_unfinished_ < next_ && finished_[oldest_unfinished_ % lead_]) {
      finished_[oldest_unfinished_ % lead_] = 0;
      ++oldest_unfinished_;
    }
  }
  window_moved_.notify_all();
}

void UnitWindow::abort() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    aborted_ = true;
  }
  window_moved_.notify_all();
}

}  // namespace snee
