#include "scheduler/unit_progress.h"

namespace snee {

UnitProgress::UnitProgress(const RenderHooks& hooks, int64_t samples_total,
                           std::chrono::steady_clock::time_point start, const FilmAccumulator& film,
                           const FilmMetadata& meta, double resumed_seconds)
    : hooks_(hooks),
      samples_total_(samples_total),
      start_(start),
      film_(film),
      meta_(meta),
      resumed_seconds_(resumed_seconds) {}

FilmState UnitProgress::state() const {
  FilmState state = film_.state();
  state.seconds = resumed_seconds_ + elapsed_seconds();
  return state;
}

double UnitProgress::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool UnitProgress::unit_finished(const UnitWorkspace& ws) {
  const uint64_t rays = rays_done_ += rays_traced(ws.counters) - ws.rays_at_start;
  nonfinite_done_ += ws.counters.nonfinite_samples - ws.nonfinite_at_start;
  report(samples_done_ += static_cast<int64_t>(ws.unit->sample_count()), rays);
  if ((hooks_.checkpoint || hooks_.checkpoint_state) && hooks_.checkpoint_seconds > 0)
    checkpoint_if_due();
  return !stop_requested();
}

void UnitProgress::unit_skipped(int64_t samples) {
  report(samples_done_ += samples, rays_done_.load());
}

void UnitProgress::report(int64_t done, uint64_t rays) {
  if (!hooks_.progress) return;
  Progress p;
  p.samples_done = done;
  p.samples_total = samples_total_;
  p.fraction = static_cast<double>(done) / static_cast<double>(samples_total_);
  p.elapsed_seconds = elapsed_seconds();
  p.mrays_per_second =
      p.elapsed_seconds > 0 ? static_cast<double>(rays) / p.elapsed_seconds * 1e-6 : 0;
  hooks_.progress(p);
}

bool UnitProgress::stop_requested() {
  if (stopping_.load(std::memory_order_relaxed)) return true;
  if (!hooks_.stop_requested || !hooks_.stop_requested()) return false;
  stopping_.store(true, std::memory_order_relaxed);
  return true;
}

void UnitProgress::checkpoint_if_due() {
  std::unique_lock<std::mutex> lock(checkpoint_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  const double now = elapsed_seconds();
  if (now - last_checkpoint_seconds_ < hooks_.checkpoint_seconds) return;
  last_checkpoint_seconds_ = now;
  FilmMetadata meta = meta_;
  meta.render_seconds = now;
  meta.nonfinite_samples = nonfinite_done_.load();
  if (hooks_.checkpoint) hooks_.checkpoint(film_.resolve(meta));
  if (hooks_.checkpoint_state) hooks_.checkpoint_state(state());
}

}  // namespace snee
