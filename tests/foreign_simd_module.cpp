// A SIMD module of another build (tests/test_simd_dispatch.cpp): the right entry point with a
// different type layout, which the dispatcher must refuse rather than call.
#include "scheduler/simd_backend.h"

extern "C" __attribute__((visibility("default"))) const snee::SimdBackend* snee_simd_backend() {
  static const snee::SimdBackend backend{.layout = snee::simd_backend_layout() + 1,
                                         .level = snee::SimdLevel::kAvx2,
                                         .render = nullptr};
  return &backend;
}
