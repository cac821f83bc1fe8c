#!/usr/bin/env bash
# Builds everything with AddressSanitizer and UndefinedBehaviorSanitizer in build-asan/ and
# runs the test suite there; exits with ctest's status. The CLI tests spawn this build's snee
# and snee-mpi, so those run sanitized too. Extra arguments go to ctest (e.g. -R Furnace).
#
#   bash scripts/sanitize.sh [--ci] [CTEST_ARGUMENT ...]
#
# --ci is the part that fits CI's budget (.ci/README.md): every layer's tests, the CLI's
# included, less the long statistical ones, which run the code of shorter tests many times over
# (samples, parameters) and would take a minute or more each sanitized: the executables
# test_snee_render and test_snee_smooth_shading are not built (tests/CMakeLists.txt's
# snee_tests_scheduler_ci leaves them out) and the tests named in long_tests below are not run.
# ctest runs one more test than there are cores: the MPI tests spend most of their time waiting
# (for a timeout, a stopped rank, mpirun), and the cores work meanwhile.
#
# The benchmarks are not built: their smoke runs exercise nothing the tests do not, and their
# build would add minutes to CI.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

for tool in clang clang++; do
  if ! command -v "$tool" >/dev/null; then
    echo "error: $tool not found (bash scripts/setup.sh installs it)" >&2
    exit 1
  fi
done

targets=(all)
ctest_scope=()
simd_modules="avx2;avx512"
if [[ ${1:-} == --ci ]]; then
  shift
  # Only the SIMD modules this machine runs (each is the kernels and scheduler compiled once
  # more; one it cannot load is only compiled, which the Release build does already). The
  # probe calls the program's own cpu_runs (kernels/simd/simd_level.h), built by the same clang.
  probe=$(mktemp -d)
  cat >"$probe/levels.cpp" <<'PROBE'
#include <cstdio>
#include "kernels/simd/simd_level.h"
int main() {
  const char* separator = "";
  for (const snee::SimdLevel level : {snee::SimdLevel::kAvx2, snee::SimdLevel::kAvx512}) {
    if (!snee::cpu_runs(level)) continue;
    std::printf("%s%s", separator, snee::simd_level_name(level).data());
    separator = ";";
  }
}
PROBE
  clang++ -std=c++20 -march=x86-64-v2 -I. "$probe/levels.cpp" -o "$probe/levels"
  simd_modules=$("$probe/levels")
  rm -rf "$probe"
  echo "sanitized SIMD modules: ${simd_modules:-none} (those this CPU runs)" >&2
  targets=(snee_tests_scene snee_tests_physics snee_tests_kernels snee_tests_scheduler_ci
    snee_tests_cli)
  # Renders: the bunny furnace at 4096 spp (FurnaceCrossing.BunnyPathsCross... runs the same
  # code at 1024), several media (Schedules.MixedMedia... mixes them in one chunk), the smooth
  # icosphere against the sphere (its diffuse twin and the furnaces run smooth shading), tiny
  # roughness against smooth (the rough and smooth interfaces are rendered by many others).
  long_tests='FurnaceCrossing\.BunnyGrazingRaysDoNotExitWithoutEntering'
  long_tests+='|SeveralMedia\.EachObjectRendersAsItDoesAlone'
  long_tests+='|SmoothShading\.TranslucentIcosphereRendersLikeTheSphere'
  long_tests+='|TinyRoughness\.PtAndSneeAgreeWithSmoothAcrossTheThreshold'
  # SNEE's half-space estimator at more parameters: its rough and smooth, cone and directional
  # cases stay (SneeHalfSpace.CaseA...004Cone, CaseB..., CaseC..., CaseD...).
  long_tests+='|SneeHalfSpace\.(CaseARough02Cone|RoughToSmoothLimit|ConeToDirectionalLimit)'
  # Chi-square and integration runs of samplers whose shorter tests stay
  # (RoughDielectric.SampleMatchesEvalAndPdf, Ggx.*FollowPdf, Lights.ConeIrradiance).
  long_tests+='|RoughDielectric\.SamplesFollowPdf|Ggx\.SmithG1PreservesProjectedArea'
  long_tests+='|Lights\.ConeChi2'
  # Tests of executables this build skipped are registered as <target>_NOT_BUILT.
  ctest_scope=(-E "_NOT_BUILT\$|^($long_tests)\$")
fi

# Clang, the sanitizers' home compiler: on 2 cores, against GCC 12 on the same targets
# (.ci/README.md), its instrumented build took less time and its tests 323 s instead of 555.
# The Release build stays GCC's, and a second compiler's warnings (as errors) are checked.
if [[ -f build-asan/CMakeCache.txt ]] &&
  ! grep -q '^CMAKE_CXX_COMPILER:FILEPATH=.*clang++' build-asan/CMakeCache.txt; then
  rm -rf build-asan  # configured by another compiler, which CMake cannot change in place
fi
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# -O1 instead of Release's -O3: the instrumented build compiles 2 to 5 times faster (85 s of
# CPU down to 18 s for the heaviest kernel file) and the tests still take seconds.
CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DSNEE_SANITIZE=address,undefined -DSNEE_BUILD_BENCHMARKS=OFF \
  -DSNEE_SIMD_MODULES="$simd_modules" "${launcher[@]}" \
  --log-level=WARNING >/dev/null
cmake --build build-asan -j"$(nproc)" --target "${targets[@]}"

# Undefined behaviour aborts already (-fno-sanitize-recover); the stack makes it readable.
# Leaks are checked, except what tests/sanitizer/lsan.supp lists with its reason.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1}
lsan_default=suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0
export LSAN_OPTIONS=${LSAN_OPTIONS:-$lsan_default}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
# The MPI tests run with leak checking off (tests/CMakeLists.txt says why).
ctest --test-dir build-asan --output-on-failure -j"$(($(nproc) + 1))" "${ctest_scope[@]}" "$@"
