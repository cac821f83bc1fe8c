// The subdivision stage's weighing of a batch of proposals: suffix_weighing.h's templates over
// the float batch (the densities of the four strategies that can produce each lane's suffix,
// their MIS weight and the integrand), and the gathering of the proposals into lanes. A lane
// whose densities or integrand leave float's range is flagged, and the caller weighs it with the
// double finish_proposal instead. Agreement with the double instantiation is measured in
// tests/test_snee_batch.cpp and stated in README.md.
#pragma once

#include <array>
#include <cmath>

#include "kernels/physics/snee/snee_strategies.h"
#include "kernels/physics/snee/suffix_weighing.h"
#include "kernels/simd/dielectric_batch.h"
#include "kernels/simd/free_flight_batch.h"
#include "kernels/simd/hg_sample_batch.h"
#include "kernels/simd/slot_chunk.h"

namespace snee::simd {

// A batch of suffixes x_i -> x_j -> x_k -> light, all producible by SNEE (every suffix a
// subdivision strategy proposes is: x_i and x_j are medium vertices and x_k is the probe's
// first hit).
using SuffixBatch = SuffixLanes<FloatBatch>;
using SuffixWeighingBatch = SuffixWeighing<FloatBatch>;
using snee::weigh_suffix;

// The strategies that compete for the suffixes a subdivision strategy proposes: the enabled ones.
inline MisWeights<FloatBatch>::Competing enabled_strategies(const SneeOptions& options) {
  MisWeights<FloatBatch>::Competing competing;
  for (int t = 0; t < kStrategyCount; ++t)
    competing[t] = options.enabled.contains(static_cast<Strategy>(t));
  return competing;
}

// The suffixes of proposals [k, k + count) of a structure of arrays with the fields of
// SNEE_PROPOSAL_FIELDS (kernels/wavefront/work_items.h), in lanes; the padding lanes repeat the
// first.
template <class Proposals>
SuffixBatch load_suffixes(const Proposals& q, size_t k, size_t count) {
  const auto lanes = [&](const auto& a) { return load_padded(a.data() + k, count); };
  const auto vec = [&](const auto& x, const auto& y, const auto& z) {
    return Vec3Batch{lanes(x), lanes(y), lanes(z)};
  };
  const FloatBatch zero(0.0f);
  return {vec(q.xi_x, q.xi_y, q.xi_z),
          vec(q.win_x, q.win_y, q.win_z),
          vec(q.xj_x, q.xj_y, q.xj_z),
          vec(q.xk_x, q.xk_y, q.xk_z),
          vec(q.nk_x, q.nk_y, q.nk_z),
          vec(q.snk_x, q.snk_y, q.snk_z),
          vec(q.wo_x, q.wo_y, q.wo_z),
          vec(q.sigma_s_x, q.sigma_s_y, q.sigma_s_z),
          vec(q.sigma_t_x, q.sigma_t_y, q.sigma_t_z),
          lanes(q.g),
          {lanes(q.eta), lanes(q.alpha)},
          lanes(q.light_pdf),
          lanes(q.light_delta) != zero,
          lanes(q.light_distant) != zero};
}

// What finish_proposal computes, for a batch of proposals: the MIS weight of each lane's own
// strategy and the contribution w_s F / p_s. `in_range` is false where a density or the
// integrand left float's range; such a lane must be weighed by finish_proposal.
struct ProposalWeights {
  float weight[kLanes];
  Rgb contribution[kLanes];
  bool in_range[kLanes];
};

// The proposals [k, k + count) of q (as load_suffixes), 1 <= count <= kLanes, each weighed for
// its own strategy.
template <class Proposals>
ProposalWeights weigh_proposals(const Proposals& q, size_t k, size_t count,
                                const SneeOptions& options) {
  const SuffixWeighingBatch w = weigh_suffix(load_suffixes(q, k, count), options);
  alignas(64) float weight[2][kLanes], attenuation[3][kLanes], path[kLanes], pdf_sum[kLanes];
  const MisWeights<FloatBatch> mis(w.pdf, enabled_strategies(options), options.heuristic);
  mis(Strategy::kTopToBottom).store_aligned(weight[0]);
  mis(Strategy::kBottomToTop).store_aligned(weight[1]);
  w.attenuation.x.store_aligned(attenuation[0]);
  w.attenuation.y.store_aligned(attenuation[1]);
  w.attenuation.z.store_aligned(attenuation[2]);
  w.path.store_aligned(path);
  (w.pdf[0] + w.pdf[1] + w.pdf[2] + w.pdf[3]).store_aligned(pdf_sum);
  ProposalWeights out;
  for (size_t l = 0; l < count; ++l) {
    const size_t i = k + l;
    const bool top_to_bottom = q.strategy[i] == static_cast<uint32_t>(Strategy::kTopToBottom);
    const float wl = weight[top_to_bottom ? 0 : 1][l];
    const Rgb emitted(q.emitted_r[i], q.emitted_g[i], q.emitted_b[i]);
    const Rgb f = Rgb(attenuation[0][l], attenuation[1][l], attenuation[2][l]) * emitted * path[l];
    out.weight[l] = wl;
    out.contribution[l] = f * static_cast<float>(wl / q.sampling_pdf[i]);
    out.in_range[l] = std::isfinite(pdf_sum[l]) && std::isfinite(wl) && std::isfinite(path[l]);
  }
  return out;
}

}  // namespace snee::simd
