// Inputs shared by the micro-benchmarks: every benchmark processes one queue's worth of items
// per iteration, with random numbers drawn before timing starts.
#pragma once

#include <cstddef>
#include <random>
#include <vector>

namespace snee::bench {

// Items per iteration: a large queue (the renderer's default unit holds 256 slots; this many
// keeps the per-iteration overhead out of the per-item figures).
inline constexpr size_t kItems = 4096;

// n uniform numbers in [0, 1), reproducible per seed.
inline std::vector<float> uniforms(size_t n, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> u(n);
  for (float& x : u) x = unit(engine);
  return u;
}

}  // namespace snee::bench
