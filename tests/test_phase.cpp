// Henyey-Greenstein phase function: normalisation, mean cosine, sampler pdf and chi-square.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>

#include "kernels/physics/medium/henyey_greenstein.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::TestRng;

constexpr float kGs[] = {-0.9f, -0.7f, -0.3f, -1e-4f, 0.0f, 1e-4f, 0.3f, 0.7f, 0.9f, 0.99f};

// Quadrature converges to ~1e-10 in 1D; the float phase function limits agreement to ~1e-6.
constexpr double kQuadratureTolerance = 1e-5;

TEST(HenyeyGreenstein, IntegratesToOne) {
  for (const float g : kGs) {
    const double integral =
        2 * M_PI *
        test::integrate_interval([&](double mu) { return hg_phase(float(mu), g); }, -1, 1);
    EXPECT_NEAR(integral, 1.0, kQuadratureTolerance) << "g " << g;
  }
}

TEST(HenyeyGreenstein, MeanCosineIsG) {
  for (const float g : kGs) {
    const double mean =
        2 * M_PI *
        test::integrate_interval([&](double mu) { return mu * hg_phase(float(mu), g); }, -1, 1);
    EXPECT_NEAR(mean, g, kQuadratureTolerance) << "g " << g;
  }
}

// The reported pdf is the phase function at the cosine actually produced. Float rounding of the
// direction perturbs that cosine by a few ulps; the pdf's relative sensitivity to it is
// |d ln p / d mu| = 3|g| / (1 + g^2 - 2 g mu), which scales the tolerance.
TEST(HenyeyGreenstein, SamplePdfMatchesPhase) {
  TestRng rng(3);
  const Vec3 w_before = normalize(Vec3(0.3f, -0.5f, 0.8f));
  for (const float g : kGs) {
    test::MeanEstimator mean_cos;
    for (int k = 0; k < 200000; ++k) {
      float pdf = 0;
      const Vec3 w = hg_sample(w_before, g, rng.uniform2(), &pdf);
      ASSERT_NEAR(length(w), 1.0f, 8 * FLT_EPSILON);
      const float mu = dot(w_before, w);
      const float sensitivity = 3 * std::fabs(g) / (1 + g * g - 2 * g * mu);
      ASSERT_NEAR(pdf / hg_phase(mu, g), 1.0f, 16 * FLT_EPSILON * (1 + sensitivity))
          << "g " << g << " mu " << mu;
      mean_cos.add(mu);
    }
    EXPECT_LT(std::fabs(mean_cos.mean() - g), 4 * mean_cos.standard_error()) << "g " << g;
  }
}

TEST(HenyeyGreenstein, SamplesFollowPhase) {
  TestRng rng(4);
  const Vec3 w_before = normalize(Vec3(-0.2f, 0.9f, 0.1f));
  for (const float g : {-0.7f, 0.0f, 1e-4f, 0.3f, 0.9f}) {
    // Strong forward scattering concentrates the mass within 1 - mu ~ (1 - g)^2 / g of the axis.
    const double cos_min = g > 0.5f ? 1.0 - 40.0 * (1 - g) * (1 - g) / g : -1.0;
    const auto r = test::chi2_sphere(
        [&]() -> std::optional<Vec3> {
          float pdf = 0;
          return hg_sample(w_before, g, rng.uniform2(), &pdf);
        },
        [&](Vec3 w) { return hg_phase(dot(w_before, w), g); },
        {.axis = g < 0 ? -w_before : w_before,
         .cos_min = g < 0 ? -1.0 : cos_min,
         .samples = 1'000'000});
    EXPECT_GT(r.p_value, 1e-4) << "g " << g << ": " << r.report;
  }
}

}  // namespace
}  // namespace snee
