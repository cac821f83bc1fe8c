// How much work a test does in each build. The sanitized build (SNEE_TEST_SANITIZED, set by
// tests/CMakeLists.txt when SNEE_SANITIZE is on) runs 20 to 30 times slower than Release; there a
// test runs for the memory errors and undefined behaviour along its code, and its statistical
// power is the Release run's job. So its slowest tests take an eighth of their work there, where
// that keeps their meaning:
// - renders that only have to outlast a signal or a checkpoint;
// - statistical tests whose tolerance derives from the measured standard error (it widens with
//   the error, so a bias beyond it still fails);
// - bitwise comparisons of renders (equality holds at any sample count);
// - furnace regressions that count rare wrongly crossed paths (Release counts them at full size).
// Every other build takes the work as written.
#pragma once

namespace snee::test {

template <class Count>
constexpr Count sanitized_share(Count work) {
#ifdef SNEE_TEST_SANITIZED
  return work / 8 > 0 ? work / 8 : 1;
#else
  return work;
#endif
}

}  // namespace snee::test
