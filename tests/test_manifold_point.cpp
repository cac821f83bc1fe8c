// The manifold strategy's exit points and reflection chains on the smooth sphere for a point
// (or spot) light (docs/method.md 3.10, 3.12): every solution obeys Snell's law for the ray
// arriving from the light, none that a forward-traced ray or chain makes is missed, and the
// volume Jacobians, whose refracted directions now turn with the direction to the light, agree
// with finite differences of the map (y, t) -> x and integrate to the volume the light reaches.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

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

// A light position outside the sphere, from just above its surface to eight radii away.
Vec3 random_light(TestRng& rng) {
  const float distance = kRadius * (1.05f + 7.0f * rng.uniform());
  return kCentre + sample_uniform_sphere(rng.uniform2()) * distance;
}

// The light from `light` refracted into the sphere at outward normal n (point y on the sphere):
// the inside propagation direction; false under total internal reflection.
bool refracted_from(Vec3 light, Vec3 n, Vec3* wt) {
  const Vec3 y = kCentre + n * kRadius;
  return refract(normalize(light - y), n, 1.0f / kEta, wt);
}

TEST(ManifoldPoint, SolutionsObeySnellsLaw) {
  TestRng rng(31);
  int solutions = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 light = random_light(rng);
    const Vec3 x = random_inside(rng);
    const SphereExits exits = sphere_exits_toward_point(kCentre, kRadius, kEta, light, x);
    for (int i = 0; i < exits.count; ++i) {
      const SphereExit& e = exits.exit[static_cast<size_t>(i)];
      ++solutions;
      ASSERT_NEAR(length(e.y - kCentre), kRadius, 1e-5f);
      ASSERT_GT(dot(e.n, light - e.y), 0.0f) << "the exit point must see the light";
      const Vec3 to_x = x - e.y;
      ASSERT_NEAR(length(to_x), e.t, 1e-5);
      Vec3 wt;
      ASSERT_TRUE(refracted_from(light, e.n, &wt));
      ASSERT_GT(dot(normalize(to_x), wt), 1.0f - 1e-5f);
      ASSERT_GT(dot(e.omega_r, wt), 1.0f - 1e-5f);
    }
  }
  // A light close to the sphere lights a small cap: fewer points see it than under a
  // directional light.
  EXPECT_GT(solutions, 10000);
  // A light inside the sphere has no exit points to refract through.
  EXPECT_EQ(
      sphere_exits_toward_point(kCentre, kRadius, kEta, kCentre, kCentre + Vec3(0.1f, 0, 0)).count,
      0);
}

// A point y of the cap that sees the light, uniform in area: cos(theta) from the axis toward
// the light uniform on (1 / l, 1), l the light's distance in radii.
Vec3 lit_normal(TestRng& rng, Vec3 light) {
  const Vec3 axis = normalize(light - kCentre);
  const float cos_edge = kRadius / length(light - kCentre);
  const float c = cos_edge + (1.0f - cos_edge) * rng.uniform(), phi = 2 * kPi * rng.uniform();
  const float s = std::sqrt(std::max(0.0f, 1 - c * c));
  return normalize(Frame::from_normal(axis).to_world({s * std::cos(phi), s * std::sin(phi), c}));
}

// Completeness: a ray from the light, refracted at a point of the lit cap, passes through x at
// some distance along its chord; the solver, asked from x, must find that point again. The
// only allowed misses are next to the caustic, where two solutions merge (a set of zero volume
// that the squared polynomial's double root hides).
TEST(ManifoldPoint, FindsEveryForwardTracedRay) {
  TestRng rng(32);
  int near_caustic_misses = 0;
  constexpr int kSamples = 30000;
  for (int k = 0; k < kSamples; ++k) {
    const Vec3 light = random_light(rng);
    const Vec3 n = lit_normal(rng, light);
    Vec3 wt;
    if (!refracted_from(light, n, &wt)) continue;
    const Vec3 y = kCentre + n * kRadius;
    const float chord = -2.0f * kRadius * dot(n, wt);
    const float t = chord * (0.001f + 0.998f * rng.uniform());
    const Vec3 x = y + wt * t;
    const SphereExits exits = sphere_exits_toward_point(kCentre, kRadius, kEta, light, x);
    bool match = false;
    for (int i = 0; i < exits.count; ++i)
      match = match || length(exits.exit[static_cast<size_t>(i)].y - y) < 1e-3f;
    if (match) continue;
    const double relative_j = refraction_volume_jacobian(n, normalize(light - y), kEta,
                                                         1.0 / kRadius, t, length(light - y)) /
                              std::abs(dot(n, wt));
    ASSERT_LT(relative_j, 0.002) << "ray " << k << " from " << light.x << " " << light.y << " "
                                 << light.z << " missed at t " << t << " of " << chord;
    ++near_caustic_misses;
  }
  std::cout << kSamples << " forward-traced rays, " << near_caustic_misses
            << " missed next to the caustic\n";
  EXPECT_LT(near_caustic_misses, kSamples / 1000);
}

