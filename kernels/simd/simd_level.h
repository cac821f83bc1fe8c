// The x86 instruction sets snee's kernels are built for, and which of them this CPU runs. A
// build compiles its kernels for one of them (arch.h); the scheduler loads the wider ones at
// run time (scheduler/simd_dispatch.h).
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <type_traits>

#include "kernels/simd/arch.h"

namespace snee {

// Narrowest first. Each is an x86-64 micro-architecture level (-march=x86-64-v2, -v3, -v4).
enum class SimdLevel { kSse42, kAvx2, kAvx512 };
inline constexpr SimdLevel kSimdLevels[] = {SimdLevel::kSse42, SimdLevel::kAvx2,
                                            SimdLevel::kAvx512};

constexpr std::string_view simd_level_name(SimdLevel level) {
  switch (level) {
    case SimdLevel::kSse42:
      return "sse4.2";
    case SimdLevel::kAvx2:
      return "avx2";
    case SimdLevel::kAvx512:
      return "avx512";
  }
  return "?";
}

inline std::optional<SimdLevel> parse_simd_level(std::string_view name) {
  for (const SimdLevel level : kSimdLevels)
    if (simd_level_name(level) == name) return level;
  return std::nullopt;
}

// Float lanes of one batch at that level.
constexpr size_t simd_level_lanes(SimdLevel level) {
  return level == SimdLevel::kSse42 ? 4 : level == SimdLevel::kAvx2 ? 8 : 16;
}

// Whether this CPU, and the OS's saving of its registers, run code built for the level: every
// instruction set of its x86-64 level (AVX-512 F, BW, CD, DQ and VL; AVX2 with FMA, BMI and
// F16C; SSE4.2 with POPCNT), as the compiler's runtime reads them from CPUID and XGETBV.
inline bool cpu_runs(SimdLevel level) {
  __builtin_cpu_init();
#if defined(__clang__) && __clang_major__ < 16
  // Clang before 16 knows no level names (the sanitized CI build uses clang 14); the
  // instruction sets that set the levels apart, each a superset of the one below.
  const bool sse42 = __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("popcnt");
  const bool avx2 = sse42 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                    __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
  const bool avx512 = avx2 && __builtin_cpu_supports("avx512f") &&
                      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512cd") &&
                      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
  switch (level) {
    case SimdLevel::kSse42:
      return sse42;
    case SimdLevel::kAvx2:
      return avx2;
    case SimdLevel::kAvx512:
      return avx512;
  }
#else
  switch (level) {
    case SimdLevel::kSse42:
      return __builtin_cpu_supports("x86-64-v2");
    case SimdLevel::kAvx2:
      return __builtin_cpu_supports("x86-64-v3");
    case SimdLevel::kAvx512:
      return __builtin_cpu_supports("x86-64-v4");
  }
#endif
  return false;
}

// The level this translation unit's batches are compiled for.
inline constexpr SimdLevel kCompiledSimdLevel =
    std::is_base_of_v<xsimd::avx512f, simd::Arch> ? SimdLevel::kAvx512
    : std::is_base_of_v<xsimd::avx2, simd::Arch>  ? SimdLevel::kAvx2
                                                  : SimdLevel::kSse42;
static_assert(simd_level_lanes(kCompiledSimdLevel) == simd::kLanes);

}  // namespace snee
