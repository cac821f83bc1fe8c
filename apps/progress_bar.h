// Progress of a running render on a terminal or a log. render() reports from its worker
// threads, so printing is serialised here and throttled to keep the output readable.
#pragma once

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

#include "scheduler/render.h"

namespace snee {

class ProgressBar {
 public:
  // A TTY gets one line redrawn in place ~4 times a second; anything else (CI logs, files) a
  // new line every ~5 s. `label` starts every line (which of several renders this is). Under a
  // time budget (RenderOptions::time_seconds) the render ends when the clock says, before its
  // spp, so the share of the budget spent counts as done when it is ahead of the samples.
  explicit ProgressBar(std::FILE* stream, std::string label = {}, double time_budget_seconds = 0);
  void update(const Progress& progress);
  // Ends the redrawn line so the next output starts on a fresh one.
  void finish();

 private:
  std::FILE* stream_;
  std::string label_;
  double time_budget_seconds_;
  bool tty_;
  std::chrono::steady_clock::duration interval_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_print_{};
  bool drawn_ = false;
};

}  // namespace snee
