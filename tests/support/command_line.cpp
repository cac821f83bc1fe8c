#include "tests/support/command_line.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

namespace snee::test {
namespace {

int exit_code(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int run_command(const std::string& command, const std::filesystem::path& log) {
  const int status = std::system((command + " > '" + log.string() + "' 2>&1 < /dev/null").c_str());
  return exit_code(status);
}

int run_in_directory(const std::filesystem::path& dir, const std::string& program,
                     const std::string& args, std::string& output) {
  const std::filesystem::path log = dir / "output.txt";
  const int code = run_command("cd '" + dir.string() + "' && '" + program + "' " + args, log);
  output = read_text_file(log);
  return code;
}

bool wait_for(const std::function<bool()>& condition, std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

BackgroundCommand::BackgroundCommand(const std::vector<std::string>& argv,
                                     const std::filesystem::path& log)
    : log_(log) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_ = fork();
  if (pid_ == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = open("/dev/null", O_RDONLY);
    dup2(null, 0);
    dup2(fd, 1);
    dup2(fd, 2);
    execv(args[0], args.data());
    _exit(127);
  }
}

BackgroundCommand::~BackgroundCommand() {
  if (pid_ <= 0 || ended_) return;
  kill(pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
}

int BackgroundCommand::wait(std::chrono::seconds timeout) const {
  int status = 0;
  const bool ended = wait_for([&] { return waitpid(pid_, &status, WNOHANG) == pid_; }, timeout);
  if (!ended) return -1;
  ended_ = true;
  return exit_code(status);
}

int BackgroundCommand::signal_and_wait(int signal, std::chrono::seconds timeout) const {
  if (kill(pid_, signal) != 0) return -1;
  return wait(timeout);
}

}  // namespace snee::test
