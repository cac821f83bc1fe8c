// The SNEE subdivision samplers at a fixed exit point of the analytic half-space of
// tests/test_snee_halfspace.cpp (medium z < 0, x_i 0.4 below the plane, one cone light).
// Argument: GGX roughness of the interface in hundredths (0 = smooth).
#include <benchmark/benchmark.h>

#include <array>

#include "benchmarks/bench_inputs.h"
#include "kernels/physics/snee/snee_strategies.h"

namespace snee {
namespace {

template <int Dimensions, typename Sampler>
void run_sampler(benchmark::State& state, Sampler sampler) {
  const Scene scene = bench::cone_light_scene();
  const LightTable lights(scene);
  const SneeOrigin origin{Vec3(0, 0, -0.4f), normalize(Vec3(0.3f, -0.1f, 1.0f))};
  const SneeMedium medium{Rgb(1.0f), Rgb(1.2f), 0.0f};
  const ExitPoint exit{Vec3(0.15f, -0.05f, 0.0f),
                       Vec3(0, 0, 1),
                       Vec3(0, 0, 1),
                       {1.5f, static_cast<float>(state.range(0)) / 100.0f}};
  const SneeOptions options;
  const std::vector<float> u = bench::uniforms(bench::kItems * Dimensions, 1);
  double sum = 0;
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; ++i) {
      const std::span<const float, Dimensions> ui(u.data() + i * Dimensions, Dimensions);
      const SneeCandidate c = sampler(origin, medium, exit, lights, options, 1e-4f, ui);
      if (c.valid) sum += c.contribution.x;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}

void BM_SneeTopToBottom(benchmark::State& state) {
  run_sampler<kTopToBottomDimensions>(state, sample_top_to_bottom);
}
BENCHMARK(BM_SneeTopToBottom)->Arg(0)->Arg(20);

void BM_SneeBottomToTop(benchmark::State& state) {
  run_sampler<kBottomToTopDimensions>(state, sample_bottom_to_top);
}
BENCHMARK(BM_SneeBottomToTop)->Arg(0)->Arg(20);

}  // namespace
}  // namespace snee
