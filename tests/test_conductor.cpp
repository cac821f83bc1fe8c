// Conductor: the complex-index Fresnel against complex arithmetic in double, the GGX
// reflection lobe (sample/eval/pdf consistency, chi-square over several roughnesses and
// incident angles), the mirror, and the white furnace: with F = 1 the albedo is the
// single-scattering GGX albedo, which the sampler's weights must reproduce.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <iterator>

#include "kernels/physics/bsdf/conductor.h"
#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/bsdf/ggx.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::TestRng;

constexpr float kAlphas[] = {0.05f, 0.3f, 0.8f};
constexpr float kCosines[] = {0.9f, 0.5f, 0.1f};

Vec3 direction(float cos_theta, float phi) {
  return spherical_direction(std::sqrt(1 - cos_theta * cos_theta), cos_theta, phi);
}

// eta = 0, k = 1 reflects everything at every angle (fresnel_conductor's comment).
ConductorParams white(float alpha) {
  return {Rgb(0.0f), Rgb(1.0f), alpha};
}

// Unpolarised reflectance from the complex Fresnel amplitudes (Born and Wolf).
double fresnel_reference(double c, double eta, double k) {
  using C = std::complex<double>;
  const C n(eta, k);
  const C cos_t = std::sqrt(C(1.0) - (1.0 - c * c) / (n * n));
  const C rs = (c - n * cos_t) / (c + n * cos_t);
  const C rp = (n * c - cos_t) / (n * c + cos_t);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

TEST(Conductor, FresnelMatchesComplexArithmetic) {
  // Gold's red and blue, aluminium's green, a weak absorber and a dielectric.
  const double indices[][2] = {{0.143, 3.98}, {1.44, 1.60}, {0.88, 6.27}, {1.5, 0.1}, {1.5, 0}};
  for (const auto& [eta, k] : indices) {
    for (const double c : {1.0, 0.8, 0.5, 0.2, 0.05, 0.0}) {
      const float f =
          fresnel_conductor(static_cast<float>(c), static_cast<float>(eta), static_cast<float>(k));
      EXPECT_NEAR(f, fresnel_reference(c, eta, k), 2e-5) << eta << " + " << k << "i, cos " << c;
      if (k == 0) {
        EXPECT_NEAR(f, fresnel_dielectric(static_cast<float>(c), static_cast<float>(eta)), 2e-6);
      }
    }
  }
  for (const float c : {1.0f, 0.6f, 0.0f}) {
    EXPECT_EQ(fresnel_conductor(c, 0.0f, 1.0f), 1.0f) << c;
    EXPECT_EQ(fresnel_conductor(c, 0.0f, 0.0f), 1.0f) << c;
  }
}

TEST(Conductor, SampleMatchesEvalAndPdf) {
  TestRng rng(31);
  const ConductorParams base{{0.2f, 0.9f, 1.1f}, {3.9f, 2.5f, 2.1f}, 0};
  for (const float alpha : kAlphas) {
    ConductorParams p = base;
    p.alpha = alpha;
    for (const float c : kCosines) {
      const Vec3 wo = direction(c, 0.8f);
      int valid = 0;
      for (int i = 0; i < 10000; ++i) {
        const BsdfSample s = conductor_sample(p, wo, rng.uniform2());
        if (!s.valid) continue;
        ++valid;
        ASSERT_GT(s.wi.z, 0.0f);
        EXPECT_FALSE(s.delta || s.transmission);
        EXPECT_NEAR(s.f / conductor_eval(p, wo, s.wi), 1.0f, 1e-4f);
        EXPECT_NEAR(s.pdf / conductor_pdf(p, wo, s.wi), 1.0f, 1e-4f);
        const Rgb fresnel = conductor_fresnel(p, wo, s.wi);
        for (int ch = 0; ch < 3; ++ch) {
          EXPECT_GT(fresnel[ch], 0.0f);
          EXPECT_LE(fresnel[ch], 1.0f);
        }
      }
      // Visible normals never face away from wo: only reflections below the horizon fail.
      EXPECT_GT(valid, alpha < 0.5f && c > 0.4f ? 9000 : 5000) << alpha << " " << c;
      EXPECT_EQ(conductor_eval(p, wo, Vec3(0, 0, -1)), 0.0f);
      EXPECT_EQ(conductor_pdf(p, wo, Vec3(0, 0, -1)), 0.0f);
    }
  }
}

TEST(Conductor, SamplesFollowPdf) {
  TestRng rng(32);
  constexpr int64_t kSamples = 400'000;
  for (const float alpha : kAlphas) {
    const ConductorParams p = white(alpha);
    for (const float c : kCosines) {
      const Vec3 wo = direction(c, 2.0f);
      // Bins about the mirror direction, as wide as the lobe (twice the normals' spread).
      const double cos_min = std::cos(std::min(M_PI, 2 * std::atan(8.0 * alpha)));
      const auto r = test::chi2_sphere(
          [&]() -> std::optional<Vec3> {
            const BsdfSample s = conductor_sample(p, wo, rng.uniform2());
            return s.valid ? std::optional<Vec3>(s.wi) : std::nullopt;
          },
          [&](Vec3 wi) { return conductor_pdf(p, wo, wi); },
          {.axis = Vec3(-wo.x, -wo.y, wo.z), .cos_min = cos_min, .samples = kSamples});
      EXPECT_GT(r.p_value, 1e-4) << "alpha " << alpha << " cos " << c << ": " << r.report;
      // The pdf integrates to the probability that the reflection stays above the surface.
      const double se = std::sqrt(r.success_fraction * (1 - r.success_fraction) / kSamples) + 1e-6;
      EXPECT_NEAR(r.integral, r.success_fraction, 5 * se + 1e-4) << alpha << " " << c;
    }
  }
}

TEST(Conductor, SmoothIsAMirror) {
  const ConductorParams p{{0.2f, 0.9f, 1.1f}, {3.9f, 2.5f, 2.1f}, 0.0f};
  const Vec3 wo = direction(0.6f, 1.0f);
  const BsdfSample s = conductor_sample(p, wo, {0.3f, 0.7f});
  ASSERT_TRUE(s.valid && s.delta);
  EXPECT_EQ(s.wi, Vec3(-wo.x, -wo.y, wo.z));
  EXPECT_FLOAT_EQ(s.f * s.wi.z / s.pdf, 1.0f);
  EXPECT_EQ(conductor_eval(p, wo, s.wi), 0.0f);
  EXPECT_EQ(conductor_pdf(p, wo, s.wi), 0.0f);
  const Rgb fresnel = conductor_fresnel(p, wo, s.wi);
  for (int ch = 0; ch < 3; ++ch)
    EXPECT_EQ(fresnel[ch], fresnel_conductor(wo.z, p.eta[ch], p.k[ch]));
  EXPECT_FALSE(conductor_sample(p, direction(-0.5f, 1.0f), {0.3f, 0.7f}).valid);
}

// Integral of the lobe times cos over wi, as a midpoint rule over the half vector in the
// coordinates of GGX's normal warp (u -> m with density D(m) m.z), where the integrand is smooth
// and bounded even for narrow lobes; dwi = 4 (wo.m) dm for a reflection.
double albedo_quadrature(const ConductorParams& p, Vec3 wo) {
  constexpr int kCells = 1000;
  double sum = 0;
  for (int i = 0; i < kCells; ++i) {
    for (int j = 0; j < kCells; ++j) {
      const Vec3 m = ggx_sample_normal({(i + 0.5f) / kCells, (j + 0.5f) / kCells}, p.alpha);
      const Vec3 wi = reflect(wo, m);
      if (!(wi.z > 0.0f) || !(dot(wo, m) > 0.0f)) continue;
      sum += double{conductor_eval(p, wo, wi)} * wi.z * 4 * dot(wo, m) / ggx_normal_pdf(m, p.alpha);
    }
  }
  return sum / (double{kCells} * kCells);
}

// White furnace of the BSDF alone: with F = 1 nothing is absorbed, and what is lost is the
// light single-scattering GGX sends into microfacets it never leaves (the missing multiple
// scattering), so the albedo is the quadrature of the lobe times cos and stays below 1, close
// to 1 for a smooth surface and lower the rougher. The sampler's mean weight must equal that
// quadrature. (With Smith's separable G the loss is large: albedo 0.44 at alpha 0.8 and cos 0.9.)
TEST(Conductor, WhiteFurnaceAlbedoIsTheSingleScatteringIntegral) {
  TestRng rng(33);
  constexpr int kSamples = 200'000;
  double previous[std::size(kCosines)] = {1.0, 1.0, 1.0};
  for (const float alpha : kAlphas) {
    const ConductorParams p = white(alpha);
    int k = 0;
    for (const float c : kCosines) {
      const Vec3 wo = direction(c, 0.3f);
      const double reference = albedo_quadrature(p, wo);
      test::MeanEstimator weights;
      for (int i = 0; i < kSamples; ++i) {
        const BsdfSample s = conductor_sample(p, wo, rng.uniform2());
        const double w = s.valid ? s.f * s.wi.z / s.pdf : 0.0;
        EXPECT_EQ(conductor_fresnel(p, wo, s.wi), Rgb(s.valid ? 1.0f : 0.0f));
        weights.add(w);
      }
      EXPECT_NEAR(weights.mean(), reference, 5 * weights.standard_error() + 1e-5)
          << "alpha " << alpha << " cos " << c;
      EXPECT_LE(reference, 1.0 + 1e-5);
      if (alpha <= 0.05f && c > 0.4f) {
        EXPECT_GT(reference, 0.99);
      }
      // Rougher loses more.
      EXPECT_LT(reference, previous[k]);
      previous[k++] = reference;
    }
  }
}

}  // namespace
}  // namespace snee
