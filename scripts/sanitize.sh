#!/usr/bin/env bash
# Builds everything with AddressSanitizer and UndefinedBehaviorSanitizer in build-asan/ and
# runs the test suite there; exits with ctest's status. The CLI tests spawn this build's snee
# and snee-mpi, so those run sanitized too. Extra arguments go to ctest (e.g. -R Furnace).
#
#   bash scripts/sanitize.sh [--ci] [CTEST_ARGUMENT ...]
#
# --ci builds and runs only the tests of the scene, physics and kernels layers
# (tests/CMakeLists.txt's snee_tests_scene, snee_tests_physics and snee_tests_kernels: every
# reader of user input, the BSDFs, media, lights, SNEE's math and the batched stage code) and
# of the scheduler layer but its two long statistical render tests (snee_tests_scheduler_ci:
# work units, schedules and threads, budgets, resume, furnaces, textures, smooth shading), the
# part that fits CI's budget (.ci/README.md); the CLI tests need the whole instrumented build
# (they spawn the sanitized binaries), which takes longer than CI has.
#
# The benchmarks are not built: their smoke runs exercise nothing the tests do not, and their
# build would add minutes to CI.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

targets=(all)
ctest_scope=()
if [[ ${1:-} == --ci ]]; then
  shift
  targets=(snee_tests_scene snee_tests_physics snee_tests_kernels snee_tests_scheduler_ci)
  # Tests of executables this build skipped are registered as <target>_NOT_BUILT.
  ctest_scope=(-E '_NOT_BUILT$')
fi

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# -O1 instead of Release's -O3: the instrumented build compiles 2 to 5 times faster (85 s of
# CPU down to 18 s for the heaviest kernel file) and the tests still take seconds.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DSNEE_SANITIZE=address,undefined -DSNEE_BUILD_BENCHMARKS=OFF "${launcher[@]}" \
  --log-level=WARNING >/dev/null
cmake --build build-asan -j"$(nproc)" --target "${targets[@]}"

# Undefined behaviour aborts already (-fno-sanitize-recover); the stack makes it readable.
# Leaks are checked, except what tests/sanitizer/lsan.supp lists with its reason.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1}
lsan_default=suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0
export LSAN_OPTIONS=${LSAN_OPTIONS:-$lsan_default}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
# Open MPI's transports are plugins it loads with dlopen and never unloads cleanly after a
# signal: LeakSanitizer reports their allocations from "<unknown module>", which no
# suppression can name. So the MPI tests (Mpi*) run with leak checking off, and everything
# else with it on.
status=0
if ((${#ctest_scope[@]} > 0)); then
  ctest --test-dir build-asan --output-on-failure -j"$(nproc)" "${ctest_scope[@]}" "$@" ||
    status=$?
  exit "$status"
fi
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -E '^Mpi' "$@" || status=$?
ASAN_OPTIONS=$ASAN_OPTIONS:detect_leaks=0 \
  ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -R '^Mpi' "$@" || status=$?
exit "$status"