// Change of variables, as for the directional light: J integrated over the lit cap and the
// chord inside, each (y, t) divided by the number of exits its x has, is the volume the light
// reaches, the sphere's volume times the share of uniform interior points that have an exit.
TEST(ManifoldPoint, JacobianIntegratesToTheVolume) {
  TestRng rng(34);
  for (const float distance : {1.6f, 4.0f}) {
    const Vec3 light = kCentre + normalize(Vec3{1, 1, 1}) * (distance * kRadius);
    const double cap = 2 * kPi * kRadius * kRadius * (1.0 - 1.0 / distance);
    test::MeanEstimator estimate;
    for (int k = 0; k < 200000; ++k) {
      const Vec3 n = lit_normal(rng, light);
      const Vec3 y = kCentre + n * kRadius;
      Vec3 w;
      if (!refracted_from(light, n, &w)) {
        estimate.add(0.0);
        continue;
      }
      const double chord = -2.0 * kRadius * dot(n, w);
      const double t = chord * rng.uniform();
      const Vec3 x = y + w * static_cast<float>(t);
      const SphereExits exits = sphere_exits_toward_point(kCentre, kRadius, kEta, light, x);
      if (exits.count == 0) {
        estimate.add(0.0);
        continue;
      }
      estimate.add(cap * chord *
                   refraction_volume_jacobian(n, normalize(light - y), kEta, 1.0 / kRadius, t,
                                              length(light - y)) /
                   exits.count);
    }
    const test::MeanEstimator lit = lit_volume(rng, [&](Vec3 x) {
      return sphere_exits_toward_point(kCentre, kRadius, kEta, light, x).count > 0;
    });
    std::cout << "light at " << distance << " radii: integral of J " << estimate.mean() << " +- "
              << estimate.standard_error() << ", lit volume " << lit.mean() << " +- "
              << lit.standard_error() << "\n";
    expect_lit_volume(estimate, lit, 0.3);
  }
}

// A chain from the point light entering at n, traced forward: the entry's direction toward the
// light, then trace_forward.
ForwardChain trace_from(Vec3 light, Vec3 n, int reflections) {
  return trace_forward(normalize(light - (kCentre + n * kRadius)), n, reflections);
}

// Completeness of the chain solver under a point light: every chain traced forward from the
// light, with 1 to 6 reflections, is found again from a point on its last chord (misses only
// next to the caustic, as for the direct exits).
TEST(ManifoldPoint, ChainsFindEveryForwardTracedPath) {
  TestRng rng(35);
  int near_caustic_misses = 0, found = 0;
  constexpr int kSamples = 20000;
  for (int k = 0; k < kSamples; ++k) {
    const Vec3 light = random_light(rng);
    const Vec3 n = lit_normal(rng, light);
    const Vec3 y = kCentre + n * kRadius;
    if (!(dot(n, normalize(light - y)) > 1e-3f)) continue;
    const int reflections = 1 + static_cast<int>(rng.uniform() * 6);
    const ForwardChain f = trace_from(light, n, reflections);
    const float t = f.chord * (0.001f + 0.998f * rng.uniform());
    const Vec3 x = f.at(t);
    const SphereChains chains =
        sphere_reflection_chains_toward_point(kCentre, kRadius, kEta, light, x, reflections);
    bool match = false;
    for (int i = 0; i < chains.count; ++i) {
      const SphereChain& c = chains.chain[static_cast<size_t>(i)];
      match = match || length(c.y - y) < 1e-3f;
      // Every chain found is one: it enters facing the light and its last chord reaches x.
      ASSERT_GT(dot(c.n, light - c.y), 0.0f);
      const ForwardChain back = trace_from(light, c.n, reflections);
      ASSERT_LT(length(back.at(c.t_last) - x), 1e-3f * kRadius);
    }
    if (match) {
      ++found;
      continue;
    }
    const double relative_j =
        sphere_chain_volume_jacobian(n, normalize(light - y), kEta, reflections, t / kRadius,
                                     length(light - y) / kRadius) /
        std::abs(dot(n, f.direction));
    ASSERT_LT(relative_j, 0.002) << "chain " << k << " with " << reflections << " reflections";
    ++near_caustic_misses;
  }
  std::cout << found << " forward-traced chains found again, " << near_caustic_misses
            << " missed next to the caustic\n";
  EXPECT_GT(found, kSamples / 2);
  EXPECT_LT(near_caustic_misses, kSamples / 1000);
}

