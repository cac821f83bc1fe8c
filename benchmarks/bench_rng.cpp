// Philox4x32-10 random blocks: Random123's scalar generator against the batched one, one block
// of four numbers per path slot.
#include <benchmark/benchmark.h>

#include "benchmarks/bench_inputs.h"
#include "kernels/simd/philox_batch.h"

namespace snee {
namespace {

void BM_RandomBlockScalar(benchmark::State& state) {
  std::vector<float> out[4];
  for (auto& o : out) o.resize(bench::kItems);
  uint32_t event = 0;
  for (auto _ : state) {
    for (uint32_t i = 0; i < bench::kItems; ++i) {
      const RandomBlock r = random_block(1, i, 7, event, RngPurpose::kFreeFlight);
      for (size_t w = 0; w < 4; ++w) out[w][i] = r.u[w];
    }
    ++event;
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_RandomBlockScalar);

void BM_RandomBlockSimd(benchmark::State& state) {
  std::vector<float> out[4];
  for (auto& o : out) o.resize(bench::kItems);
  const simd::UintBatch lanes = simd::lane_index();
  uint32_t event = 0;
  for (auto _ : state) {
    for (uint32_t i = 0; i < bench::kItems; i += simd::kLanes) {
      const simd::RandomBlockBatch r =
          simd::random_block(1, simd::UintBatch(i) + lanes, simd::UintBatch(7u),
                             simd::UintBatch(event), RngPurpose::kFreeFlight);
      for (size_t w = 0; w < 4; ++w) r.u[w].store_unaligned(out[w].data() + i);
    }
    ++event;
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_RandomBlockSimd);

}  // namespace
}  // namespace snee
