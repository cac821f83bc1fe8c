// The manifold strategy's reflection chains on the smooth sphere (docs/method.md 3.12): every
// chain found enters facing the light, refracts by Snell's law, reflects by the mirror law and
// reaches x on its last chord; every chain traced forward from the light is found again from its
// end point; the chain's volume Jacobian agrees with finite differences and, with no
// reflection, with the refraction Jacobian; and it integrates to the volume the chains reach.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/sampling.h"
#include "kernels/physics/snee/manifold_sphere.h"
#include "tests/support/chi2.h"
#include "tests/support/manifold_sphere_setup.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::TestRng;
using namespace test::manifold_sphere;

// An outward normal facing the light.
Vec3 lit_normal(TestRng& rng, Vec3 light) {
  const Vec3 n = sample_uniform_sphere(rng.uniform2());
  return dot(n, light) < 0 ? -n : n;
}

TEST(ManifoldChains, ChainsObeySnellAndTheMirrorLaw) {
  TestRng rng(11);
  int chains = 0;
  for (int k = 0; k < 5000; ++k) {
    const Vec3 light = sample_uniform_sphere(rng.uniform2());
    const Vec3 x = random_inside(rng);
    const int reflections = 1 + k % 6;
    const SphereChains found =
        sphere_reflection_chains_toward_light(kCentre, kRadius, kEta, light, x, reflections);
    ASSERT_EQ(found.dropped, 0);
    for (int i = 0; i < found.count; ++i) {
      const SphereChain& c = found.chain[static_cast<size_t>(i)];
      ++chains;
      ASSERT_EQ(c.reflections, reflections);
      ASSERT_NEAR(length(c.y - kCentre), kRadius, 1e-5f);
      ASSERT_GT(dot(c.n, light), 0.0f);
      // Forward from the entry with Snell's and the mirror law, the light must pass the same
      // reflection points and reach x along the last chord.
      const ForwardChain f = trace_forward(light, c.n, c.reflections);
      for (int b = 0; b < c.reflections; ++b) {
        ASSERT_LT(length(f.points[static_cast<size_t>(b + 1)] - c.bounce[static_cast<size_t>(b)]),
                  1e-4f);
        ASSERT_NEAR(length(c.bounce[static_cast<size_t>(b)] - kCentre), kRadius, 1e-5f);
      }
      const Vec3 to_x = x - c.bounce[static_cast<size_t>(c.reflections - 1)];
      ASSERT_NEAR(length(to_x), c.t_last, 1e-4);
      ASSERT_GT(dot(normalize(to_x), f.direction), 1.0f - 1e-5f);
      ASSERT_GT(dot(c.omega_last, f.direction), 1.0f - 1e-5f);
      ASSERT_GT(c.jacobian, 0.0);
      // Every chord of a sphere chain has the same length (the angle to the normal is kept).
      const float chord = length(c.bounce[0] - c.y);
      ASSERT_NEAR(c.length, chord * static_cast<float>(c.reflections) + c.t_last, 1e-4);
    }
  }
  EXPECT_GT(chains, 5000);
}

// The entry points found for x with this many reflections (the direct exits of section 3.10
// for none).
std::vector<Vec3> entries_found(Vec3 light, Vec3 x, int reflections) {
  std::vector<Vec3> entries;
  if (reflections == 0) {
    const SphereExits exits = sphere_exits_toward_light(kCentre, kRadius, kEta, light, x);
    for (int i = 0; i < exits.count; ++i) entries.push_back(exits.exit[static_cast<size_t>(i)].y);
    return entries;
  }
  const SphereChains found =
      sphere_reflection_chains_toward_light(kCentre, kRadius, kEta, light, x, reflections);
  for (int i = 0; i < found.count; ++i) {
    EXPECT_EQ(found.chain[static_cast<size_t>(i)].reflections, reflections);
    entries.push_back(found.chain[static_cast<size_t>(i)].y);
  }
  return entries;
}