// The chain's volume Jacobian by central differences at distance t along its last chord (no
// reflection: the refraction's).
double numerical_chain_jacobian(Vec3 n0, Vec3 light, int reflections, double t) {
  return numerical_volume_jacobian(n0, trace_from(light, n0, reflections).direction,
                                   [&](Vec3 n) { return trace_from(light, n, reflections).at(t); });
}

TEST(ManifoldPoint, JacobiansMatchFiniteDifferences) {
  TestRng rng(36);
  int checked = 0;
  for (int k = 0; k < 400; ++k) {
    const Vec3 light = random_light(rng);
    const Vec3 n = lit_normal(rng, light);
    const Vec3 y = kCentre + n * kRadius;
    const Vec3 toward = normalize(light - y);
    if (dot(n, toward) < 0.2f) continue;
    const int reflections = static_cast<int>(rng.uniform() * 7);
    const ForwardChain f = trace_from(light, n, reflections);
    const double t = f.chord * rng.uniform();
    const double distance = length(light - y);
    const double exact =
        sphere_chain_volume_jacobian(n, toward, kEta, reflections, t / kRadius, distance / kRadius);
    const double numeric = numerical_chain_jacobian(n, light, reflections, t);
    ASSERT_NEAR(exact, numeric, 3e-3 * (1 + numeric)) << reflections << " reflections, t " << t;
    if (reflections == 0) {
      ASSERT_NEAR(exact, refraction_volume_jacobian(n, toward, kEta, 1.0 / kRadius, t, distance),
                  1e-6 * (1 + exact));
    }
    ++checked;
  }
  EXPECT_GT(checked, 100);
  // Far away the light's directions stop turning: the directional Jacobian is the limit.
  const Vec3 n = normalize(Vec3{0.2f, 0.3f, 1}), toward = normalize(Vec3{0.5f, 0.2f, 1});
  EXPECT_NEAR(refraction_volume_jacobian(n, toward, kEta, 1.0 / kRadius, 0.7, 1e7),
              refraction_volume_jacobian(n, toward, kEta, 1.0 / kRadius, 0.7), 1e-6);
}

// The change of variables per reflection count, as for the directional light's chains: J over
// the lit cap and the last chord, divided by the number of m-reflection chains each x has, is
// the volume such chains reach (the whole sphere from two reflections on).
TEST(ManifoldPoint, ChainJacobianIntegratesToTheVolumeTheChainsReach) {
  const float distance = 2.5f;
  const Vec3 light = kCentre + normalize(Vec3{1, -1, 1}) * (distance * kRadius);
  const double cap = 2 * kPi * kRadius * kRadius * (1.0 - 1.0 / distance);
  for (int m = 1; m <= 3; ++m) {
    TestRng rng(static_cast<uint64_t>(40 + m));
    test::MeanEstimator estimate;
    for (int k = 0; k < 100000; ++k) {
      const Vec3 n = lit_normal(rng, light);
      const Vec3 y = kCentre + n * kRadius;
      const ForwardChain chain = trace_from(light, n, m);
      const double t = chain.chord * rng.uniform();
      const int count =
          sphere_reflection_chains_toward_point(kCentre, kRadius, kEta, light, chain.at(t), m)
              .count;
      if (count == 0) {
        estimate.add(0.0);
        continue;
      }
      estimate.add(cap * chain.chord *
                   sphere_chain_volume_jacobian(n, normalize(light - y), kEta, m, t / kRadius,
                                                length(light - y) / kRadius) /
                   count);
    }
    const test::MeanEstimator reached = lit_volume(rng, [&](Vec3 x) {
      return sphere_reflection_chains_toward_point(kCentre, kRadius, kEta, light, x, m).count > 0;
    });
    std::cout << m << " reflections: integral of J " << estimate.mean() << " +- "
              << estimate.standard_error() << ", volume reached " << reached.mean() << " +- "
              << reached.standard_error() << "\n";
    // Long chains' Jacobians vary more over the cap: measured to 2%, as the directional ones.
    expect_lit_volume(estimate, reached, 0.3, 0.02);
  }
}

}  // namespace
}  // namespace snee
