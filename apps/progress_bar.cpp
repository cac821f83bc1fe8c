#include "apps/progress_bar.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <unistd.h>

namespace snee {
namespace {

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const long total = std::lround(seconds);
  const long h = total / 3600, m = total / 60 % 60, s = total % 60;
  char buf[32];
  if (h > 0)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", h, m, s);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", m, s);
  return buf;
}

}  // namespace

ProgressBar::ProgressBar(std::FILE* stream, std::string label, double time_budget_seconds)
    : stream_(stream),
      label_(label.empty() ? label : label + ": "),
      time_budget_seconds_(time_budget_seconds),
      tty_(isatty(fileno(stream)) != 0),
      interval_(tty_ ? std::chrono::milliseconds(250) : std::chrono::seconds(5)) {
  // The first line of a log appears after one interval, not at 0 %.
  last_print_ = std::chrono::steady_clock::now();
}

void ProgressBar::update(const Progress& progress) {
  // A worker that finds another one printing skips its report instead of waiting for it.
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_print_ < interval_) return;
  last_print_ = now;

  const double clock =
      time_budget_seconds_ > 0 ? std::min(1.0, progress.elapsed_seconds / time_budget_seconds_) : 0;
  const double f = std::max(progress.fraction, clock);
  const double eta = f > 0 ? progress.elapsed_seconds * (1 - f) / f : -1;
  // Under a time budget the spp is only a cap, so the samples it would take mean little.
  char samples[64];
  if (time_budget_seconds_ > 0)
    std::snprintf(samples, sizeof samples, "%lld samples in a %s budget",
                  static_cast<long long>(progress.samples_done),
                  format_duration(time_budget_seconds_).c_str());
  else
    std::snprintf(samples, sizeof samples, "%lld/%lld samples",
                  static_cast<long long>(progress.samples_done),
                  static_cast<long long>(progress.samples_total));
  std::fprintf(stream_, "%s%s%5.1f%%  %s  %.1f Mrays/s  elapsed %s  ETA %s%s", tty_ ? "\r" : "",
               label_.c_str(), 100 * f, samples, progress.mrays_per_second,
               format_duration(progress.elapsed_seconds).c_str(), format_duration(eta).c_str(),
               tty_ ? "\033[K" : "\n");
  std::fflush(stream_);
  drawn_ = true;
}

void ProgressBar::finish() {
  std::lock_guard lock(mutex_);
  if (tty_ && drawn_) std::fputs("\r\033[K", stream_);
  drawn_ = false;
}

}  // namespace snee
