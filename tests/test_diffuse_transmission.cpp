// Diffuse transmitter (thin sheet): sampling on both sides of the sheet, pdf and value
// consistency, chi-square over the whole sphere, the pdf integrating to 1, and the expected
// weight per channel being R + T (all light scattered when R + T = 1).
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/physics/bsdf/diffuse_transmission.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::TestRng;

const DiffuseTransmissionParams kSheet{{0.2f, 0.5f, 0.1f}, {0.7f, 0.3f, 0.6f}};

TEST(DiffuseTransmission, SampleMatchesEvalAndPdfOnBothSides) {
  TestRng rng(41);
  for (const float side : {1.0f, -1.0f}) {
    const Vec3 wo = normalize(Vec3(0.3f, -0.2f, side * 0.7f));
    int transmitted = 0;
    constexpr int kSamples = 20000;
    for (int k = 0; k < kSamples; ++k) {
      const BsdfSample s = diffuse_transmission_sample(kSheet, wo, rng.uniform2(), rng.uniform());
      ASSERT_TRUE(s.valid);
      EXPECT_FALSE(s.delta);
      EXPECT_EQ(s.transmission, s.wi.z * wo.z < 0.0f);
      transmitted += s.transmission;
      EXPECT_EQ(s.f, diffuse_transmission_eval(wo, s.wi));
      EXPECT_EQ(s.pdf, diffuse_transmission_pdf(kSheet, wo, s.wi));
      EXPECT_EQ(diffuse_transmission_tint(kSheet, wo, s.wi),
                s.transmission ? kSheet.transmittance : kSheet.reflectance);
    }
    // Transmission is chosen with probability sum(T) / (sum(R) + sum(T)) = 1.6 / 2.4.
    const double p = 1.6 / 2.4;
    EXPECT_NEAR(transmitted / double(kSamples), p, 5 * std::sqrt(p * (1 - p) / kSamples));
  }
}

TEST(DiffuseTransmission, SamplesFollowPdf) {
  TestRng rng(42);
  for (const float side : {1.0f, -1.0f}) {
    const Vec3 wo = normalize(Vec3(-0.5f, 0.1f, side * 0.4f));
    const auto r = test::chi2_sphere(
        [&]() -> std::optional<Vec3> {
          const BsdfSample s =
              diffuse_transmission_sample(kSheet, wo, rng.uniform2(), rng.uniform());
          return s.valid ? std::optional<Vec3>(s.wi) : std::nullopt;
        },
        [&](Vec3 wi) { return diffuse_transmission_pdf(kSheet, wo, wi); }, {.samples = 1'000'000});
    EXPECT_GT(r.p_value, 1e-4) << r.report;
    EXPECT_NEAR(r.integral, 1.0, 1e-5);
    EXPECT_EQ(r.success_fraction, 1.0);
  }
}

// The expected weight f |cos| / pdf times the tint is R + T per channel: the albedo the
// renderer's furnace test relies on.
TEST(DiffuseTransmission, MeanWeightIsReflectancePlusTransmittance) {
  TestRng rng(43);
  const Vec3 wo = normalize(Vec3(0.1f, 0.4f, 0.6f));
  test::MeanEstimator channel[3];
  for (int k = 0; k < 200'000; ++k) {
    const BsdfSample s = diffuse_transmission_sample(kSheet, wo, rng.uniform2(), rng.uniform());
    const Rgb w = diffuse_transmission_tint(kSheet, wo, s.wi) * (s.f * std::fabs(s.wi.z) / s.pdf);
    for (int c = 0; c < 3; ++c) channel[c].add(w[c]);
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(channel[c].mean(), kSheet.reflectance[c] + kSheet.transmittance[c],
                5 * channel[c].standard_error())
        << c;
  }
}

// A black lobe is never sampled.
TEST(DiffuseTransmission, BlackLobeIsNeverChosen) {
  TestRng rng(44);
  const DiffuseTransmissionParams no_reflection{Rgb(0.0f), Rgb(0.8f)};
  const Vec3 wo(0, 0, 1);
  for (int k = 0; k < 1000; ++k) {
    const BsdfSample s =
        diffuse_transmission_sample(no_reflection, wo, rng.uniform2(), rng.uniform());
    ASSERT_TRUE(s.valid);
    EXPECT_TRUE(s.transmission);
  }
  EXPECT_EQ(diffuse_transmission_pdf(no_reflection, wo, Vec3(0, 0, 1)), 0.0f);
}

}  // namespace
}  // namespace snee
