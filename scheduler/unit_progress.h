// What happens after every finished work unit, on the worker that finished it: progress
// reports, checkpoints of the film, and the question whether to stop (render.h, RenderHooks).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>

#include "scene/film.h"
#include "scheduler/film_accumulator.h"
#include "scheduler/render.h"
#include "scheduler/work_unit.h"

namespace snee {

class UnitProgress {
 public:
  // `meta` is stamped on every checkpoint, with the time so far; the state of every
  // checkpoint counts `resumed_seconds` (those of the runs a resumed render continues) too.
  UnitProgress(const RenderHooks& hooks, int64_t samples_total,
               std::chrono::steady_clock::time_point start, const FilmAccumulator& film,
               const FilmMetadata& meta, double resumed_seconds = 0);
  // The film's exact state now (RenderHooks::checkpoint_state), with the seconds so far.
  FilmState state() const;
  // `ws` has just finished its current unit and the film holds it. Returns false once the
  // caller asked to stop. Thread-safe.
  bool unit_finished(const UnitWorkspace& ws);
  // A unit of `samples` was not run (its tile had met the noise target): it counts as done.
  void unit_skipped(int64_t samples);
  // Whether the caller asked to stop (RenderHooks::stop_requested); once it did, stays true
  // without asking again. Thread-safe.
  bool stop_requested();

 private:
  double elapsed_seconds() const;
  void report(int64_t samples_done, uint64_t rays_done);
  void checkpoint_if_due();

  const RenderHooks& hooks_;
  const int64_t samples_total_;
  const std::chrono::steady_clock::time_point start_;
  const FilmAccumulator& film_;
  const FilmMetadata meta_;
  const double resumed_seconds_;
  std::atomic<int64_t> samples_done_{0};
  std::atomic<uint64_t> rays_done_{0};
  std::atomic<uint64_t> nonfinite_done_{0};  // stamped on checkpoints
  std::atomic<bool> stopping_{false};
  std::mutex checkpoint_mutex_;  // held while a checkpoint is taken; others skip, never wait
  double last_checkpoint_seconds_ = 0;
};

}  // namespace snee
