// Free-flight distance sampling with its pdf and transmittance over one queue of lanes, each
// lane with its own medium: the scalar functions against the batched ones (xsimd exp/log1p).
#include <benchmark/benchmark.h>

#include "benchmarks/bench_inputs.h"
#include "kernels/physics/medium/free_flight.h"
#include "kernels/simd/free_flight_batch.h"

namespace snee {
namespace {

struct FlightInputs {
  FlightInputs()
      : sigma_r(bench::uniforms(bench::kItems, 1)),
        sigma_g(bench::uniforms(bench::kItems, 2)),
        sigma_b(bench::uniforms(bench::kItems, 3)),
        u_channel(bench::uniforms(bench::kItems, 4)),
        u(bench::uniforms(bench::kItems, 5)),
        t(bench::kItems),
        pdf(bench::kItems),
        tr_r(bench::kItems),
        tr_g(bench::kItems),
        tr_b(bench::kItems) {
    for (auto* sigma : {&sigma_r, &sigma_g, &sigma_b})
      for (float& s : *sigma) s = 0.5f + 20.0f * s;  // extinction of dense media, per mm
  }
  std::vector<float> sigma_r, sigma_g, sigma_b, u_channel, u;
  std::vector<float> t, pdf, tr_r, tr_g, tr_b;
};

void BM_FreeFlightScalar(benchmark::State& state) {
  FlightInputs in;
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; ++i) {
      const Rgb sigma_t(in.sigma_r[i], in.sigma_g[i], in.sigma_b[i]);
      const float t = free_flight_sample(sigma_t, in.u_channel[i], in.u[i]);
      const Rgb tr = transmittance(sigma_t, t);
      in.t[i] = t;
      in.pdf[i] = free_flight_pdf(sigma_t, t);
      in.tr_r[i] = tr.x;
      in.tr_g[i] = tr.y;
      in.tr_b[i] = tr.z;
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_FreeFlightScalar);

void BM_FreeFlightSimd(benchmark::State& state) {
  using simd::FloatBatch;
  FlightInputs in;
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; i += simd::kLanes) {
      const simd::Vec3Batch sigma_t{FloatBatch::load_unaligned(in.sigma_r.data() + i),
                                    FloatBatch::load_unaligned(in.sigma_g.data() + i),
                                    FloatBatch::load_unaligned(in.sigma_b.data() + i)};
      const FloatBatch t =
          simd::free_flight_sample(sigma_t, FloatBatch::load_unaligned(in.u_channel.data() + i),
                                   FloatBatch::load_unaligned(in.u.data() + i));
      const simd::Vec3Batch tr = simd::transmittance(sigma_t, t);
      t.store_unaligned(in.t.data() + i);
      simd::free_flight_pdf(sigma_t, t).store_unaligned(in.pdf.data() + i);
      tr.x.store_unaligned(in.tr_r.data() + i);
      tr.y.store_unaligned(in.tr_g.data() + i);
      tr.z.store_unaligned(in.tr_b.data() + i);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_FreeFlightSimd);

}  // namespace
}  // namespace snee
