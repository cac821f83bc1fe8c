// What a build of the kernels at one SIMD level offers the dispatcher (simd_dispatch.h): the
// render entry point compiled for that level. The baseline level's backend is linked into every
// program; the wider ones are shared modules (snee-simd-avx2.so, snee-simd-avx512.so) built
// from the same sources with another -march, which export only snee_simd_backend() and keep
// everything else, their copies of inline functions and templates included, to themselves, so
// code compiled for a wider level never runs where the dispatcher did not choose it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "kernels/simd/simd_level.h"
#include "scheduler/render.h"

namespace snee {

// Bumped whenever SimdBackend or what its render takes changes meaning.
inline constexpr uint32_t kSimdBackendInterface = 1;

// Sizes of the types that cross between the program and a module; a module whose layout differs
// (built from other sources) is refused rather than called.
constexpr uint64_t simd_backend_layout() {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const uint64_t size : {sizeof(Scene), sizeof(RenderOptions), sizeof(RenderHooks),
                              sizeof(RenderResult), sizeof(RenderStats), sizeof(FilmState),
                              sizeof(Film), alignof(Scene), alignof(RenderResult)}) {
    h ^= size;
    h *= 0x100000001b3ull;
  }
  return h;
}

using RenderEntry = RenderResult (*)(const Scene&, const RenderOptions&, const RenderHooks&,
                                     const FilmState*);

struct SimdBackend {
  uint32_t interface = kSimdBackendInterface;
  uint64_t layout = simd_backend_layout();
  const char* version = SNEE_VERSION;
  SimdLevel level = kCompiledSimdLevel;
  RenderEntry render = nullptr;
};

// The backend of this compilation (render.cpp), at kCompiledSimdLevel: the program's built-in
// one, and what a module's snee_simd_backend() returns.
const SimdBackend& compiled_backend();

}  // namespace snee

// The one symbol a SIMD module exports (simd_module.cpp).
extern "C" const snee::SimdBackend* snee_simd_backend();
