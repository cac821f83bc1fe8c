// Queue routing after a trace, as kernels/stages/extend.cpp does it: every slot of one queue goes,
// in slot order, to the medium, surface or escaped queue (a stable compaction by push). The kernels
// have no separate prefix-sum compaction, so this is the compaction that runs.
#include <benchmark/benchmark.h>

#include <random>

#include "benchmarks/bench_inputs.h"
#include "kernels/wavefront/queues.h"

namespace snee {
namespace {

void BM_QueueRouting(benchmark::State& state) {
  // A third of the rays in a medium, half of the others hitting a surface.
  std::mt19937 engine(1);
  std::vector<int32_t> medium(bench::kItems);
  std::vector<uint32_t> geom(bench::kItems);
  SlotQueue in(bench::kItems), to_medium(bench::kItems), to_surface(bench::kItems),
      to_escaped(bench::kItems);
  for (uint32_t s = 0; s < bench::kItems; ++s) {
    medium[s] = engine() % 3 == 0 ? 0 : -1;
    geom[s] = engine() % 2 == 0 ? 1u : kInvalidId;
    in.push(s);
  }
  for (auto _ : state) {
    to_medium.clear();
    to_surface.clear();
    to_escaped.clear();
    for (const uint32_t s : in) {
      if (medium[s] >= 0) {
        to_medium.push(s);
      } else if (geom[s] != kInvalidId) {
        to_surface.push(s);
      } else {
        to_escaped.push(s);
      }
    }
    benchmark::DoNotOptimize(to_escaped.size());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_QueueRouting);

}  // namespace
}  // namespace snee
