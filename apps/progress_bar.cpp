#include "apps/progress_bar.h"

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

ProgressBar::ProgressBar(std::FILE* stream)
    : stream_(stream),
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

  const double f = progress.fraction;
  const double eta = f > 0 ? progress.elapsed_seconds * (1 - f) / f : -1;
  std::fprintf(stream_, "%s%5.1f%%  %lld/%lld samples  %.1f Mrays/s  elapsed %s  ETA %s%s",
               tty_ ? "\r" : "", 100 * f, static_cast<long long>(progress.samples_done),
               static_cast<long long>(progress.samples_total), progress.mrays_per_second,
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
