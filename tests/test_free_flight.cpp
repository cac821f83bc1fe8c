// Spectral-MIS free-flight sampling: normalisation, survival, chi-square, and unbiasedness of the
// collision/pass-through estimator for every channel (including a channel with sigma = 0).
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/physics/medium/free_flight.h"
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

// Weighted channel mixtures (the path tracer's carried channel probabilities): the pdf still
// integrates to the stopping channels' share, survival is one minus its cdf, and samples follow
// it.
TEST(FreeFlight, WeightedMixtureIsConsistent) {
  const Rgb weights(0.6f, 0.3f, 0.1f);
  TestRng rng(7);
  for (const Case& c : kCases) {
    const double stopping =
        (c.sigma_t.x > 0) * 0.6 + (c.sigma_t.y > 0) * 0.3 + (c.sigma_t.z > 0) * 0.1;
    const auto pdf = [&](double t) { return free_flight_pdf(c.sigma_t, weights, float(t)); };
    EXPECT_NEAR(test::integrate_interval(pdf, 0, INFINITY), stopping, kQuadratureTolerance)
        << c.name;
    for (const float d : {0.1f, 0.7f, 2.0f}) {
      EXPECT_NEAR(free_flight_survival(c.sigma_t, weights, d),
                  1.0 - test::integrate_interval(pdf, 0, d), kQuadratureTolerance)
          << c.name << " d " << d;
    }
    const auto r = test::chi2_distance(
        [&]() -> std::optional<double> {
          const float u_channel = rng.uniform();
          return free_flight_sample(c.sigma_t, weights, u_channel, rng.uniform());
        },
        pdf, {.scale = 1.0 / average(c.sigma_t), .samples = 1'000'000});
    EXPECT_GT(r.p_value, 1e-4) << c.name << ": " << r.report;
  }
}

// Path-level spectral MIS, as medium_event runs it: a beam through a forward-scattering slab
// (scattering keeps the direction) of depth L, the channel probabilities carried from flight to
// flight. Per channel the expected throughput leaving the slab is the absorption-only
// transmittance e^{-sigma_a L}, however different the channels' extinctions are.
TEST(FreeFlight, PathLevelSpectralMisIsUnbiasedOverManyFlights) {
  const Rgb sigma_s(4.0f, 5.0f, 6.0f), sigma_a(0.3f, 0.1f, 0.05f);
  const Rgb sigma_t = sigma_s + sigma_a;
  const float depth = 3.0f;  // about 15 collisions per path
  TestRng rng(8);
  test::MeanEstimator leaving[3];
  for (int k = 0; k < 400'000; ++k) {
    float x = 0;
    Rgb throughput(1.0f), p(kThird);
    for (;;) {
      const float u_channel = rng.uniform();
      const float t = free_flight_sample(sigma_t, p, u_channel, rng.uniform());
      if (!(x + t < depth)) {
        const Rgb tr = transmittance(sigma_t, depth - x);
        const float survival = free_flight_survival(sigma_t, p, depth - x);
        throughput = throughput * tr / survival;
        break;
      }
      x += t;
      const Rgb q = free_flight_channel_pdfs(sigma_t, t);
      const float pdf = dot(p, q);
      throughput = throughput * sigma_s * transmittance(sigma_t, t) / pdf;
      p = p * q / pdf;
    }
    for (int ch = 0; ch < 3; ++ch) leaving[ch].add(throughput[ch]);
  }
  for (int ch = 0; ch < 3; ++ch) {
    const double expected = std::exp(-double(sigma_a[ch]) * depth);
    EXPECT_LT(std::fabs(leaving[ch].mean() - expected), 4 * leaving[ch].standard_error())
        << "channel " << ch << ": " << leaving[ch].mean() << " +- " << leaving[ch].standard_error()
        << ", expected " << expected;
  }
}

}  // namespace
}  // namespace snee
