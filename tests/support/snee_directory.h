// A test that runs the snee binary in a scratch directory of its own, so default outputs land
// there, and reads back what the program said.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/command_line.h"
#include "tests/support/test_directory.h"

namespace snee::test {

class SneeDirectoryTest : public ::testing::Test {
 protected:
  explicit SneeDirectoryTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override { dir_ = fresh_test_directory(prefix_); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Exit code of `binary ARGS` run in the directory; its output is in output().
  int run(const std::string& binary, const std::string& args) const {
    return run_command("cd '" + dir_.string() + "' && '" + binary + "' " + args,
                       dir_ / "output.txt");
  }
  std::string output() const { return read_text_file(dir_ / "output.txt"); }
  bool said(const std::string& text) const { return output().find(text) != std::string::npos; }
  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace snee::test
