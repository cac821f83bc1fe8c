// Turns the first SIGINT (Ctrl-C) or SIGTERM into a request to stop, so a render can drop the
// work units in flight and write what it has; a second signal ends the process at once as
// usual, removing the partial file being written, if any (FileInFlight).
#pragma once

#include <string>

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

// While one exists, `path` is the partial file being written, which a second signal removes
// before ending the process. One at a time (the render's writes never overlap).
class FileInFlight {
 public:
  explicit FileInFlight(const std::string& path);
  ~FileInFlight();
  FileInFlight(const FileInFlight&) = delete;
  FileInFlight& operator=(const FileInFlight&) = delete;
};

}  // namespace snee