// Completeness, for the direct exits (no reflection) and the chains: a path traced forward from
// the light (entry point, reflection count, a point on its last chord) must be found from that
// point. A float point lies ~1e-7 off the exact path, which can remove a pair of solutions where
// they merge on a caustic (J -> 0): such misses are allowed only there and must be rare (this
// sampling concentrates near the caustic like 1 / J, the renderer's points do not).
TEST(ManifoldChains, FindsEveryForwardTracedPath) {
  TestRng rng(12);
  int near_caustic_misses = 0;
  constexpr int kSamples = 28000;
  for (int k = 0; k < kSamples; ++k) {
    const Vec3 light = sample_uniform_sphere(rng.uniform2());
    const Vec3 n = lit_normal(rng, light);
    const int reflections = static_cast<int>(rng.uniform() * 7);
    const ForwardChain f = trace_forward(light, n, reflections);
    const float t = f.chord * (0.001f + 0.998f * rng.uniform());
    const Vec3 x = f.at(t);
    bool match = false;
    for (const Vec3& y : entries_found(light, x, reflections))
      match = match || length(y - f.points[0]) < 1e-3f;
    if (match) continue;
    const double relative_j =
        sphere_chain_volume_jacobian(n, light, kEta, reflections, t / kRadius) /
        std::abs(dot(n, f.direction));
    ASSERT_LT(relative_j, 0.002) << "path " << k << " with " << reflections << " reflections";
    ++near_caustic_misses;
  }
  EXPECT_LT(near_caustic_misses, kSamples / 1000);
}

// The chain's volume Jacobian by central differences at distance t along its last chord.
double numerical_chain_jacobian(Vec3 n0, Vec3 light, int reflections, double t) {
  return numerical_volume_jacobian(
      n0, trace_forward(light, n0, reflections).direction,
      [&](Vec3 n) { return trace_forward(light, n, reflections).at(t); });
}

TEST(ManifoldChains, JacobianMatchesFiniteDifferencesAndTheRefractionJacobian) {
  TestRng rng(13);
  for (int k = 0; k < 300; ++k) {
    const Vec3 light = sample_uniform_sphere(rng.uniform2());
    const Vec3 n = lit_normal(rng, light);
    if (dot(n, light) < 0.2f) continue;
    const int reflections = static_cast<int>(rng.uniform() * 7);
    const ForwardChain f = trace_forward(light, n, reflections);
    const double t = f.chord * rng.uniform();
    const double exact = sphere_chain_volume_jacobian(n, light, kEta, reflections, t / kRadius);
    const double numeric = numerical_chain_jacobian(n, light, reflections, t);
    ASSERT_NEAR(exact, numeric, 3e-3 * (1 + numeric)) << reflections << " reflections, t " << t;
    if (reflections == 0) {
      ASSERT_NEAR(exact, refraction_volume_jacobian(n, light, kEta, 1.0 / kRadius, t),
                  1e-9 * (1 + exact));
    }
  }
}

// The change of variables per reflection count m: integrating J over the lit hemisphere and the
// last chord, divided by the number of m-reflection chains x has, gives the volume such chains
// reach: the sphere's volume times the share of uniform interior points that have one. Both
// sides are sampled, each term bounded, so the standard errors are reliable.
TEST(ManifoldChains, JacobianIntegratesToTheVolumeTheChainsReach) {
  const Vec3 light = normalize(Vec3{1, 1, 1});
  const double sphere = 4.0 / 3.0 * kPi * kRadius * kRadius * kRadius;
  for (int m = 1; m <= 4; ++m) {
    TestRng rng(static_cast<uint64_t>(20 + m));
    test::MeanEstimator estimate;
    for (int k = 0; k < 100000; ++k) {
      const float c = rng.uniform(), phi = 2 * kPi * rng.uniform();
      const float s = std::sqrt(std::max(0.0f, 1 - c * c));
      const Frame f = Frame::from_normal(light);
      const Vec3 n = normalize(f.to_world({s * std::cos(phi), s * std::sin(phi), c}));
      const ForwardChain chain = trace_forward(light, n, m);
      const double t = chain.chord * rng.uniform();
      const Vec3 x = chain.at(t);
      const int count =
          sphere_reflection_chains_toward_light(kCentre, kRadius, kEta, light, x, m).count;
      if (count == 0) {
        estimate.add(0.0);
        continue;
      }
      const double measure = 2 * kPi * kRadius * kRadius * chain.chord;
      estimate.add(measure * sphere_chain_volume_jacobian(n, light, kEta, m, t / kRadius) / count);
    }
    test::MeanEstimator reached;
    for (int k = 0; k < 100000; ++k) {
      const Vec3 x = random_inside(rng);
      reached.add(sphere_reflection_chains_toward_light(kCentre, kRadius, kEta, light, x, m).count >
                          0
                      ? sphere
                      : 0.0);
    }
    EXPECT_LT(test::z_score(estimate.mean(), estimate.standard_error(), reached.mean(),
                            reached.standard_error()),
              4.0)
        << m << " reflections: " << estimate.mean() << " +- " << estimate.standard_error() << " vs "
        << reached.mean() << " +- " << reached.standard_error();
    EXPECT_LT(estimate.standard_error(), 0.02 * reached.mean());
    EXPECT_GT(reached.mean(), 0.3 * sphere);
  }
}

