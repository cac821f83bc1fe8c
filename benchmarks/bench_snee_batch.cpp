// SNEE subdivision in scalar and SIMD form on the same exits: random medium vertices under the
// plane z = 0 of a half-space medium, exit points on the plane, one cone light. Each pair does
// the same work per exit as the subdivision stage: top-to-bottom's light sample (per exit in
// both forms), refraction, distance and density; bottom-to-top's placement, refraction,
// density and light lookup; and the weighing (four-way pdfs, MIS weight, integrand) of
// top-to-bottom proposals. Argument: GGX roughness of the interface in hundredths (0 = smooth).
#include <benchmark/benchmark.h>

#include <array>
#include <vector>

#include "benchmarks/bench_inputs.h"
#include "kernels/physics/snee/snee_strategies.h"
#include "kernels/physics/snee/subdivision_vertices.h"
#include "kernels/simd/snee_weights_batch.h"
#include "kernels/wavefront/subdivision_scratch.h"

namespace snee {
namespace {

struct Exits {
  explicit Exits(float alpha) : lights(bench::cone_light_scene()) {
    interface = {1.5f, alpha};
    const std::vector<float> r = bench::uniforms(bench::kItems * 7, 2);
    for (size_t i = 0; i < bench::kItems; ++i) {
      const float* q = r.data() + 7 * i;
      origins[i] = {Vec3(0.3f * q[0], 0.3f * q[1], -0.05f - 0.6f * q[2]),
                    sample_uniform_sphere(Vec2{q[3], q[4]})};
      exits[i] = {Vec3(2 * q[5] - 1, 2 * q[6] - 1, 0.0f), Vec3(0, 0, 1), Vec3(0, 0, 1), interface};
    }
    u = bench::uniforms(bench::kItems * 16, 3);
  }
  const float* u_of(size_t i) const { return u.data() + 16 * i; }
  simd::Vec3Batch vector(size_t k, Vec3 (*of)(const Exits&, size_t)) const {
    alignas(64) float v[3][simd::kLanes];
    for (size_t l = 0; l < simd::kLanes; ++l) {
      const Vec3 x = of(*this, k + l);
      v[0][l] = x.x;
      v[1][l] = x.y;
      v[2][l] = x.z;
    }
    return {simd::FloatBatch::load_aligned(v[0]), simd::FloatBatch::load_aligned(v[1]),
            simd::FloatBatch::load_aligned(v[2])};
  }
  simd::FloatBatch numbers(size_t k, int n) const {
    alignas(64) float v[simd::kLanes];
    for (size_t l = 0; l < simd::kLanes; ++l) v[l] = u_of(k + l)[n];
    return simd::FloatBatch::load_aligned(v);
  }

