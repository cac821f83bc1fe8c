// The manifold strategy's exit points on the smooth sphere for a point (or spot) light
// (docs/method.md 3.10): every solution obeys Snell's law for the ray arriving from the light,
// none that a forward-traced ray makes is missed, and the volume Jacobian, whose refracted
// directions now turn with the direction to the light, agrees with finite differences of the
// map (y, t) -> x and integrates to the volume the refracted light reaches.
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

// |det(dx/du, dx/dv, dx/dt)| for x = y(u, v) + t omega_r(y(u, v)), (u, v) arc lengths on the
// sphere around y, by central differences.
double numerical_jacobian(Vec3 n0, Vec3 light, double t) {
  const Frame f = Frame::from_normal(n0);
  const auto x_of = [&](double u, double v) {
    const Vec3 n = normalize(
        n0 + f.to_world(Vec3(static_cast<float>(u / kRadius), static_cast<float>(v / kRadius), 0)));
    Vec3 wt;
    EXPECT_TRUE(refracted_from(light, n, &wt));
    return kCentre + n * kRadius + wt * static_cast<float>(t);
  };
  const double h = 1e-3;
  const Vec3 du = (x_of(h, 0) - x_of(-h, 0)) / static_cast<float>(2 * h);
  const Vec3 dv = (x_of(0, h) - x_of(0, -h)) / static_cast<float>(2 * h);
  Vec3 wt;
  EXPECT_TRUE(refracted_from(light, n0, &wt));
  return std::abs(dot(cross(du, dv), wt));
}

TEST(ManifoldPoint, JacobianMatchesFiniteDifferences) {
  TestRng rng(33);
  int checked = 0;
  for (int k = 0; k < 400; ++k) {
    const Vec3 light = random_light(rng);
    const Vec3 n = lit_normal(rng, light);
    const Vec3 y = kCentre + n * kRadius;
    const Vec3 toward = normalize(light - y);
    if (dot(n, toward) < 0.2f) continue;
    Vec3 wt;
    ASSERT_TRUE(refracted_from(light, n, &wt));
    const double t = -2 * kRadius * dot(n, wt) * rng.uniform();
    const double analytic =
        refraction_volume_jacobian(n, toward, kEta, 1.0 / kRadius, t, length(light - y));
    const double numeric = numerical_jacobian(n, light, t);
    ASSERT_NEAR(analytic, numeric, 2e-3 * (1 + numeric)) << "t " << t;
    ++checked;
  }
  EXPECT_GT(checked, 100);
  // Far away the light's directions stop turning: the directional Jacobian is the limit.
  const Vec3 n = normalize(Vec3{0.2f, 0.3f, 1}), toward = normalize(Vec3{0.5f, 0.2f, 1});
  EXPECT_NEAR(refraction_volume_jacobian(n, toward, kEta, 1.0 / kRadius, 0.7, 1e7),
              refraction_volume_jacobian(n, toward, kEta, 1.0 / kRadius, 0.7), 1e-6);
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

}  // namespace
}  // namespace snee
