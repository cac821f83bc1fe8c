// The chi-square helper itself: it accepts correct samplers (including ones that fail part of
// the time) and rejects slightly wrong pdfs, wrong normalisation and wrong distances.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/physics/medium/henyey_greenstein.h"
#include "tests/support/chi2.h"

namespace snee {
namespace {

using test::TestRng;

constexpr double kReject = 1e-4;

std::optional<Vec3> hg_draw(TestRng& rng, float g) {
  float pdf = 0;
  return hg_sample(Vec3(0, 0, 1), g, rng.uniform2(), &pdf);
}

TEST(Chi2Sphere, AcceptsSamplerThatFailsWithMatchingPdfIntegral) {
  TestRng rng(31);
  const auto r = test::chi2_sphere(
      [&]() -> std::optional<Vec3> {
        const bool fails = rng.uniform() < 0.3f;
        const auto w = hg_draw(rng, 0.5f);
        return fails ? std::nullopt : w;
      },
      [](Vec3 w) { return 0.7 * hg_phase(w.z, 0.5f); }, {.samples = 500'000});
  EXPECT_GT(r.p_value, kReject) << r.report;
  EXPECT_NEAR(r.integral, 0.7, 1e-5);
}

TEST(Chi2Sphere, RejectsSlightlyWrongShape) {
  TestRng rng(32);
  const auto r =
      test::chi2_sphere([&] { return hg_draw(rng, 0.3f); },
                        [](Vec3 w) { return hg_phase(w.z, 0.32f); }, {.samples = 500'000});
  EXPECT_LT(r.p_value, kReject) << r.report;
}

TEST(Chi2Sphere, RejectsMissingFailures) {
  TestRng rng(33);
  const auto r =
      test::chi2_sphere([&] { return hg_draw(rng, 0.3f); },
                        [](Vec3 w) { return 0.98 * hg_phase(w.z, 0.3f); }, {.samples = 500'000});
  EXPECT_LT(r.p_value, kReject) << r.report;
}

TEST(Chi2Sphere, RejectsMalformedDirections) {
  const auto r = test::chi2_sphere([] { return std::optional<Vec3>(Vec3(0, 0, 2)); },
                                   [](Vec3) { return 1 / (4 * M_PI); }, {.samples = 10});
  EXPECT_EQ(r.p_value, 0.0);
}

TEST(Chi2Distance, AcceptsExponentialAndRejectsWrongRate) {
  for (const double pdf_rate : {1.0, 1.02}) {
    TestRng rng(34);
    const auto r = test::chi2_distance(
        [&]() -> std::optional<double> { return -std::log1p(-double(rng.uniform())); },
        [&](double t) { return pdf_rate * std::exp(-pdf_rate * t); }, {.samples = 500'000});
    if (pdf_rate == 1.0) {
      EXPECT_GT(r.p_value, kReject) << r.report;
      EXPECT_NEAR(r.integral, 1.0, 1e-6);
    } else {
      EXPECT_LT(r.p_value, kReject) << r.report;
    }
  }
}

}  // namespace
}  // namespace snee
