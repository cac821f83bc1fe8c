// The guided exit's direction sampler (kernels/physics/snee/exit_guide.h, docs/method.md 3.15):
// its axes point at the sphere's exit points that refract a small light toward the vertex, its
// samples follow its density (chi-square per cap), the density integrates to the share of the
// targets that have axes, and the exit distance lands on the sphere.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/physics/snee/exit_guide.h"
#include "tests/support/chi2.h"

namespace snee {
namespace {

// Two targets: a light above and to the side (distant) and a point light on the other side.
ProbeTargets two_targets() {
  ProbeTargets targets;
  targets.count = 2;
  targets.target[0] = {normalize(Vec3(1, 1, 1)), false, 0.75f};
  targets.target[1] = {Vec3(-2.5f, 0.5f, 1.0f), true, 0.25f};
  targets.uniform_share = 0;
  return targets;
}

constexpr float kEta = 1.5f;

TEST(ExitGuide, AxesLeadToExitPointsThatRefractTheLight) {
  const ProbeTargets targets = two_targets();
  const Vec3 x(0.2f, -0.3f, 0.1f);
  const ExitGuide guide = exit_guide(targets, {0, 0, 0}, 1.0f, kEta, x);
  ASSERT_GE(guide.count, 2);
  float total = 0;
  for (int k = 0; k < guide.count; ++k) {
    const Vec3 axis = guide.axis[static_cast<size_t>(k)];
    EXPECT_NEAR(length(axis), 1.0f, 1e-5f);
    const Vec3 y = x + axis * sphere_exit_distance({0, 0, 0}, 1.0f, x, axis);
    EXPECT_NEAR(length(y), 1.0f, 1e-4f);
    // Snell's law at y between the direction inside (axis) and the light's direction outside
    // (one of the two targets): the tangential parts differ by the index.
    const Vec3 n = normalize(y);
    const auto tangential = [&](Vec3 w) { return length(w - n * dot(w, n)); };
    const Vec3 to_distant = targets.target[0].where;
    const Vec3 to_point = normalize(targets.target[1].where - y);
    const float inside = kEta * tangential(axis);
    EXPECT_TRUE(std::fabs(inside - tangential(to_distant)) < 1e-3f ||
                std::fabs(inside - tangential(to_point)) < 1e-3f)
        << "axis " << k;
    total += guide.probability[static_cast<size_t>(k)];
  }
  EXPECT_NEAR(total, 1.0f, 1e-5f);
}

TEST(ExitGuide, SphereExitDistanceLandsOnTheSphere) {
  test::TestRng rng(3);
  const Vec3 centre(0.5f, -1.0f, 2.0f);
  for (int i = 0; i < 10000; ++i) {
    const Vec3 x = centre + sample_uniform_sphere(rng.uniform2()) * (1.9f * rng.uniform());
    const Vec3 w = sample_uniform_sphere(rng.uniform2());
    const float t = sphere_exit_distance(centre, 2.0f, x, w);
    ASSERT_GT(t, 0.0f);
    ASSERT_NEAR(length(x + w * t - centre), 2.0f, 1e-4f);
  }
}

// Each cap alone: draws from the other caps count as failures, so the cap's own probability is
// what its density must integrate to.
TEST(ExitGuide, SamplesFollowTheirDensity) {
  const ProbeTargets targets = two_targets();
  const Vec3 x(0.2f, -0.3f, 0.1f);
  const ExitGuide guide = exit_guide(targets, {0, 0, 0}, 1.0f, kEta, x);
  const float cap = exit_guide_cap_cosine(5.0f);
  int tested = 0;
  for (int k = 0; k < guide.count; ++k) {
    const Vec3 axis = guide.axis[static_cast<size_t>(k)];
    bool overlaps = false;
    for (int j = 0; j < guide.count; ++j) {
      if (j != k && dot(axis, guide.axis[static_cast<size_t>(j)]) > std::cos(0.2f)) overlaps = true;
    }
    if (overlaps) continue;  // the per-cap density below would miss the other cap's part
    ++tested;
    test::TestRng rng(11 + static_cast<uint64_t>(k));
    const auto r = test::chi2_sphere(
        [&]() -> std::optional<Vec3> {
          const float u_axis = rng.uniform();
          Vec3 w;
          if (!exit_guide_sample(guide, cap, u_axis, rng.uniform2(), &w)) return std::nullopt;
          if (dot(w, axis) < cap) return std::nullopt;  // another cap
          return w;
        },
        [&](Vec3 w) {
          return dot(w, axis) >= cap
                     ? guide.probability[static_cast<size_t>(k)] / (2.0 * kPi * (1.0 - cap))
                     : 0.0;
        },
        {.axis = axis, .cos_min = cap, .cos_bins = 10, .phi_bins = 20, .samples = 400'000});
    EXPECT_GT(r.p_value, 1e-4) << "cap " << k << ": " << r.report;
    // The evaluated density of the whole guide agrees with the cap's inside it.
    for (int i = 0; i < 100; ++i) {
      Vec3 w;
      if (!exit_guide_sample(guide, cap, rng.uniform(), rng.uniform2(), &w) || dot(w, axis) < cap)
        continue;
      EXPECT_NEAR(exit_guide_pdf(guide, cap, w),
                  guide.probability[static_cast<size_t>(k)] / (2.0f * kPi * (1.0f - cap)), 1e-2f);
    }
  }
  EXPECT_GE(tested, 2);
}

// Over the sphere of directions the density integrates to the shares of the targets that have
// axes (all of them here); estimated with uniform directions, within 4 standard errors.
TEST(ExitGuide, DensityIntegratesToTheUsedShare) {
  const ProbeTargets targets = two_targets();
  const Vec3 x(-0.1f, 0.4f, -0.2f);
  const ExitGuide guide = exit_guide(targets, {0, 0, 0}, 1.0f, kEta, x);
  ASSERT_GT(guide.count, 0);
  float used = 0;
  for (int k = 0; k < guide.count; ++k) used += guide.probability[static_cast<size_t>(k)];
  const float cap = exit_guide_cap_cosine(8.0f);
  test::TestRng rng(5);
  const int n = 2'000'000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double v = exit_guide_pdf(guide, cap, sample_uniform_sphere(rng.uniform2())) * 4.0 * kPi;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n;
  const double error = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, used, 4 * error) << "+- " << error;
  // Without targets there are no axes.
  ProbeTargets none;
  EXPECT_EQ(exit_guide(none, {0, 0, 0}, 1.0f, kEta, x).count, 0);
}

}  // namespace
}  // namespace snee
