// The fixture of the tests that run the snee program as a user would (test_cli*.cpp): a fresh
// directory per test, where `snee ARGS` runs so that its default outputs land there too. Header
// only: SNEE_BINARY is defined per test executable (tests/CMakeLists.txt's snee_cli_test).
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/command_line.h"
#include "tests/support/test_directory.h"

namespace snee::test {

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

inline void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// No partial (temporary) file in `dir`: every name there is a final one.
inline bool only_final_files(const std::filesystem::path& dir) {
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (contains(entry.path().filename().string(), ".partial")) return false;
  }
  return true;
}

class CliTest : public ::testing::Test {
 public:
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

 protected:
  void SetUp() override { dir_ = fresh_test_directory("cli"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  Outcome snee(const std::string& args) const {
    Outcome result;
    result.exit_code = run_in_directory(dir_, SNEE_BINARY, args, result.output);
    return result;
  }
  std::filesystem::path dir_;
};

}  // namespace snee::test
