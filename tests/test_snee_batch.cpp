// SNEE's batched kernels against their scalar references: the weighing of proposals
// (simd/snee_weights_batch.h) against finish_proposal, on proposals the real samplers make
// (every interface and light measure, isotropic and forward media, thin and dense, both
// heuristics and both probe kinds), and bottom-to-top's batched placement and refraction
// (simd/bottom_to_top_batch.h) against propose_bottom_to_top.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "kernels/lights/light_table.h"
#include "kernels/simd/bottom_to_top_batch.h"
#include "kernels/simd/snee_weights_batch.h"
#include "kernels/snee/snee_strategies.h"
#include "tests/support/chi2.h"
#include "tests/support/snee_setups.h"

namespace snee {
namespace {

using test::ExitSetup;
using test::light_scene;
using test::random_setup;
using test::TestRng;
using test::uniforms;

// Relative error that float rounding alone can cause in the suffix's terms: of the vertices
// (each known to half an ulp of its largest coordinate) in its directions and distances, and
// of a unit direction in the cosines at the exit (the interface's terms go as the cosine at
// grazing angles), amplified up to 1/alpha by a microfacet lobe of roughness alpha. The scalar
// functions take differences in double, the batch in float, so they part by about this much.
double rounding_conditioning(const SneeSuffix& s) {
  const auto magnitude = [](Vec3 v) {
    return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  };
  const double rounding =
      std::sqrt(3.0) * 0x1p-24 * std::max({magnitude(s.x_i), magnitude(s.x_j), magnitude(s.x_k)});
  const double amplification = s.interface.delta() ? 1.0 : 1.0 / s.interface.alpha;
  const double cos_o = dot(s.n_k, s.omega_o), cos_k_j = dot(s.n_k, normalize(s.x_k - s.x_j));
  return amplification * (rounding * (1 / length(s.x_j - s.x_i) + 1 / length(s.x_k - s.x_j) +
                                      1 / length(s.x_k - s.x_i)) +
                          0x1p-24 / std::min(cos_o, cos_k_j));
}

// The stated agreement (kernels/simd/README.md).
constexpr double kWeightBound = 1e-5;        // absolute, weights in [0, 1]
constexpr double kContributionBound = 5e-5;  // relative, where rounding_conditioning < 1e-6
constexpr double kConditioningFactor = 200;  // relative <= bound + factor * conditioning
// Contributions this small come from products that pass through subnormals, where float and
// the scalar's double intermediates round differently (the renderer flushes them to zero).
constexpr double kSmallestCompared = 1e-30;

struct Agreement {
  int proposals = 0, weighed = 0, valid_mismatch = 0, out_of_range = 0, well_conditioned = 0;
  double weight_error = 0, contribution_error = 0, well_conditioned_error = 0;
  double error_per_conditioning = 0;
  void merge(const Agreement& o) {
    proposals += o.proposals;
    weighed += o.weighed;
    valid_mismatch += o.valid_mismatch;
    out_of_range += o.out_of_range;
    well_conditioned += o.well_conditioned;
    weight_error = std::max(weight_error, o.weight_error);
    contribution_error = std::max(contribution_error, o.contribution_error);
    well_conditioned_error = std::max(well_conditioned_error, o.well_conditioned_error);
    error_per_conditioning = std::max(error_per_conditioning, o.error_per_conditioning);
  }
};

using Proposals = std::vector<std::pair<SneeProposal, Strategy>>;

simd::ProposalWeights weigh(const Proposals& proposals, size_t k, size_t count,
                            const SneeOptions& options) {
  return simd::weigh_proposals(
      [&](size_t l) {
        return std::pair<const SneeProposal&, Strategy>(proposals[k + l].first,
                                                        proposals[k + l].second);
      },
      count, options);
}

// Weighs `proposals` in batches, compares every lane with finish_proposal and asserts the
// stated bounds.
Agreement compare(const Proposals& proposals, const SneeOptions& options) {
  Agreement a;
  for (size_t k = 0; k < proposals.size(); k += simd::kLanes) {
    const size_t count = std::min(simd::kLanes, proposals.size() - k);
    const simd::ProposalWeights w = weigh(proposals, k, count, options);
    for (size_t l = 0; l < count; ++l) {
      const auto& [p, st] = proposals[k + l];
      const SneeCandidate c = finish_proposal(st, p, options);
      ++a.proposals;
      if (!w.in_range[l]) {
        ++a.out_of_range;
        continue;
      }
      const bool valid =
          w.weight[l] > 0 && !is_black(w.contribution[l]) && is_finite(w.contribution[l]);
      EXPECT_EQ(valid, c.valid) << "proposal " << k + l;
      if (valid != c.valid) ++a.valid_mismatch;
      if (!valid || !c.valid) continue;
      ++a.weighed;
      const double weight_error = std::fabs(w.weight[l] - c.weight);
      EXPECT_LE(weight_error, kWeightBound) << "proposal " << k + l;
      a.weight_error = std::max(a.weight_error, weight_error);
      const double conditioning = rounding_conditioning(p.suffix);
      if (conditioning < 1e-6) ++a.well_conditioned;
      for (int ch = 0; ch < 3; ++ch) {
        const double simd_value = w.contribution[l][ch], scalar_value = c.contribution[ch];
        if (!(scalar_value >= kSmallestCompared)) continue;
        const double e = std::fabs(simd_value - scalar_value) / scalar_value;
        EXPECT_LE(e, kContributionBound + kConditioningFactor * conditioning)
            << "proposal " << k + l << " channel " << ch << ": " << simd_value << " vs "
            << scalar_value << ", conditioning " << conditioning;
        a.contribution_error = std::max(a.contribution_error, e);
        if (conditioning < 1e-6) a.well_conditioned_error = std::max(a.well_conditioned_error, e);
        a.error_per_conditioning = std::max(a.error_per_conditioning, e / conditioning);
      }
    }
  }
  return a;
}

constexpr test::SneeCase kCases[] = {
    {"A rough+cone", {1.5f, 0.2f}, LightKind::kCone},
    {"A rough+env", {1.33f, 0.05f}, LightKind::kConstantEnv},
    {"B rough+directional", {1.5f, 0.2f}, LightKind::kDirectional},
    {"C smooth+cone", {1.5f, 0.0f}, LightKind::kCone},
    {"C smooth+env", {1.5f, 0.0f}, LightKind::kConstantEnv},
    {"D smooth+directional", {1.5f, 0.0f}, LightKind::kDirectional},
    {"index matched", {1.0f, 0.3f}, LightKind::kCone},
};

// Proposals of both strategies for every case, thin and dense, isotropic and forward media, both
// heuristics (the phase-function probe with the forward medium).
std::vector<std::pair<SneeOptions, Proposals>> proposal_sets(const test::SneeCase& c, TestRng& rng,
                                                             int exits) {
  const Scene scene = light_scene(c.light, Rgb(1.0f, 0.7f, 0.4f));
  const LightTable lights(scene);
  std::vector<std::pair<SneeOptions, Proposals>> sets;
  for (const float g : {0.0f, 0.8f}) {
    for (const float density : {1.0f, 40.0f}) {
      const SneeMedium medium{Rgb(0.9f, 0.7f, 0.5f) * density, Rgb(1.0f, 0.8f, 0.6f) * density, g};
      for (const MisHeuristic h : {MisHeuristic::kBalance, MisHeuristic::kPower}) {
        SneeOptions options;
        options.heuristic = h;
        options.probe = g == 0 ? ProbeDirections::kUniformSphere : ProbeDirections::kPhaseFunction;
        Proposals proposals;
        for (int k = 0; k < exits; ++k) {
          const ExitSetup setup = random_setup(rng, c.interface, 0.04f / density, 2.0f / density);
          const SneeProposal tb =
              propose_top_to_bottom(setup.origin, medium, setup.exit, lights, options, 1e-4f,
                                    uniforms<kTopToBottomDimensions>(rng));
          if (tb.failure == SneeFailure::kNone) proposals.push_back({tb, Strategy::kTopToBottom});
          const SneeProposal bt =
              propose_bottom_to_top(setup.origin, medium, setup.exit, lights, options, 1e-4f,
                                    uniforms<kBottomToTopDimensions>(rng));
          if (bt.failure == SneeFailure::kNone) proposals.push_back({bt, Strategy::kBottomToTop});
        }
        sets.push_back({options, std::move(proposals)});
      }
    }
  }
  return sets;
}

TEST(SneeWeightsBatch, AgreesWithScalarFinishProposal) {
  TestRng rng(71);
  Agreement total;
  for (const test::SneeCase& c : kCases) {
    Agreement per_case;
    for (const auto& [options, proposals] : proposal_sets(c, rng, 10000)) {
      per_case.merge(compare(proposals, options));
    }
    EXPECT_GT(per_case.weighed, 50000) << c.name;
    total.merge(per_case);
  }
  EXPECT_EQ(total.out_of_range, 0);
  EXPECT_GT(total.well_conditioned, 150000);
  std::printf(
      "%d proposals, %d weighed, %d valid flags differ, %d out of float range\n"
      "largest weight difference %.3g; largest relative contribution difference %.3g, "
      "%.3g on the %d well-conditioned lanes; largest difference / conditioning %.3g\n",
      total.proposals, total.weighed, total.valid_mismatch, total.out_of_range, total.weight_error,
      total.contribution_error, total.well_conditioned_error, total.well_conditioned,
      total.error_per_conditioning);
}

// Each lane is a function of its own proposal alone: weighed alone (the megakernel's one-slot
// chunks) or at any position in a batch, it gives the same bits.
TEST(SneeWeightsBatch, LanesAreIndependentOfTheirBatch) {
  TestRng rng(72);
  int compared = 0;
  for (const test::SneeCase& c : kCases) {
    for (const auto& [options, proposals] : proposal_sets(c, rng, 200)) {
      for (size_t k = 0; k + simd::kLanes <= proposals.size(); k += simd::kLanes) {
        const simd::ProposalWeights batch = weigh(proposals, k, simd::kLanes, options);
        for (size_t l = 0; l < simd::kLanes; ++l) {
          const simd::ProposalWeights alone = weigh(proposals, k + l, 1, options);
          ASSERT_EQ(std::memcmp(&alone.weight[0], &batch.weight[l], sizeof(float)), 0);
          ASSERT_EQ(std::memcmp(&alone.contribution[0], &batch.contribution[l], sizeof(Rgb)), 0);
          ASSERT_EQ(alone.in_range[0], batch.in_range[l]);
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 10000);
}

// A middle vertex a hair from the exit point puts 1 / r_jk^2 beyond float's range: that lane
// is reported out of range (the kernel then weighs it with the scalar function) and its
// neighbours are unaffected.
TEST(SneeWeightsBatch, FlagsLanesBeyondFloatRange) {
  TestRng rng(73);
  const test::SneeCase& c = kCases[0];
  const auto sets = proposal_sets(c, rng, 200);
  const auto& [options, proposals] = sets.front();
  ASSERT_GE(proposals.size(), simd::kLanes);
  Proposals batch(proposals.begin(), proposals.begin() + simd::kLanes);
  const simd::ProposalWeights before = weigh(batch, 0, simd::kLanes, options);
  SneeProposal& p = batch[0].first;
  const Vec3 omega_kj = normalize(p.suffix.x_j - p.suffix.x_k);
  p.suffix.x_j = p.suffix.x_k + 1e-21f * omega_kj;
  ASSERT_NE(p.suffix.x_j.z, p.suffix.x_k.z);
  const simd::ProposalWeights after = weigh(batch, 0, simd::kLanes, options);
  EXPECT_FALSE(after.in_range[0]);
  for (size_t l = 1; l < simd::kLanes; ++l) {
    EXPECT_TRUE(after.in_range[l]);
    EXPECT_EQ(after.weight[l], before.weight[l]);
  }
  // The scalar function, in double, still weighs it.
  const SneeCandidate scalar = finish_proposal(batch[0].second, p, options);
  EXPECT_TRUE(std::isfinite(scalar.weight));
}

// --- bottom-to-top placement ---------------------------------------------------------------

simd::FloatBatch broadcast_lanes(const float* v) {
  return simd::FloatBatch::load_unaligned(v);
}

// The batch decides like the scalar sampler (placed, refracted, or neither) on all but a few
// lanes on the boundary of a decision, and where both sample, x_j, omega_o and the density
// agree to float rounding amplified by the configuration's conditioning.
TEST(SneeBottomToTopBatch, AgreesWithScalarSampler) {
  TestRng rng(74);
  int lanes = 0, decisions_differ = 0, sampled = 0;
  double position_error = 0, direction_error = 0, pdf_error = 0, well_conditioned_pdf_error = 0;
  for (const test::SneeCase& c : kCases) {
    if (c.light == LightKind::kDirectional) continue;  // BT never reaches a delta light
    const Scene scene = light_scene(c.light, Rgb(1.0f, 0.7f, 0.4f));
    const LightTable lights(scene);
    for (const float g : {0.0f, 0.8f}) {
      for (const float density : {1.0f, 40.0f}) {
        const SneeMedium medium{Rgb(0.9f, 0.7f, 0.5f) * density, Rgb(1.0f, 0.8f, 0.6f) * density,
                                g};
        SneeOptions options;
        options.probe = g == 0 ? ProbeDirections::kUniformSphere : ProbeDirections::kPhaseFunction;
        for (int k = 0; k < 4000; ++k) {
          alignas(64) float f[16 + kBottomToTopDimensions][simd::kLanes];
          std::array<ExitSetup, simd::kLanes> setups;
          std::array<std::array<float, kBottomToTopDimensions>, simd::kLanes> us;
          for (size_t l = 0; l < simd::kLanes; ++l) {
            setups[l] = random_setup(rng, c.interface, 0.04f / density, 2.0f / density);
            us[l] = uniforms<kBottomToTopDimensions>(rng);
            const Vec3 v[4] = {setups[l].origin.x_i, setups[l].origin.omega_in, setups[l].exit.x_k,
                               setups[l].exit.n_k};
            for (int i = 0; i < 4; ++i) {
              f[3 * i][l] = v[i].x;
              f[3 * i + 1][l] = v[i].y;
              f[3 * i + 2][l] = v[i].z;
            }
            f[12][l] = g;
            f[13][l] = c.interface.eta;
            f[14][l] = c.interface.alpha;
            for (int n = 0; n < kBottomToTopDimensions; ++n) f[16 + n][l] = us[l][n];
          }
          const auto vec = [&](int i) {
            return simd::Vec3Batch{broadcast_lanes(f[3 * i]), broadcast_lanes(f[3 * i + 1]),
                                   broadcast_lanes(f[3 * i + 2])};
          };
          std::array<simd::FloatBatch, kBottomToTopDimensions> u;
          for (int n = 0; n < kBottomToTopDimensions; ++n) u[n] = broadcast_lanes(f[16 + n]);
          const simd::BottomToTopBatch b =
              simd::propose_bottom_to_top({vec(0),
                                           vec(1),
                                           vec(2),
                                           vec(3),
                                           broadcast_lanes(f[12]),
                                           {broadcast_lanes(f[13]), broadcast_lanes(f[14])}},
                                          options, u, simd::kLanes);
          alignas(64) float x[3][simd::kLanes], w[3][simd::kLanes], pdf[simd::kLanes];
          alignas(64) float placed[simd::kLanes], refracted[simd::kLanes];
          const simd::FloatBatch one(1.0f), zero(0.0f);
          xsimd::select(b.placed, one, zero).store_aligned(placed);
          xsimd::select(b.refracted, one, zero).store_aligned(refracted);
          b.x_j.x.store_aligned(x[0]);
          b.x_j.y.store_aligned(x[1]);
          b.x_j.z.store_aligned(x[2]);
          b.omega_o.x.store_aligned(w[0]);
          b.omega_o.y.store_aligned(w[1]);
          b.omega_o.z.store_aligned(w[2]);
          b.pdf.store_aligned(pdf);
          for (size_t l = 0; l < simd::kLanes; ++l) {
            const SneeProposal p = propose_bottom_to_top(setups[l].origin, medium, setups[l].exit,
                                                         lights, options, 1e-4f, us[l]);
            const int scalar_stage = p.failure == SneeFailure::kPlacement    ? 0
                                     : p.failure == SneeFailure::kRefraction ? 1
                                                                             : 2;
            const int batch_stage = placed[l] == 0 ? 0 : refracted[l] == 0 ? 1 : 2;
            ++lanes;
            if (scalar_stage != batch_stage) {
              ++decisions_differ;
              continue;
            }
            if (p.failure != SneeFailure::kNone) continue;
            ++sampled;
            const SneeSuffix& s = p.suffix;
            const Vec3 x_j(x[0][l], x[1][l], x[2][l]), omega_o(w[0][l], w[1][l], w[2][l]);
            const double scale = std::max(length(s.x_j - s.x_i), 1.0f);
            position_error = std::max(position_error, double(length(x_j - s.x_j)) / scale);
            const double conditioning = rounding_conditioning(s);
            const double direction = length(omega_o - s.omega_o);
            EXPECT_LE(direction, kContributionBound + kConditioningFactor * conditioning);
            EXPECT_LE(length(x_j - s.x_j) / scale, kContributionBound);
            direction_error = std::max(direction_error, direction);
            const double e = std::fabs(pdf[l] - p.sampling_pdf) / p.sampling_pdf;
            EXPECT_LE(e, kContributionBound + kConditioningFactor * conditioning)
                << c.name << ": " << pdf[l] << " vs " << p.sampling_pdf;
            pdf_error = std::max(pdf_error, e);
            if (conditioning < 1e-6)
              well_conditioned_pdf_error = std::max(well_conditioned_pdf_error, e);
          }
        }
      }
    }
  }
  std::printf(
      "%d lanes, %d sampled, %d decided differently; largest x_j difference %.3g of "
      "max(|x_j - x_i|, 1), omega_o %.3g; density %.3g, %.3g where well conditioned\n",
      lanes, sampled, decisions_differ, position_error, direction_error, pdf_error,
      well_conditioned_pdf_error);
  EXPECT_GT(sampled, 20000);
  EXPECT_LE(decisions_differ, lanes / 10000);
}

}  // namespace
}  // namespace snee
