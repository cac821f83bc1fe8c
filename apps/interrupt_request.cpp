#include "apps/interrupt_request.h"

#include <unistd.h>

#include <atomic>
#include <climits>
#include <csignal>
#include <cstring>

namespace snee {
namespace {

// Lock-free atomics are the one thing a signal handler may safely touch, besides the calls
// POSIX lists as async-signal-safe (unlink, signal, raise).
std::atomic<int> received_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);
std::atomic<bool> file_in_flight{false};
static_assert(std::atomic<bool>::is_always_lock_free);
char file_in_flight_path[PATH_MAX + 1];

struct sigaction previous_int, previous_term;

void on_signal(int signal) {
  if (received_signal.exchange(signal) == 0) return;
  if (file_in_flight.load()) ::unlink(file_in_flight_path);
  // The signal is blocked while its handler runs, so it is delivered, with the default
  // action, as soon as the handler returns.
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

InterruptRequest::InterruptRequest() {
  received_signal.store(0);
  struct sigaction action = {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  // Without SA_RESTART a signal during a file write would fail the write with EINTR.
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
}

InterruptRequest::~InterruptRequest() {
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
}

bool InterruptRequest::requested() const {
  return received_signal.load() != 0;
}

int InterruptRequest::exit_status() const {
  const int signal = received_signal.load();
  return signal != 0 ? 128 + signal : 0;
}

FileInFlight::FileInFlight(const std::string& path) {
  // A path too long to keep could not be created either.
  if (path.size() > PATH_MAX) return;
  std::memcpy(file_in_flight_path, path.c_str(), path.size() + 1);
  file_in_flight.store(true);
}

FileInFlight::~FileInFlight() {
  file_in_flight.store(false);
}

}  // namespace snee
