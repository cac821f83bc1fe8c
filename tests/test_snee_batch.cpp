// SNEE's templates instantiated over the float batch against their double instantiation (the
// scalar functions): the weighing of proposals (kernels/physics/snee/suffix_weighing.h, loaded
// from the subdivision stage's ProposalQueue by simd/snee_weights_batch.h) against finish_proposal,
// on proposals the real samplers make (every interface and light measure, isotropic and forward
// media, thin and dense, both heuristics and both probe kinds), and both strategies' straight-line
// parts (kernels/physics/snee/subdivision_vertices.h) against propose_bottom_to_top and
// propose_top_to_bottom.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "kernels/physics/lights/light_table.h"
#include "kernels/physics/snee/light_extent.h"
#include "kernels/physics/snee/probe.h"
#include "kernels/physics/snee/snee_pdfs.h"
#include "kernels/physics/snee/snee_strategies.h"
#include "kernels/physics/snee/subdivision_vertices.h"
#include "kernels/simd/snee_weights_batch.h"
#include "kernels/wavefront/subdivision_scratch.h"
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
// grazing angles), amplified up to 1/alpha by a microfacet lobe of roughness alpha; and of the
// Fresnel transmission 1 - F at the exit's (micro)normal, which float forms by cancellation and
// which vanishes toward total internal reflection. The double instantiation keeps these digits,
// the float batch does not, so they part by about this much.
double rounding_conditioning(const SneeSuffix& s) {
  const auto magnitude = [](Vec3 v) {
    return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  };
  const double rounding =
      std::sqrt(3.0) * 0x1p-24 * std::max({magnitude(s.x_i), magnitude(s.x_j), magnitude(s.x_k)});
  const double amplification = s.interface.delta() ? 1.0 : 1.0 / s.interface.alpha;
  const Vec3 omega_jk = normalize(s.x_k - s.x_j);
  const double cos_o = dot(s.ns_k, s.omega_o),
               cos_k_j = std::min(dot(s.n_k, omega_jk), dot(s.ns_k, omega_jk));
  const Frame frame = Frame::from_normal(s.ns_k);
  const Vec3d local_kj(frame.to_local(-omega_jk)), local_o(frame.to_local(s.omega_o));
  const Vec3d h = s.interface.delta() ? Vec3d(0, 0, 1)
                                      : normalize(local_kj * double(s.interface.eta) + local_o);
  const double transmission =
      1 - fresnel_dielectric<double>(std::fabs(dot(local_o, h)), s.interface.eta);
  return amplification * (rounding * (1 / length(s.x_j - s.x_i) + 1 / length(s.x_k - s.x_j) +
                                      1 / length(s.x_k - s.x_i)) +
                          0x1p-24 / std::min(cos_o, cos_k_j)) +
         0x1p-24 / transmission;
}

// The stated agreement (kernels/simd/README.md).
// Weights in [0, 1]: absolute, plus w (1 - w) times the densities' relative bound (a weight
// w = p / (p + q) moves by w (1 - w) times the relative change of p / q).
constexpr double kWeightBound = 1e-5;
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

// The proposals in the subdivision stage's queue, which the batched weighing loads from.
ProposalQueue queue_of(const Proposals& proposals) {
  ProposalQueue q(proposals.size());
  for (const auto& [p, st] : proposals) q.push(p, st, 0);
  return q;
}

simd::ProposalWeights weigh(const ProposalQueue& q, size_t k, size_t count,
                            const SneeOptions& options) {
  return simd::weigh_proposals(q.items(), k, count, options);
}