// The reflection count a vertex searches: the probabilities sum to the search probability, each
// is what the sampler returns with its choice, and the draws follow them (chi-square over
// m = 1..8 and the tail, 200k draws).
TEST(ManifoldChains, ReflectionCountFollowsItsProbabilities) {
  constexpr double kChainSearchProbability = 0.3;
  double total = 0;
  for (int m = 1; m <= 100000; ++m)
    total += chain_reflections_probability(m, kChainSearchProbability);
  EXPECT_NEAR(total, kChainSearchProbability, 1e-4);
  EXPECT_EQ(chain_reflections_probability(0, kChainSearchProbability), 0.0);
  TestRng rng(30);
  constexpr int kBins = 10;  // none, m = 1..8, m > 8
  std::vector<double> observed(kBins, 0.0), expected(kBins, 0.0);
  constexpr int kDraws = 200000;
  for (int k = 0; k < kDraws; ++k) {
    const ChainChoice c = choose_chain_reflections(rng.uniform(), kChainSearchProbability);
    if (c.reflections == 0) {
      ASSERT_EQ(c.probability, 0.0);
      observed[0] += 1;
      continue;
    }
    ASSERT_NEAR(c.probability,
                chain_reflections_probability(c.reflections, kChainSearchProbability), 1e-15);
    observed[static_cast<size_t>(std::min(c.reflections, kBins - 1))] += 1;
  }
  expected[0] = (1.0 - kChainSearchProbability) * kDraws;
  double below = 0;
  for (int m = 1; m < kBins - 1; ++m) {
    expected[static_cast<size_t>(m)] =
        chain_reflections_probability(m, kChainSearchProbability) * kDraws;
    below += chain_reflections_probability(m, kChainSearchProbability);
  }
  expected[kBins - 1] = (kChainSearchProbability - below) * kDraws;
  double statistic = 0;
  for (int i = 0; i < kBins; ++i) {
    const double d = observed[static_cast<size_t>(i)] - expected[static_cast<size_t>(i)];
    statistic += d * d / expected[static_cast<size_t>(i)];
  }
  EXPECT_GT(test::chi2_survival(statistic, kBins - 1), 1e-4) << "chi-square " << statistic;
  // The extremes of the unit interval give the first count and a long chain, never a failure.
  EXPECT_EQ(choose_chain_reflections(0.0f, kChainSearchProbability).reflections, 1);
  EXPECT_GT(
      choose_chain_reflections(std::nextafter(static_cast<float>(kChainSearchProbability), 0.0f),
                               kChainSearchProbability)
          .reflections,
      100);
  EXPECT_EQ(choose_chain_reflections(0.31f, kChainSearchProbability).reflections, 0);
  // The search probability follows the medium's clearest channel, within its bounds.
  EXPECT_EQ(chain_search_probability(Rgb(0.0f), 1.0f), 0.5);
  EXPECT_NEAR(chain_search_probability(Rgb(2.0f, 0.5f, 3.0f), 2.0f), 0.5 * std::exp(-1.0), 1e-7);
  EXPECT_EQ(chain_search_probability(Rgb(40.0f), 1.0f), 1.0 / 32.0);
}

// What the choice leaves of its random number (the start of a subsampled run of chains) is
// uniform on [0, 1) and independent of the count chosen: chi-square over 10 bins, for m = 1,
// m = 2 and m >= 3 separately, 400k draws.
TEST(ManifoldChains, LeftoverIsUniformWhateverTheCount) {
  constexpr double kChainSearchProbability = 0.3;
  constexpr int kBins = 10, kGroups = 3;
  std::vector<std::vector<double>> observed(kGroups, std::vector<double>(kBins, 0.0));
  TestRng rng(31);
  for (int k = 0; k < 400000; ++k) {
    const ChainChoice c = choose_chain_reflections(rng.uniform(), kChainSearchProbability);
    if (c.reflections == 0) continue;
    ASSERT_GE(c.leftover, 0.0);
    ASSERT_LT(c.leftover, 1.0);
    observed[static_cast<size_t>(std::min(c.reflections, kGroups) - 1)]
            [static_cast<size_t>(c.leftover * kBins)] += 1;
  }
  for (int g = 0; g < kGroups; ++g) {
    double total = 0, statistic = 0;
    for (const double o : observed[static_cast<size_t>(g)]) total += o;
    for (const double o : observed[static_cast<size_t>(g)]) {
      const double expected = total / kBins;
      statistic += (o - expected) * (o - expected) / expected;
    }
    EXPECT_GT(total, 5000) << "group " << g;
    EXPECT_GT(test::chi2_survival(statistic, kBins - 1), 1e-4)
        << "group " << g << ": chi-square " << statistic;
  }
}

}  // namespace
}  // namespace snee
