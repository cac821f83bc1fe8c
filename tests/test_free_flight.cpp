// Spectral-MIS free-flight sampling: normalisation, survival, chi-square, and unbiasedness of the
// collision/pass-through estimator for every channel (including a channel with sigma = 0).
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/medium/free_flight.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::TestRng;

struct Case {
  const char* name;
  Rgb sigma_t;
};
constexpr Case kCases[] = {
    {"grey", Rgb(2.0f)},
    {"chromatic", Rgb(0.5f, 1.0f, 4.0f)},
    {"clear channel", Rgb(0.0f, 1.0f, 3.0f)},
};

// Fraction of channels that can stop the flight: the pdf's integral, the rest being t = inf.
double finite_fraction(Rgb sigma_t) {
  return ((sigma_t.x > 0) + (sigma_t.y > 0) + (sigma_t.z > 0)) / 3.0;
}

// 1D quadrature converges to ~1e-10; float evaluation of the pdf limits it to ~1e-6.
constexpr double kQuadratureTolerance = 1e-5;

TEST(FreeFlight, PdfIntegratesToFiniteFraction) {
  for (const Case& c : kCases) {
    const double integral = test::integrate_interval(
        [&](double t) { return free_flight_pdf(c.sigma_t, float(t)); }, 0, INFINITY);
    EXPECT_NEAR(integral, finite_fraction(c.sigma_t), kQuadratureTolerance) << c.name;
  }
}

TEST(FreeFlight, SurvivalIsOneMinusCdf) {
  for (const Case& c : kCases) {
    for (const float d : {0.0f, 0.1f, 0.7f, 2.0f, 10.0f}) {
      const double cdf = test::integrate_interval(
          [&](double t) { return free_flight_pdf(c.sigma_t, float(t)); }, 0, d);
      EXPECT_NEAR(free_flight_survival(c.sigma_t, d), 1.0 - cdf, kQuadratureTolerance)
          << c.name << " d " << d;
    }
    EXPECT_NEAR(free_flight_survival(c.sigma_t, INFINITY), 1.0 - finite_fraction(c.sigma_t), 1e-7)
        << c.name;
    const Rgb t_inf = transmittance(c.sigma_t, INFINITY);
    for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(t_inf[ch], c.sigma_t[ch] > 0 ? 0.0f : 1.0f) << c.name;
  }
}

TEST(FreeFlight, SamplesFollowPdf) {
  TestRng rng(5);
  for (const Case& c : kCases) {
    const auto r = test::chi2_distance(
        [&]() -> std::optional<double> {
          const float u_channel = rng.uniform();
          return free_flight_sample(c.sigma_t, u_channel, rng.uniform());
        },
        [&](double t) { return free_flight_pdf(c.sigma_t, float(t)); },
        {.scale = 1.0 / average(c.sigma_t), .samples = 2'000'000});
    EXPECT_GT(r.p_value, 1e-4) << c.name << ": " << r.report;
    EXPECT_NEAR(r.integral, finite_fraction(c.sigma_t), kQuadratureTolerance) << c.name;
  }
}

// A medium slab of depth d: per channel, the collision estimate sigma e^{-sigma t} / pdf(t) for
// t < d plus the pass-through estimate e^{-sigma d} / survival(d) for t >= d must average to
// (1 - e^{-sigma d}) + e^{-sigma d} = 1, with each part matching its own closed form.
TEST(FreeFlight, SpectralMisEstimatorIsUnbiased) {
  TestRng rng(6);
  for (const Case& c : kCases) {
    for (const float d : {0.3f, 1.5f}) {
      test::MeanEstimator total[3], collided[3];
      for (int k = 0; k < 1'000'000; ++k) {
        const float u_channel = rng.uniform();
        const float t = free_flight_sample(c.sigma_t, u_channel, rng.uniform());
        const bool collides = t < d;
        const float pdf =
            collides ? free_flight_pdf(c.sigma_t, t) : free_flight_survival(c.sigma_t, d);
        for (int ch = 0; ch < 3; ++ch) {
          const float sigma = c.sigma_t[ch];
          const double collision = collides ? sigma * std::exp(-sigma * t) / pdf : 0.0;
          const double pass = collides ? 0.0 : channel_transmittance(sigma, d) / pdf;
          total[ch].add(collision + pass);
          collided[ch].add(collision);
        }
      }
      for (int ch = 0; ch < 3; ++ch) {
        const double expected_collided = 1.0 - std::exp(-double(c.sigma_t[ch]) * d);
        EXPECT_LT(std::fabs(total[ch].mean() - 1.0), 4 * total[ch].standard_error() + 1e-6)
            << c.name << " d " << d << " channel " << ch << ": " << total[ch].mean();
        EXPECT_LT(std::fabs(collided[ch].mean() - expected_collided),
                  4 * collided[ch].standard_error() + 1e-6)
            << c.name << " d " << d << " channel " << ch << ": " << collided[ch].mean();
      }
    }
  }
}

}  // namespace
}  // namespace snee
