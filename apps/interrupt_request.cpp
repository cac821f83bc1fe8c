#include "apps/interrupt_request.h"

#include <atomic>
#include <csignal>

namespace snee {
namespace {

// A lock-free atomic is the one thing a signal handler may safely write.
std::atomic<int> received_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

struct sigaction previous_int, previous_term;

void on_signal(int signal) {
  received_signal.store(signal);
}

}  // namespace

InterruptRequest::InterruptRequest() {
  received_signal.store(0);
  struct sigaction action = {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
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

}  // namespace snee
