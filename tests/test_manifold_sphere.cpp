// The manifold strategy's exit-point solver and volume Jacobian on the smooth sphere
// (docs/method.md 3.10), and its place in the MIS weights: every solution obeys Snell's law
// (completeness is tested with the reflection chains'), the Jacobian
// agrees with finite differences of the map (y, t) -> x and integrates to the sphere's volume,
// and top-to-bottom and the manifold strategy share case-D suffixes with weights summing to one.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/sampling.h"
#include "kernels/physics/snee/manifold_sphere.h"
#include "kernels/physics/snee/snee_pdfs.h"
#include "tests/support/chi2.h"
#include "tests/support/manifold_sphere_setup.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::TestRng;
using namespace test::manifold_sphere;

// The light refracted into the sphere at outward normal n: the inside propagation direction.
Vec3 refracted_light(Vec3 light, Vec3 n, float eta = kEta) {
  Vec3 wt;
  EXPECT_TRUE(refract(light, n, 1.0f / eta, &wt));
  return wt;
}

TEST(ManifoldSphere, SolutionsObeySnellsLaw) {
  TestRng rng(1);
  int solutions = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 light = sample_uniform_sphere(rng.uniform2());
    const Vec3 x = random_inside(rng);
    const SphereExits exits = sphere_exits_toward_light(kCentre, kRadius, kEta, light, x);
    for (int i = 0; i < exits.count; ++i) {
      const SphereExit& e = exits.exit[static_cast<size_t>(i)];
      ++solutions;
      ASSERT_NEAR(length(e.y - kCentre), kRadius, 1e-5f);
      ASSERT_GT(dot(e.n, light), 0.0f);
      const Vec3 to_x = x - e.y;
      ASSERT_NEAR(length(to_x), e.t, 1e-5);
      ASSERT_GT(dot(normalize(to_x), refracted_light(light, e.n)), 1.0f - 1e-5f);
    }
  }
  // Most of the sphere sees the light (the rest lies in the shadow of total internal reflection).
  EXPECT_GT(solutions, 15000);
}

// Completeness of the solver (every exit point a forward-traced refracted ray passes through is
// found again) is tested with the reflection chains', as their case of no reflection:
// ManifoldChains.FindsEveryForwardTracedPath in tests/test_manifold_chains.cpp.

// The refraction's volume Jacobian by central differences at distance t along the refracted ray.
double numerical_jacobian(Vec3 n0, Vec3 light, double t) {
  return numerical_volume_jacobian(n0, refracted_light(light, n0), [&](Vec3 n) {
    return kCentre + n * kRadius + refracted_light(light, n) * static_cast<float>(t);
  });
}

TEST(ManifoldSphere, JacobianMatchesFiniteDifferences) {
  TestRng rng(3);
  for (int k = 0; k < 200; ++k) {
    const Vec3 light = sample_uniform_sphere(rng.uniform2());
    Vec3 n = sample_uniform_sphere(rng.uniform2());
    if (dot(n, light) < 0.2f) continue;
    const double chord = -2 * kRadius * dot(n, refracted_light(light, n));
    const double t = chord * rng.uniform();
    const double analytic = refraction_volume_jacobian(n, light, kEta, 1.0 / kRadius, t);
    const double numeric = numerical_jacobian(n, light, t);
    ASSERT_NEAR(analytic, numeric, 2e-3 * (1 + numeric)) << "t " << t;
  }
  // A flat boundary: the Jacobian is the refracted cosine, whatever the distance.
  const Vec3 n{0, 0, 1}, light = normalize(Vec3{0.5f, 0.2f, 1});
  EXPECT_NEAR(refraction_volume_jacobian(n, light, kEta, 0.0, 3.0),
              -dot(n, refracted_light(light, n)), 1e-6);
}

// Change of variables: integrating J over the lit hemisphere and the chord inside, divided by
// the number of exits x has, gives the volume the refracted light reaches, the sphere's volume
// times the share of uniformly drawn interior points that have an exit. Sampled uniformly in
// dA dt; each term is bounded, so the measured standard errors are reliable.
TEST(ManifoldSphere, JacobianIntegratesToTheVolume) {
  TestRng rng(4);
  const Vec3 light = normalize(Vec3{1, 1, 1});
  test::MeanEstimator estimate;
  // Measure of (y, t): the lit hemisphere's area 2 pi R^2 times the chord, sampled as
  // cos_theta uniform (area-uniform on the hemisphere) and t uniform on the chord.
  for (int k = 0; k < 200000; ++k) {
    const float c = rng.uniform(), phi = 2 * kPi * rng.uniform();
    const float s = std::sqrt(std::max(0.0f, 1 - c * c));
    const Frame f = Frame::from_normal(light);
    const Vec3 n = normalize(f.to_world({s * std::cos(phi), s * std::sin(phi), c}));
    const Vec3 w = refracted_light(light, n);
    const double chord = -2.0 * kRadius * dot(n, w);
    const double t = chord * rng.uniform();
    const Vec3 x = kCentre + n * kRadius + w * static_cast<float>(t);
    const SphereExits exits = sphere_exits_toward_light(kCentre, kRadius, kEta, light, x);
    if (exits.count == 0) {
      estimate.add(0.0);
      continue;
    }
    const double measure = 2 * kPi * kRadius * kRadius * chord;
    estimate.add(measure * refraction_volume_jacobian(n, light, kEta, 1.0 / kRadius, t) /
                 exits.count);
  }
  const test::MeanEstimator lit = lit_volume(rng, [&](Vec3 x) {
    return sphere_exits_toward_light(kCentre, kRadius, kEta, light, x).count > 0;
  });
  expect_lit_volume(estimate, lit, 0.5);
}