  LightTable lights;
  SneeMedium medium{Rgb(1.0f, 0.8f, 0.6f), Rgb(1.2f, 1.0f, 0.8f), 0.0f};
  SneeOptions options;
  DielectricParams interface;
  std::array<SneeOrigin, bench::kItems> origins;
  std::array<ExitPoint, bench::kItems> exits;
  std::vector<float> u;
};

Vec3 x_i_of(const Exits& e, size_t i) {
  return e.origins[i].x_i;
}
Vec3 omega_in_of(const Exits& e, size_t i) {
  return e.origins[i].omega_in;
}
Vec3 x_k_of(const Exits& e, size_t i) {
  return e.exits[i].x_k;
}
Vec3 n_k_of(const Exits& e, size_t i) {
  return e.exits[i].n_k;
}
Vec3 ns_k_of(const Exits& e, size_t i) {
  return e.exits[i].ns_k;
}

float alpha_of(const benchmark::State& state) {
  return static_cast<float>(state.range(0)) / 100.0f;
}

void BM_SneeProposeTopToBottomScalar(benchmark::State& state) {
  const Exits e(alpha_of(state));
  double sum = 0;
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; ++i) {
      const SneeProposal p =
          propose_top_to_bottom(e.origins[i], e.medium, e.exits[i], e.lights, e.options, 1e-4f,
                                std::span<const float, kTopToBottomDimensions>(e.u_of(i), 8));
      sum += p.sampling_pdf;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_SneeProposeTopToBottomScalar)->Arg(0)->Arg(20);

simd::Vec3Batch broadcast(Vec3 v) {
  return {simd::FloatBatch(v.x), simd::FloatBatch(v.y), simd::FloatBatch(v.z)};
}

// The stage's form: light samples per exit, the batched part per chunk, then the proposal of
// every exit that sampled.
void BM_SneeProposeTopToBottomSimd(benchmark::State& state) {
  const Exits e(alpha_of(state));
  std::array<LightSample, simd::kLanes> samples;
  const simd::DielectricLanes dielectric{simd::FloatBatch(e.interface.eta),
                                         simd::FloatBatch(e.interface.alpha)};
  double sum = 0;
  for (auto _ : state) {
    for (size_t k = 0; k < bench::kItems; k += simd::kLanes) {
      alignas(64) float w[3][simd::kLanes], pdf[simd::kLanes], delta[simd::kLanes];
      bool lit[simd::kLanes];
      for (size_t l = 0; l < simd::kLanes; ++l) {
        const float* u = e.u_of(k + l);
        const LightSample& s = samples[l] = e.lights.sample(
            e.exits[k + l].x_k, u[TopToBottomRandoms::kLightSelection],
            Vec2{u[TopToBottomRandoms::kLightPoint], u[TopToBottomRandoms::kLightPoint + 1]});
        lit[l] = lights_exit_point(s, e.exits[k + l].n_k, e.exits[k + l].ns_k);
        w[0][l] = s.wi.x;
        w[1][l] = s.wi.y;
        w[2][l] = s.wi.z;
        pdf[l] = s.pdf;
        delta[l] = s.delta ? 1.0f : 0.0f;
      }
      std::array<simd::FloatBatch, kTopToBottomDimensions> u;
      for (int n = 0; n < kTopToBottomDimensions; ++n) u[n] = e.numbers(k, n);
      const TopToBottomVertex<simd::FloatBatch> b = top_to_bottom_vertex<simd::FloatBatch>(
          {e.vector(k, x_i_of),
           e.vector(k, omega_in_of),
           e.vector(k, x_k_of),
           e.vector(k, n_k_of),
           e.vector(k, ns_k_of),
           simd::FloatBatch(e.medium.g),
           broadcast(e.medium.sigma_t),
           dielectric,
           {simd::FloatBatch::load_aligned(w[0]), simd::FloatBatch::load_aligned(w[1]),
            simd::FloatBatch::load_aligned(w[2])},
           simd::FloatBatch::load_aligned(pdf),
           simd::FloatBatch::load_aligned(delta) != simd::FloatBatch(0.0f)},
          e.options, u);
      alignas(64) float x[3][simd::kLanes], p[simd::kLanes], ok[simd::kLanes];
      simd::store_aligned(b.x_j, x[0], x[1], x[2]);
      b.pdf.store_aligned(p);
      xsimd::select(b.distanced, simd::FloatBatch(1.0f), simd::FloatBatch(0.0f)).store_aligned(ok);
      for (size_t l = 0; l < simd::kLanes; ++l) {
        if (!lit[l] || ok[l] == 0) continue;
        const SneeProposal proposal =
            top_to_bottom_proposal(e.origins[k + l], e.medium, e.exits[k + l], samples[l], 1e-4f,
                                   Vec3(x[0][l], x[1][l], x[2][l]), p[l]);
        sum += proposal.sampling_pdf;
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_SneeProposeTopToBottomSimd)->Arg(0)->Arg(20);

void BM_SneeProposeBottomToTopScalar(benchmark::State& state) {
  const Exits e(alpha_of(state));
  double sum = 0;
  for (auto _ : state) {
    for (size_t i = 0; i < bench::kItems; ++i) {
      const SneeProposal p =
          propose_bottom_to_top(e.origins[i], e.medium, e.exits[i], e.lights, e.options, 1e-4f,
                                std::span<const float, kBottomToTopDimensions>(e.u_of(i) + 8, 6));
      sum += p.sampling_pdf;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_SneeProposeBottomToTopScalar)->Arg(0)->Arg(20);

void BM_SneeProposeBottomToTopSimd(benchmark::State& state) {
  const Exits e(alpha_of(state));
  const simd::DielectricLanes dielectric{simd::FloatBatch(e.interface.eta),
                                         simd::FloatBatch(e.interface.alpha)};
  double sum = 0;
  for (auto _ : state) {
    for (size_t k = 0; k < bench::kItems; k += simd::kLanes) {
      std::array<simd::FloatBatch, kBottomToTopDimensions> u;
      for (int n = 0; n < kBottomToTopDimensions; ++n)
        u[n] = e.numbers(k, kTopToBottomDimensions + n);
      const BottomToTopVertex<simd::FloatBatch> b = bottom_to_top_vertex<simd::FloatBatch>(
          {e.vector(k, x_i_of), e.vector(k, omega_in_of), e.vector(k, x_k_of), e.vector(k, n_k_of),
           e.vector(k, ns_k_of), simd::FloatBatch(e.medium.g), dielectric},
          e.options, u);
      alignas(64) float x[3][simd::kLanes], w[3][simd::kLanes], p[simd::kLanes], ok[simd::kLanes];
      simd::store_aligned(b.x_j, x[0], x[1], x[2]);
      simd::store_aligned(b.omega_o, w[0], w[1], w[2]);
      b.pdf.store_aligned(p);
      xsimd::select(b.placed && b.refracted, simd::FloatBatch(1.0f), simd::FloatBatch(0.0f))
          .store_aligned(ok);
      for (size_t l = 0; l < simd::kLanes; ++l) {
        if (ok[l] == 0) continue;
        const SneeProposal proposal = bottom_to_top_proposal(
            e.origins[k + l], e.medium, e.exits[k + l], e.lights, 1e-4f,
            Vec3(x[0][l], x[1][l], x[2][l]), Vec3(w[0][l], w[1][l], w[2][l]), p[l]);
        sum += proposal.sampling_pdf;
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_SneeProposeBottomToTopSimd)->Arg(0)->Arg(20);

// Top-to-bottom proposals that sampled, weighed as the stage weighs them.
std::vector<SneeProposal> proposals_of(const Exits& e) {
  std::vector<SneeProposal> out;
  for (size_t i = 0; out.size() < bench::kItems; i = (i + 1) % bench::kItems) {
    std::vector<float> u = bench::uniforms(8, static_cast<unsigned>(out.size() + 7 * i));
    const SneeProposal p =
        propose_top_to_bottom(e.origins[i], e.medium, e.exits[i], e.lights, e.options, 1e-4f,
                              std::span<const float, kTopToBottomDimensions>(u.data(), 8));
    if (p.failure == SneeFailure::kNone) out.push_back(p);
  }
  return out;
}

void BM_SneeWeighScalar(benchmark::State& state) {
  const Exits e(alpha_of(state));
  const std::vector<SneeProposal> proposals = proposals_of(e);
  double sum = 0;
  for (auto _ : state) {
    for (const SneeProposal& p : proposals)
      sum += finish_proposal(Strategy::kTopToBottom, p, e.options).contribution.x;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(proposals.size()));
}
BENCHMARK(BM_SneeWeighScalar)->Arg(0)->Arg(20);

void BM_SneeWeighSimd(benchmark::State& state) {
  const Exits e(alpha_of(state));
  const std::vector<SneeProposal> proposals = proposals_of(e);
  ProposalQueue queue(proposals.size());
  for (const SneeProposal& p : proposals) queue.push(p, Strategy::kTopToBottom, 0);
  double sum = 0;
  for (auto _ : state) {
    for (size_t k = 0; k < proposals.size(); k += simd::kLanes) {
      const simd::ProposalWeights w =
          simd::weigh_proposals(queue.items(), k, simd::kLanes, e.options);
      for (size_t l = 0; l < simd::kLanes; ++l) sum += w.contribution[l].x;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(proposals.size()));
}
BENCHMARK(BM_SneeWeighSimd)->Arg(0)->Arg(20);

}  // namespace
}  // namespace snee
