// Turns the first SIGINT (Ctrl-C) or SIGTERM into a request to stop, so a render can finish
// the work units in flight and write what it has; the handler then reverts to the default, so
// a second signal ends the process at once as usual.
#pragma once

namespace snee {

class InterruptRequest {
 public:
  InterruptRequest();   // installs the handlers
  ~InterruptRequest();  // restores the handlers that were there before
  InterruptRequest(const InterruptRequest&) = delete;
  InterruptRequest& operator=(const InterruptRequest&) = delete;

  bool requested() const;
  // The shell's exit status for the signal received (128 + its number); 0 if none.
  int exit_status() const;
};

}  // namespace snee
