// Helpers for tests that run the snee programs as a user would: a command through the shell
// with its output captured, a program in the background to signal, and files read back whole.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace snee::test {

std::string read_text_file(const std::filesystem::path& path);

// Runs `command` through /bin/sh with stdin from /dev/null and stdout and stderr into `log`;
// returns its exit code (128 + the signal number if a signal ended it).
int run_command(const std::string& command, const std::filesystem::path& log);
// Runs `program args` from directory `dir` as run_command does, its output (stdout and stderr,
// through dir/output.txt) into `output`; returns its exit code.
int run_in_directory(const std::filesystem::path& dir, const std::string& program,
                     const std::string& args, std::string& output);

// Polls `condition` until it holds or `timeout` passes; returns whether it held. Generous
// timeouts only: they bound a hang, never measure speed.
bool wait_for(const std::function<bool()>& condition,
              std::chrono::seconds timeout = std::chrono::seconds(60));

// A program started in the background (argv[0] is its path) with stdout and stderr in `log`;
// killed, if still running, when this goes away.
class BackgroundCommand {
 public:
  BackgroundCommand(const std::vector<std::string>& argv, const std::filesystem::path& log);
  ~BackgroundCommand();
  BackgroundCommand(const BackgroundCommand&) = delete;
  BackgroundCommand& operator=(const BackgroundCommand&) = delete;

  pid_t pid() const { return pid_; }
  std::string output() const { return read_text_file(log_); }
  // Sends `signal` and waits up to `timeout` for the program to end; returns its exit code
  // (128 + the signal number if a signal ended it), or -1 if it did not end in time.
  int signal_and_wait(int signal, std::chrono::seconds timeout = std::chrono::seconds(60)) const;
  // Waits up to `timeout`; the exit code as above, -1 if it did not end in time.
  int wait(std::chrono::seconds timeout = std::chrono::seconds(60)) const;

 private:
  const std::filesystem::path log_;
  pid_t pid_ = -1;
  mutable bool ended_ = false;
};

}  // namespace snee::test
