// The entry point of a SIMD module (simd_backend.h): the kernels and scheduler built for a wider
// level than the program's, loaded by simd_dispatch.cpp. Never part of the program itself.
#include "scheduler/simd_backend.h"

extern "C" __attribute__((visibility("default"))) const snee::SimdBackend* snee_simd_backend() {
  return &snee::compiled_backend();
}
