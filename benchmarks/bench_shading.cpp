// Henyey-Greenstein phase sampling and evaluation, Fresnel reflectance, and dielectric BSDF
// sampling, one queue of lanes per iteration; phase evaluation and Fresnel also batched.
#include <benchmark/benchmark.h>

#include "benchmarks/bench_inputs.h"
#include "kernels/bsdf/dielectric.h"
#include "kernels/bsdf/fresnel.h"
#include "kernels/medium/henyey_greenstein.h"
#include "kernels/simd/fresnel_batch.h"
#include "kernels/simd/hg_phase_batch.h"

namespace snee {
namespace {

using simd::FloatBatch;

constexpr float kG = 0.7f;  // forward-scattering medium
const Vec3 kWo = normalize(Vec3(0.3f, -0.2f, 0.9f));

void BM_HgSample(benchmark::State& state) {
  const std::vector<float> u0 = bench::uniforms(bench::kItems, 1),
                           u1 = bench::uniforms(bench::kItems, 2);
  std::vector<Vec3> out(bench::kItems);
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; ++i) {
      float pdf;
      out[i] = hg_sample(kWo, kG, {u0[i], u1[i]}, &pdf);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_HgSample);

// cos_theta in [-1, 1) per lane.
std::vector<float> cosines() {
  std::vector<float> c = bench::uniforms(bench::kItems, 3);
  for (float& x : c) x = 2.0f * x - 1.0f;
  return c;
}

void BM_HgPhaseScalar(benchmark::State& state) {
  const std::vector<float> mu = cosines();
  std::vector<float> out(bench::kItems);
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; ++i) out[i] = hg_phase(mu[i], kG);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_HgPhaseScalar);

void BM_HgPhaseSimd(benchmark::State& state) {
  const std::vector<float> mu = cosines();
  std::vector<float> out(bench::kItems);
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; i += simd::kLanes)
      simd::hg_phase(FloatBatch::load_unaligned(mu.data() + i), FloatBatch(kG))
          .store_unaligned(out.data() + i);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_HgPhaseSimd);

// Both sides of the interface: eta 1.5 from outside, 1 / 1.5 from inside (with TIR).
constexpr float kEta[2] = {1.5f, 1.0f / 1.5f};

void BM_FresnelScalar(benchmark::State& state) {
  const std::vector<float> c = bench::uniforms(bench::kItems, 4);
  std::vector<float> out(bench::kItems);
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; ++i) out[i] = fresnel_dielectric(c[i], kEta[i & 1]);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_FresnelScalar);

void BM_FresnelSimd(benchmark::State& state) {
  const std::vector<float> c = bench::uniforms(bench::kItems, 4);
  std::vector<float> eta(bench::kItems), out(bench::kItems);
  for (size_t i = 0; i < bench::kItems; ++i) eta[i] = kEta[i & 1];
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; i += simd::kLanes)
      simd::fresnel_dielectric(FloatBatch::load_unaligned(c.data() + i),
                               FloatBatch::load_unaligned(eta.data() + i))
          .store_unaligned(out.data() + i);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_FresnelSimd);

// Argument: GGX roughness alpha in hundredths (0 = smooth interface).
void BM_DielectricSample(benchmark::State& state) {
  const DielectricParams p{1.5f, static_cast<float>(state.range(0)) / 100.0f};
  const std::vector<float> u0 = bench::uniforms(bench::kItems, 5),
                           u1 = bench::uniforms(bench::kItems, 6),
                           lobe = bench::uniforms(bench::kItems, 7);
  std::vector<BsdfSample> out(bench::kItems);
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; ++i)
      out[i] = dielectric_sample(p, kWo, {u0[i], u1[i]}, lobe[i]);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_DielectricSample)->Arg(0)->Arg(20);

}  // namespace
}  // namespace snee