// Weighs `proposals` in batches, compares every lane with finish_proposal and asserts the
// stated bounds.
Agreement compare(const Proposals& proposals, const SneeOptions& options) {
  Agreement a;
  const ProposalQueue q = queue_of(proposals);
  for (size_t k = 0; k < proposals.size(); k += simd::kLanes) {
    const size_t count = std::min(simd::kLanes, proposals.size() - k);
    const simd::ProposalWeights w = weigh(q, k, count, options);
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
      const double conditioning = rounding_conditioning(p.suffix);
      EXPECT_LE(weight_error,
                kWeightBound + c.weight * (1 - c.weight) * kConditioningFactor * conditioning)
          << "proposal " << k + l << ": " << w.weight[l] << " vs " << c.weight << ", conditioning "
          << conditioning;
      a.weight_error = std::max(a.weight_error, weight_error);
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
// heuristics (the phase-function probe with the forward medium, the light-favouring one with the
// isotropic medium's power heuristic).
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
        // The light-favouring probe with the isotropic medium's power heuristic.
        options.probe = g != 0                      ? ProbeDirections::kPhaseFunction
                        : h == MisHeuristic::kPower ? ProbeDirections::kTowardLights
                                                    : ProbeDirections::kUniformSphere;
        options.probe_targets = probe_targets_of(scene, lights, kWholeSkyDegrees);
        Proposals proposals;
        for (int k = 0; k < exits; ++k) {
          // Every other exit on a smooth-shaded boundary (docs/method.md 4.9).
          const ExitSetup setup = random_setup(rng, c.interface, 0.04f / density, 2.0f / density,
                                               k % 2 == 0 ? 0.0f : 0.4f);
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
    EXPECT_GT(per_case.weighed, 45000) << c.name;  // tilted shading normals reject more
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
    for (const auto& [options, proposals] : proposal_sets(c, rng, 400)) {
      const ProposalQueue q = queue_of(proposals);
      for (size_t k = 0; k + simd::kLanes <= proposals.size(); k += simd::kLanes) {
        const simd::ProposalWeights batch = weigh(q, k, simd::kLanes, options);
        for (size_t l = 0; l < simd::kLanes; ++l) {
          const simd::ProposalWeights alone = weigh(q, k + l, 1, options);
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
  const simd::ProposalWeights before = weigh(queue_of(batch), 0, simd::kLanes, options);
  SneeProposal& p = batch[0].first;
  const Vec3 omega_kj = normalize(p.suffix.x_j - p.suffix.x_k);
  p.suffix.x_j = p.suffix.x_k + 1e-21f * omega_kj;
  ASSERT_NE(p.suffix.x_j.z, p.suffix.x_k.z);
  const simd::ProposalWeights after = weigh(queue_of(batch), 0, simd::kLanes, options);
  EXPECT_FALSE(after.in_range[0]);
  for (size_t l = 1; l < simd::kLanes; ++l) {
    EXPECT_TRUE(after.in_range[l]);
    EXPECT_EQ(after.weight[l], before.weight[l]);
  }
  // The scalar function, in double, still weighs it.
  const SneeCandidate scalar = finish_proposal(batch[0].second, p, options);
  EXPECT_TRUE(std::isfinite(scalar.weight));
}

// --- the strategies' batched sampling ---------------------------------------------------------

// One lane's result: how far the sampler got (its failure stages in order, then success), and
// what it sampled.
struct LaneSample {
  int stage = 0;
  Vec3 x_j, omega_o;
  double pdf = 0;
};

struct SamplerLanes {
  std::array<ExitSetup, simd::kLanes> setups;
  alignas(64) float x_i[3][simd::kLanes], omega_in[3][simd::kLanes], x_k[3][simd::kLanes],
      n_k[3][simd::kLanes], ns_k[3][simd::kLanes], g[simd::kLanes], eta[simd::kLanes],
      alpha[simd::kLanes];
  simd::Vec3Batch vec(const float (&v)[3][simd::kLanes]) const {
    return {simd::FloatBatch::load_aligned(v[0]), simd::FloatBatch::load_aligned(v[1]),
            simd::FloatBatch::load_aligned(v[2])};
  }
  simd::DielectricLanes interface() const {
    return {simd::FloatBatch::load_aligned(eta), simd::FloatBatch::load_aligned(alpha)};
  }
};

std::array<LaneSample, simd::kLanes> read_lanes(const simd::Vec3Batch& x_j,
                                                const simd::Vec3Batch& omega_o,
                                                simd::FloatBatch pdf,
                                                const std::array<simd::BoolBatch, 2>& passed) {
  alignas(64) float x[3][simd::kLanes], w[3][simd::kLanes], p[simd::kLanes], ok[2][simd::kLanes];
  const simd::FloatBatch one(1.0f), zero(0.0f);
  for (int i = 0; i < 2; ++i) xsimd::select(passed[i], one, zero).store_aligned(ok[i]);
  simd::store_aligned(x_j, x[0], x[1], x[2]);
  simd::store_aligned(omega_o, w[0], w[1], w[2]);
  pdf.store_aligned(p);
  std::array<LaneSample, simd::kLanes> out;
  for (size_t l = 0; l < simd::kLanes; ++l) {
    out[l].stage = ok[0][l] == 0 ? 0 : ok[1][l] == 0 ? 1 : 2;
    out[l].x_j = Vec3(x[0][l], x[1][l], x[2][l]);
    out[l].omega_o = Vec3(w[0][l], w[1][l], w[2][l]);
    out[l].pdf = p[l];
  }
  return out;
}

// Runs batch(lanes, u, medium, options, lights) and scalar(setup, u, medium, options, lights),
// which returns the stage the scalar sampler reached and its proposal, on the same exits and random
// numbers for every case, medium and probe kind; the batch must decide like the scalar sampler on
// all but a few lanes at the edge of a decision, and where both sample, x_j, omega_o and the
// density agree within the stated bounds.
template <int N, class Batch, class Scalar>
void compare_sampler(uint64_t seed, bool delta_lights, Batch&& batch, Scalar&& scalar) {
  TestRng rng(seed);
  int lanes = 0, decisions_differ = 0, sampled = 0, alone_checked = 0;
  double position_error = 0, direction_error = 0, pdf_error = 0, well_conditioned_pdf_error = 0;
  for (const test::SneeCase& c : kCases) {
    if (!delta_lights && c.light == LightKind::kDirectional) continue;
    const Scene scene = light_scene(c.light, Rgb(1.0f, 0.7f, 0.4f));
    const LightTable lights(scene);
    for (const float g : {0.0f, 0.8f}) {
      for (const float density : {1.0f, 40.0f}) {
        const SneeMedium medium{Rgb(0.9f, 0.7f, 0.5f) * density, Rgb(1.0f, 0.8f, 0.6f) * density,
                                g};
        SneeOptions options;
        // The light-favouring probe with the dense isotropic medium.
        options.probe = g != 0           ? ProbeDirections::kPhaseFunction
                        : density > 1.0f ? ProbeDirections::kTowardLights
                                         : ProbeDirections::kUniformSphere;
        options.probe_targets = probe_targets_of(scene, lights, kWholeSkyDegrees);
        for (int k = 0; k < 4000; ++k) {
          SamplerLanes in;
          std::array<std::array<float, N>, simd::kLanes> us;
          for (size_t l = 0; l < simd::kLanes; ++l) {
            // Every other exit on a smooth-shaded boundary (docs/method.md 4.9).
            const ExitSetup e = random_setup(rng, c.interface, 0.04f / density, 2.0f / density,
                                             l % 2 == 0 ? 0.0f : 0.4f);
            in.setups[l] = e;
            us[l] = uniforms<N>(rng);
            const Vec3 v[5] = {e.origin.x_i, e.origin.omega_in, e.exit.x_k, e.exit.n_k,
                               e.exit.ns_k};
            float(*dst[5])[simd::kLanes] = {in.x_i, in.omega_in, in.x_k, in.n_k, in.ns_k};
            for (int i = 0; i < 5; ++i) {
              dst[i][0][l] = v[i].x;
              dst[i][1][l] = v[i].y;
              dst[i][2][l] = v[i].z;
            }
            in.g[l] = g;
            in.eta[l] = c.interface.eta;
            in.alpha[l] = c.interface.alpha;
          }
          const std::array<LaneSample, simd::kLanes> got = batch(in, us, medium, options, lights);
          // Every lane is a function of its own exit alone: the same exit in every lane (a
          // megakernel chunk, padded with its one entry) gives the same bits.
          if (k % 16 == 0) {
            for (size_t l = 0; l < simd::kLanes; ++l) {
              SamplerLanes alone = in;
              std::array<std::array<float, N>, simd::kLanes> u_alone;
              for (size_t m = 0; m < simd::kLanes; ++m) {
                alone.setups[m] = in.setups[l];
                u_alone[m] = us[l];
                for (auto* v : {&alone.x_i, &alone.omega_in, &alone.x_k, &alone.n_k, &alone.ns_k})
                  for (int i = 0; i < 3; ++i) (*v)[i][m] = (*v)[i][l];
                alone.g[m] = in.g[l];
                alone.eta[m] = in.eta[l];
                alone.alpha[m] = in.alpha[l];
              }
              const LaneSample a = batch(alone, u_alone, medium, options, lights)[0];
              const LaneSample& b = got[l];
              ASSERT_EQ(a.stage, b.stage) << c.name << " lane " << l;
              if (a.stage == 0) continue;  // nothing sampled yet: the rest is not defined
              ASSERT_EQ(std::memcmp(&a.x_j, &b.x_j, sizeof(Vec3)), 0) << c.name << " lane " << l;
              ASSERT_EQ(std::memcmp(&a.omega_o, &b.omega_o, sizeof(Vec3)), 0) << c.name;
              ASSERT_EQ(std::memcmp(&a.pdf, &b.pdf, sizeof(double)), 0) << c.name;
              ++alone_checked;
            }
          }
          for (size_t l = 0; l < simd::kLanes; ++l) {
            const auto [stage, p] = scalar(in.setups[l], us[l], medium, options, lights);
            ++lanes;
            const LaneSample& b = got[l];
            if (b.stage != stage) {
              ++decisions_differ;
              continue;
            }
            if (p.failure != SneeFailure::kNone) continue;
            ++sampled;
            const SneeSuffix& s = p.suffix;
            const double conditioning = rounding_conditioning(s);
            const double scale = std::max(length(s.x_j - s.x_i), 1.0f);
            const double position = length(b.x_j - s.x_j) / scale;
            const double direction = length(b.omega_o - s.omega_o);
            const double e = std::fabs(b.pdf - p.sampling_pdf) / p.sampling_pdf;
            EXPECT_LE(position, kContributionBound + kConditioningFactor * conditioning) << c.name;
            EXPECT_LE(direction, kContributionBound + kConditioningFactor * conditioning) << c.name;
            EXPECT_LE(e, kContributionBound + kConditioningFactor * conditioning)
                << c.name << ": " << b.pdf << " vs " << p.sampling_pdf;
            position_error = std::max(position_error, position);
            direction_error = std::max(direction_error, direction);
            pdf_error = std::max(pdf_error, e);
            if (conditioning < 1e-6) {
              well_conditioned_pdf_error = std::max(well_conditioned_pdf_error, e);
            }
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
  EXPECT_GT(alone_checked, 1000);
  EXPECT_LE(decisions_differ, lanes / 10000);
}

TEST(SneeBottomToTopBatch, AgreesWithScalarSampler) {
  // Stages: not placed, not refracted, sampled (the light lookup is per exit, after the batch).
  compare_sampler<kBottomToTopDimensions>(
      74, false,
      [](const SamplerLanes& in, const auto& us, const SneeMedium&, const SneeOptions& options,
         const LightTable&) {
        std::array<simd::FloatBatch, kBottomToTopDimensions> u;
        for (int n = 0; n < kBottomToTopDimensions; ++n) {
          alignas(64) float lane[simd::kLanes];
          for (size_t l = 0; l < simd::kLanes; ++l) lane[l] = us[l][n];
          u[n] = simd::FloatBatch::load_aligned(lane);
        }
        const BottomToTopVertex<simd::FloatBatch> b = bottom_to_top_vertex<simd::FloatBatch>(
            {in.vec(in.x_i), in.vec(in.omega_in), in.vec(in.x_k), in.vec(in.n_k), in.vec(in.ns_k),
             simd::FloatBatch::load_aligned(in.g), in.interface()},
            options, u);
        return read_lanes(b.x_j, b.omega_o, b.pdf, {b.placed, b.refracted});
      },
      [](const ExitSetup& e, const auto& u, const SneeMedium& medium, const SneeOptions& options,
         const LightTable& lights) {
        const SneeProposal p =
            propose_bottom_to_top(e.origin, medium, e.exit, lights, options, 1e-4f, u);
        const int stage = p.failure == SneeFailure::kPlacement    ? 0
                          : p.failure == SneeFailure::kRefraction ? 1
                                                                  : 2;
        return std::pair<int, SneeProposal>(stage, p);
      });
}

TEST(SneeTopToBottomBatch, AgreesWithScalarSampler) {
  // Stages: no light, not refracted, no distance, sampled. The light sample is taken per lane
  // first, as the subdivision stage does.
  compare_sampler<kTopToBottomDimensions>(
      75, true,
      [](const SamplerLanes& in, const auto& us, const SneeMedium& medium,
         const SneeOptions& options, const LightTable& lights) {
        alignas(64) float u[kTopToBottomDimensions][simd::kLanes], wi[3][simd::kLanes],
            light_pdf[simd::kLanes], light_delta[simd::kLanes];
        std::array<bool, simd::kLanes> lit;
        for (size_t l = 0; l < simd::kLanes; ++l) {
          using R = TopToBottomRandoms;
          const LightSample light =
              lights.sample(in.setups[l].exit.x_k, us[l][R::kLightSelection],
                            Vec2{us[l][R::kLightPoint], us[l][R::kLightPoint + 1]});
          lit[l] = lights_exit_point(light, in.setups[l].exit.n_k, in.setups[l].exit.ns_k);
          wi[0][l] = light.wi.x;
          wi[1][l] = light.wi.y;
          wi[2][l] = light.wi.z;
          light_pdf[l] = light.pdf;
          light_delta[l] = light.delta ? 1.0f : 0.0f;
          for (int n = 0; n < kTopToBottomDimensions; ++n) u[n][l] = us[l][n];
        }
        std::array<simd::FloatBatch, kTopToBottomDimensions> ub;
        for (int n = 0; n < kTopToBottomDimensions; ++n)
          ub[n] = simd::FloatBatch::load_aligned(u[n]);
        const simd::FloatBatch zero(0.0f);
        const TopToBottomVertex<simd::FloatBatch> b = top_to_bottom_vertex<simd::FloatBatch>(
            {in.vec(in.x_i),
             in.vec(in.omega_in),
             in.vec(in.x_k),
             in.vec(in.n_k),
             in.vec(in.ns_k),
             simd::FloatBatch::load_aligned(in.g),
             {simd::FloatBatch(medium.sigma_t.x), simd::FloatBatch(medium.sigma_t.y),
              simd::FloatBatch(medium.sigma_t.z)},
             in.interface(),
             in.vec(wi),
             simd::FloatBatch::load_aligned(light_pdf),
             simd::FloatBatch::load_aligned(light_delta) != zero},
            options, ub);
        std::array<LaneSample, simd::kLanes> out =
            read_lanes(b.x_j, in.vec(wi), b.pdf, {b.refracted, b.distanced});
        for (size_t l = 0; l < simd::kLanes; ++l) out[l].stage = lit[l] ? out[l].stage + 1 : 0;
        return out;
      },
      [](const ExitSetup& e, const auto& u, const SneeMedium& medium, const SneeOptions& options,
         const LightTable& lights) {
        const SneeProposal p =
            propose_top_to_bottom(e.origin, medium, e.exit, lights, options, 1e-4f, u);
        const int stage = p.failure == SneeFailure::kNoLight      ? 0
                          : p.failure == SneeFailure::kRefraction ? 1
                          : p.failure == SneeFailure::kZero       ? 2
                                                                  : 3;
        return std::pair<int, SneeProposal>(stage, p);
      });
}

}  // namespace
}  // namespace snee
