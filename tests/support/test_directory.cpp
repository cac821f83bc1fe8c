#include "tests/support/test_directory.h"

#include <unistd.h>

#include <string>

#include <gtest/gtest.h>

namespace snee::test {

std::filesystem::path fresh_test_directory(std::string_view prefix) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("snee_" + std::string(prefix) + "_" + std::to_string(::getpid()) + "_" +
       ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace snee::test
