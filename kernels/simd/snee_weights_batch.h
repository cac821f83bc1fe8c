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

// Fills a batch from suffix_of(l), the suffix of lane l, for lanes [0, count); the padding
// lanes repeat lane 0.
template <class SuffixOf>
SuffixBatch load_suffixes(SuffixOf&& suffix_of, size_t count) {
  constexpr int kVectors = 9, kFields = 3 * kVectors + 6;
  alignas(64) float f[kFields][kLanes];
  for (size_t l = 0; l < kLanes; ++l) {
    const SneeSuffix& s = suffix_of(l < count ? l : 0);
    const Vec3 v[kVectors] = {s.x_i,     s.omega_in,       s.x_j,           s.x_k, s.n_k, s.ns_k,
                              s.omega_o, s.medium.sigma_s, s.medium.sigma_t};
    for (int i = 0; i < kVectors; ++i) {
      f[3 * i][l] = v[i].x;
      f[3 * i + 1][l] = v[i].y;
      f[3 * i + 2][l] = v[i].z;
    }
    const float scalars[] = {s.medium.g,
                             s.interface.eta,
                             s.interface.alpha,
                             s.light_pdf,
                             s.light_delta ? 1.0f : 0.0f,
                             s.light_distant ? 1.0f : 0.0f};
    for (int i = 0; i < 6; ++i) f[3 * kVectors + i][l] = scalars[i];
  }
  const auto batch = [&](int i) { return FloatBatch::load_aligned(f[i]); };
  const auto vec = [&](int i) {
    return Vec3Batch{batch(3 * i), batch(3 * i + 1), batch(3 * i + 2)};
  };
  const auto flag = [&](int i) { return batch(i) != FloatBatch(0.0f); };
  constexpr int kScalars = 3 * kVectors;
  return {vec(0),
          vec(1),
          vec(2),
          vec(3),
          vec(4),
          vec(5),
          vec(6),
          vec(7),
          vec(8),
          batch(kScalars),
          {batch(kScalars + 1), batch(kScalars + 2)},
          batch(kScalars + 3),
          flag(kScalars + 4),
          flag(kScalars + 5)};
}

// What finish_proposal computes, for a batch of proposals: the MIS weight of each lane's own
// strategy and the contribution w_s F / p_s. `in_range` is false where a density or the
// integrand left float's range; such a lane must be weighed by finish_proposal.
struct ProposalWeights {
  float weight[kLanes];
  Rgb contribution[kLanes];
  bool in_range[kLanes];
};

// proposal_of(l) returns lane l's proposal and strategy (top-to-bottom or bottom-to-top), for
// lanes [0, count), 1 <= count <= kLanes.
template <class ProposalOf>
ProposalWeights weigh_proposals(ProposalOf&& proposal_of, size_t count,
                                const SneeOptions& options) {
  const SuffixWeighingBatch w = weigh_suffix(
      load_suffixes([&](size_t l) -> const SneeSuffix& { return proposal_of(l).first.suffix; },
                    count),
      options);
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
    const auto [p, st] = proposal_of(l);
    const float wl = weight[st == Strategy::kTopToBottom ? 0 : 1][l];
    const Rgb f =
        Rgb(attenuation[0][l], attenuation[1][l], attenuation[2][l]) * p.emitted * path[l];
    out.weight[l] = wl;
    out.contribution[l] = f * static_cast<float>(wl / p.sampling_pdf);
    out.in_range[l] = std::isfinite(pdf_sum[l]) && std::isfinite(wl) && std::isfinite(path[l]);
  }
  return out;
}

}  // namespace snee::simd
