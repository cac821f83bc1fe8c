// Helpers for tests that run the snee programs as a user would: a command through the shell
// with its output captured, and files read back whole.
#pragma once

#include <filesystem>
#include <string>

namespace snee::test {

std::string read_text_file(const std::filesystem::path& path);

// Runs `command` through /bin/sh with stdin from /dev/null and stdout and stderr into `log`;
// returns its exit code (128 + the signal number if a signal ended it).
int run_command(const std::string& command, const std::filesystem::path& log);

}  // namespace snee::test
