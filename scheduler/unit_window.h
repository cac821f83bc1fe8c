// Hands out work units in order, with a bounded lead: unit k is handed out only once every
// unit before k - lead has finished. The film keeps one sample buffer per position in that
// window (film_accumulator.h), so memory is bounded by the lead, never by spp, and no barrier
// ever stops the threads between groups of units: a slow unit holds back only the threads that
// have run `lead` units past it.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>
#include <vector>

namespace snee {

class UnitWindow {
 public:
  UnitWindow(size_t units, size_t lead);

  // The next unit; nullopt once every unit has been handed out. With `wait`, blocks while the
  // window is full; without it, also returns nullopt then.
  std::optional<size_t> take(bool wait);
  // Called once per unit taken, after its samples are in the film.
  void finish(size_t unit);
  // Hands out nothing more and wakes every waiting take: the render was asked to stop, or a
  // unit failed and will never finish (the others must not wait for it).
  void abort();

 private:
  bool full() const { return next_ == oldest_unfinished_ + lead_; }

  const size_t units_, lead_;
  std::mutex mutex_;
  std::condition_variable window_moved_;
  bool aborted_ = false;
  size_t next_ = 0;               // units handed out so far
  size_t oldest_unfinished_ = 0;  // every unit before it has finished
  std::vector<char> finished_;    // by unit % lead, for units in [oldest_unfinished_, next_)
};

}  // namespace snee