// A case-D suffix x_i -> x_j -> exit -> directional light on the sphere, with the manifold
// strategy running at x_j.
SneeSuffix manifold_suffix(TestRng& rng, bool x_i_medium, bool* ok) {
  const Vec3 light = sample_uniform_sphere(rng.uniform2());
  SneeSuffix s;
  s.x_i = random_inside(rng);
  s.omega_in = sample_uniform_sphere(rng.uniform2());
  s.x_j = random_inside(rng);
  const SphereExits exits = sphere_exits_toward_light(kCentre, kRadius, kEta, light, s.x_j);
  *ok = exits.count > 0;
  if (!*ok) return s;
  s.x_k = exits.exit[0].y;
  s.n_k = s.ns_k = exits.exit[0].n;
  s.omega_o = light;
  s.medium = {Rgb(2.0f), Rgb(2.02f), 0.3f};
  s.interface = {kEta, 0.0f};
  s.light_pdf = 0.5f;
  s.light_delta = true;
  s.light_distant = true;
  s.v_first = rng.uniform() < 0.7f;
  s.x_i_medium = x_i_medium;
  s.x_j_medium = true;
  s.manifold = true;
  s.boundary_curvature = 1.0f / kRadius;
  return s;
}

TEST(ManifoldSphere, WeightsWithTopToBottomSumToOne) {
  TestRng rng(5);
  for (const MisHeuristic h : {MisHeuristic::kBalance, MisHeuristic::kPower}) {
    SneeOptions options;
    options.heuristic = h;
    int shared = 0;
    for (int k = 0; k < 20000; ++k) {
      const bool x_i_medium = rng.uniform() < 0.8f;
      bool ok = false;
      SneeSuffix s = manifold_suffix(rng, x_i_medium, &ok);
      if (!ok) continue;
      const StrategyPdfs p = strategy_pdfs(s, options);
      const double w_tb = mis_weight(Strategy::kTopToBottom, p, options);
      const double w_mn = mis_weight(Strategy::kManifold, p, options);
      for (const Strategy st : {Strategy::kBottomToTop, Strategy::kUnidirectionalBsdf,
                                Strategy::kUnidirectionalLight}) {
        ASSERT_EQ(mis_weight(st, p, options), 0.0);
      }
      ASSERT_GT(w_mn, 0.0);
      ASSERT_NEAR(w_tb + w_mn, 1.0, 1e-9);
      if (snee_can_produce(s)) {
        ASSERT_GT(w_tb, 0.0);
        ASSERT_EQ(p[Strategy::kManifold], manifold_pdf(s));
        ++shared;
      } else {
        ASSERT_EQ(w_mn, 1.0);  // a surface x_i or V_first = 0: nothing else can make it
      }
      // Where the manifold strategy does not run (the walk's depth limit), TB takes it all.
      s.manifold = false;
      const StrategyPdfs alone = strategy_pdfs(s, options);
      ASSERT_EQ(mis_weight(Strategy::kManifold, alone, options), 0.0);
      if (snee_can_produce(s)) {
        ASSERT_EQ(mis_weight(Strategy::kTopToBottom, alone, options), 1.0);
      }
    }
    EXPECT_GT(shared, 5000);
  }
}

// Disabled in the handled class, the manifold strategy still takes the suffixes nothing else can
// make (a surface x_i), like the tracer's own strategies (StrategySet).
TEST(ManifoldSphere, IsolationOnlyRedistributesTheHandledClass) {
  TestRng rng(6);
  SneeOptions tb_only;
  tb_only.enabled = StrategySet::only(Strategy::kTopToBottom);
  for (int k = 0; k < 2000; ++k) {
    bool ok = false;
    SneeSuffix s = manifold_suffix(rng, true, &ok);
    if (!ok) continue;
    s.v_first = true;
    const StrategyPdfs handled = strategy_pdfs(s, tb_only);
    ASSERT_EQ(mis_weight(Strategy::kManifold, handled, tb_only), 0.0);
    ASSERT_EQ(mis_weight(Strategy::kTopToBottom, handled, tb_only), 1.0);
    s.x_i_medium = false;
    ASSERT_EQ(mis_weight(Strategy::kManifold, strategy_pdfs(s, tb_only), tb_only), 1.0);
  }
}

}  // namespace
}  // namespace snee
