// What `snee bench` reports for one workload: the measured runs (schedule x threads x SIMD
// level) with the
// figures derived from them, as a table for people and as JSON for scripts and CI.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/bench_workloads.h"
#include "apps/measure_render.h"
#include "benchmarks/embree_throughput.h"

namespace snee {

struct BenchRun {
  std::string schedule;
  int threads = 0;
  int queue_capacity = 0;  // path slots per work unit (1 for the megakernel)
  SimdLevel simd = SimdLevel::kSse42;
  Measurement measurement;
};

struct BenchResult {
  const BenchWorkload* workload = nullptr;
  int spp = 0;
  size_t triangles = 0;
  EmbreeThroughput raw;  // the traversal limit on the same geometry
  std::vector<BenchRun> runs;
  // The levels --simd gave, in its order; speed-ups per width are against the first. Empty
  // without --simd: each schedule ran at its default level, and every speed-up is 1.
  std::vector<SimdLevel> simd_levels;
};

void print_bench_result(std::FILE* out, const BenchResult& result);
nlohmann::ordered_json bench_result_json(const BenchResult& result);

}  // namespace snee
