// GGX distribution: normalisation of D, Smith G1 projected-area identity, the normal sampler
// (inverse warp, Jacobian and chi-square) and the visible-normal sampler (chi-square).
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>

#include "kernels/physics/bsdf/ggx.h"
#include "tests/support/chi2.h"

namespace snee {
namespace {

using test::TestRng;

constexpr float kAlphas[] = {0.04f, 0.2f, 0.5f, 1.0f};

// Quadrature tolerance: integrate_sphere converges to ~1e-7 relative, far below this.
constexpr double kQuadratureTolerance = 1e-5;

TEST(Ggx, ProjectedNormalsIntegrateToOne) {
  for (const float alpha : kAlphas) {
    const double integral = test::integrate_sphere([&](Vec3 m) { return ggx_d(m, alpha) * m.z; });
    EXPECT_NEAR(integral, 1.0, kQuadratureTolerance) << "alpha " << alpha;
  }
}

// Smith's G1 is defined so that the visible projected microfacet area equals the projected
// macro area: integral of G1(v, m) max(0, v.m) D(m) dm = v.z.
TEST(Ggx, SmithG1PreservesProjectedArea) {
  for (const float alpha : kAlphas) {
    for (const float cos_v : {0.95f, 0.6f, 0.2f}) {
      const Vec3 v = spherical_direction(std::sqrt(1 - cos_v * cos_v), cos_v, 0.7f);
      const double visible = test::integrate_sphere([&](Vec3 m) {
        return ggx_g1(v, m, alpha) * std::max(0.0f, dot(v, m)) * ggx_d(m, alpha);
      });
      EXPECT_NEAR(visible, cos_v, kQuadratureTolerance) << "alpha " << alpha << " cos_v " << cos_v;
    }
  }
}

// The warp is u1 = tan^2 / (alpha^2 + tan^2), u2 = phi / 2 pi. Inverting it recovers u, and the
// pdf must equal the Jacobian |du1/d cos| / (2 pi) of that inverse, evaluated in double.
TEST(Ggx, SampledNormalPdfMatchesWarpJacobian) {
  TestRng rng(1);
  for (const float alpha : kAlphas) {
    for (int k = 0; k < 10000; ++k) {
      const Vec2 u = rng.uniform2();
      const Vec3 m = ggx_sample_normal(u, alpha);
      ASSERT_NEAR(length(m), 1.0f, 4 * FLT_EPSILON);
      const double c = m.z, a2 = double(alpha) * alpha;
      const double s2 = double(m.x) * m.x + double(m.y) * m.y;
      const double u1 = s2 / (s2 + a2 * c * c);
      double phi = std::atan2(double(m.y), double(m.x));
      if (phi < 0) phi += 2 * M_PI;
      // Float rounding of m bounds how well u is recovered; u1 near 1 is the steep tail.
      EXPECT_NEAR(u1, u.x, 1e-5 / std::max(1e-3, 1 - double(u.x))) << alpha;
      if (s2 > 1e-8) {
        EXPECT_NEAR(phi / (2 * M_PI), u.y, 1e-5) << alpha;
      }
      // u1(c) = (1 - c^2) / (1 - c^2 + a2 c^2)  =>  du1/dc = -2 a2 c / (1 - c^2 + a2 c^2)^2.
      const double den = s2 + a2 * c * c;
      const double jacobian = 2 * a2 * c / (den * den) / (2 * M_PI);
      EXPECT_NEAR(ggx_normal_pdf(m, alpha) / jacobian, 1.0, 1e-4) << alpha;
    }
  }
}

TEST(Ggx, SampledNormalsFollowPdf) {
  TestRng rng(2);
  for (const float alpha : kAlphas) {
    // Bins cover the cone where tan theta < 8 alpha (98.5% of the mass) so narrow lobes resolve.
    const double cos_min = std::cos(std::min(0.5 * M_PI, std::atan(8.0 * alpha)));
    const auto r = test::chi2_sphere(
        [&]() -> std::optional<Vec3> { return ggx_sample_normal(rng.uniform2(), alpha); },
        [&](Vec3 m) { return ggx_normal_pdf(m, alpha); },
        {.cos_min = cos_min, .samples = 1'000'000});
    EXPECT_GT(r.p_value, 1e-4) << "alpha " << alpha << ": " << r.report;
    EXPECT_EQ(r.success_fraction, 1.0);
  }
}

// The visible-normal density integrates to 1 for every view (Smith's projected-area identity
// makes it a density), and the sampler draws it.
TEST(Ggx, VisibleNormalsFollowPdf) {
  TestRng rng(3);
  for (const float alpha : {0.05f, 0.3f, 1.0f}) {
    for (const float cos_v : {0.95f, 0.5f, 0.1f}) {
      const Vec3 v = spherical_direction(std::sqrt(1 - cos_v * cos_v), cos_v, 0.4f);
      const double cos_min = std::cos(std::min(0.5 * M_PI, std::atan(8.0 * alpha)));
      const auto r = test::chi2_sphere(
          [&]() -> std::optional<Vec3> {
            return ggx_sample_visible_normal(v, rng.uniform2(), alpha);
          },
          [&](Vec3 m) { return ggx_visible_normal_pdf(v, m, alpha); },
          {.cos_min = cos_min, .samples = 400'000});
      EXPECT_GT(r.p_value, 1e-4) << "alpha " << alpha << " cos_v " << cos_v << ": " << r.report;
      EXPECT_EQ(r.success_fraction, 1.0);
      EXPECT_NEAR(r.integral, 1.0, kQuadratureTolerance) << "alpha " << alpha << " cos_v " << cos_v;
    }
  }
}

}  // namespace
}  // namespace snee
