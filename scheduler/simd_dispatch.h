// Which SIMD level renders: render() (render.h) runs the kernels built for
// RenderOptions::simd, or for default_simd_level() when it is unset. A level
// can be used when the CPU runs it (kernels/simd/simd_level.h) and its kernels are in this
// program (the build's own level) or in a module found beside it (simd_backend.h). Images are
// bitwise identical at every level, so the choice changes only the speed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "kernels/simd/simd_level.h"
#include "scheduler/simd_backend.h"

namespace snee {

// One level's standing in this process.
struct SimdLevelStatus {
  SimdLevel level = SimdLevel::kSse42;
  bool usable = false;
  // Why it is usable ("built in", "module /path/snee-simd-avx2.so") or not ("this CPU lacks
  // it", "not built: ...", "module ...: <loader error>").
  std::string detail;
};

// A level's module looked for in `directories`, in order: the first file of its name
// (snee-simd-avx2.so, snee-simd-avx512.so) is loaded and checked; the backend is null unless it
// is a module of this very build. Loads code: call it only for a level the CPU runs.
struct SimdModule {
  SimdLevelStatus status;
  const SimdBackend* backend = nullptr;
};
SimdModule load_simd_module(SimdLevel level, const std::vector<std::filesystem::path>& directories);

// Every level, narrowest first. Modules are loaded on the first call, only for levels the CPU
// runs (a module's code must never run where the CPU lacks its instructions).
const std::vector<SimdLevelStatus>& simd_levels();

// Whether this build made the module of a level wider than its own (SNEE_SIMD_DISPATCH, for the
// levels in SNEE_SIMD_MODULES); false for the level the program itself is built for.
bool simd_module_built(SimdLevel level);

// The widest usable level.
SimdLevel widest_simd_level();

// The level a render runs when RenderOptions::simd is unset: the widest usable one for the
// wavefront schedules, the build's own (the narrowest) for the megakernel, whose one-path
// batches compute every lane for a single slot, so that a wider batch is only more work
// (0.70-0.79x the SSE4.2 rate at AVX-512, docs/performance.md "SIMD levels").
SimdLevel default_simd_level(const std::string& schedule);

// The backend of a level; throws std::invalid_argument naming the level and why it cannot be
// used, with the levels that can.
const SimdBackend& simd_backend(SimdLevel level);

// "avx512 (16 float lanes)".
std::string simd_level_description(SimdLevel level);

}  // namespace snee
