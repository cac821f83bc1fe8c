// Henyey-Greenstein phase sampling and evaluation, Fresnel reflectance and dielectric BSDF
// sampling, one queue of lanes per iteration, each in scalar and batched (SIMD) form.
#include <benchmark/benchmark.h>

#include "benchmarks/bench_inputs.h"
#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/simd/dielectric_batch.h"
#include "kernels/simd/hg_sample_batch.h"

namespace snee {
namespace {

using simd::FloatBatch;

constexpr float kG = 0.7f;  // forward-scattering medium
const Vec3 kWo = normalize(Vec3(0.3f, -0.2f, 0.9f));

void BM_HgSampleScalar(benchmark::State& state) {
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
BENCHMARK(BM_HgSampleScalar);

void BM_HgSampleSimd(benchmark::State& state) {
  const std::vector<float> u0 = bench::uniforms(bench::kItems, 1),
                           u1 = bench::uniforms(bench::kItems, 2);
  std::vector<float> x(bench::kItems), y(bench::kItems), z(bench::kItems);
  const simd::Vec3Batch wo{FloatBatch(kWo.x), FloatBatch(kWo.y), FloatBatch(kWo.z)};
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; i += simd::kLanes) {
      const simd::HgSampleBatch s =
          simd::hg_sample(wo, FloatBatch(kG), FloatBatch::load_unaligned(u0.data() + i),
                          FloatBatch::load_unaligned(u1.data() + i));
      s.direction.x.store_unaligned(x.data() + i);
      s.direction.y.store_unaligned(y.data() + i);
      s.direction.z.store_unaligned(z.data() + i);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_HgSampleSimd);

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
      hg_phase(FloatBatch::load_unaligned(mu.data() + i), FloatBatch(kG))
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
      fresnel_dielectric(FloatBatch::load_unaligned(c.data() + i),
                         FloatBatch::load_unaligned(eta.data() + i))
          .store_unaligned(out.data() + i);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_FresnelSimd);

// Argument: GGX roughness alpha in hundredths (0 = smooth interface).
void BM_DielectricSampleScalar(benchmark::State& state) {
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
BENCHMARK(BM_DielectricSampleScalar)->Arg(0)->Arg(20);

void BM_DielectricSampleSimd(benchmark::State& state) {
  const simd::DielectricLanes p{FloatBatch(1.5f),
                                FloatBatch(static_cast<float>(state.range(0)) / 100.0f)};
  const std::vector<float> u0 = bench::uniforms(bench::kItems, 5),
                           u1 = bench::uniforms(bench::kItems, 6),
                           lobe = bench::uniforms(bench::kItems, 7);
  std::vector<float> f(bench::kItems), pdf(bench::kItems);
  const simd::Vec3Batch wo{FloatBatch(kWo.x), FloatBatch(kWo.y), FloatBatch(kWo.z)};
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; i += simd::kLanes) {
      const simd::BsdfSampleBatch s = simd::dielectric_sample(
          p, wo, FloatBatch::load_unaligned(u0.data() + i),
          FloatBatch::load_unaligned(u1.data() + i), FloatBatch::load_unaligned(lobe.data() + i));
      s.f.store_unaligned(f.data() + i);
      s.pdf.store_unaligned(pdf.data() + i);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_DielectricSampleSimd)->Arg(0)->Arg(20);

}  // namespace
}  // namespace snee
