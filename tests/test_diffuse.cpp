// Two-sided Lambertian: sampling on wo's side, pdf and value consistency, chi-square, albedo 1.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/physics/bsdf/diffuse.h"
#include "tests/support/chi2.h"

namespace snee {
namespace {

using test::TestRng;

TEST(Diffuse, SampleMatchesEvalAndPdfOnBothSides) {
  TestRng rng(21);
  for (const float side : {1.0f, -1.0f}) {
    const Vec3 wo = normalize(Vec3(0.3f, -0.2f, side * 0.7f));
    for (int k = 0; k < 10000; ++k) {
      const BsdfSample s = diffuse_sample(wo, rng.uniform2());
      ASSERT_TRUE(s.valid);
      EXPECT_FALSE(s.delta || s.transmission);
      EXPECT_GT(s.wi.z * wo.z, 0.0f);
      EXPECT_EQ(s.f, diffuse_eval(wo, s.wi));
      EXPECT_EQ(s.pdf, diffuse_pdf(wo, s.wi));
      // Cosine sampling makes every weight f |cos| / pdf exactly 1 (times albedo).
      EXPECT_NEAR(s.f * std::fabs(s.wi.z) / s.pdf, 1.0f, 1e-6f);
    }
    EXPECT_EQ(diffuse_eval(wo, Vec3(0, 0, -side)), 0.0f);
    EXPECT_EQ(diffuse_pdf(wo, Vec3(0, 0, -side)), 0.0f);
  }
}

TEST(Diffuse, SamplesFollowPdf) {
  TestRng rng(22);
  for (const float side : {1.0f, -1.0f}) {
    const Vec3 wo = normalize(Vec3(-0.5f, 0.1f, side * 0.4f));
    const auto r = test::chi2_sphere(
        [&]() -> std::optional<Vec3> {
          const BsdfSample s = diffuse_sample(wo, rng.uniform2());
          return s.valid ? std::optional<Vec3>(s.wi) : std::nullopt;
        },
        [&](Vec3 wi) { return diffuse_pdf(wo, wi); },
        {.axis = Vec3(0, 0, side), .samples = 1'000'000});
    EXPECT_GT(r.p_value, 1e-4) << r.report;
    EXPECT_NEAR(r.integral, 1.0, 1e-5);
  }
}

}  // namespace
}  // namespace snee
