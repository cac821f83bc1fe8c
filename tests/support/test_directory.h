// A scratch directory of the test that is running, for reproducer files and outputs.
#pragma once

#include <filesystem>
#include <string_view>

namespace snee::test {

// <temp>/snee_<prefix>_<pid>_<test name>, emptied and created. The pid keeps parallel ctest
// runs of one binary apart and the test name keeps tests apart, since gtest_discover_tests runs
// each test as its own process.
std::filesystem::path fresh_test_directory(std::string_view prefix);

}  // namespace snee::test
