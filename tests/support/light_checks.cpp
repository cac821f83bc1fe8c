#include "tests/support/light_checks.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/chi2.h"

namespace snee::test {

double pearson_p_value(const std::vector<double>& observed, const std::vector<double>& expected) {
  double statistic = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
  }
  return chi2_survival(statistic, static_cast<double>(observed.size() - 1));
}

void expect_agrees(const MeanEstimator& e, double expected, const char* what) {
  EXPECT_LT(z_score(e.mean(), e.standard_error(), expected, 0), kMaxZ)
      << what << ": estimate " << e.mean() << " +- " << e.standard_error() << ", expected "
      << expected;
}

void expect_round_trip(const Scene& scene, const LightTable& lights, Vec3 p, uint64_t seed) {
  TestRng rng(seed);
  int valid = 0;
  for (int k = 0; k < 100000; ++k) {
    const float u_select = rng.uniform();
    const LightSample s = lights.sample(p, u_select, rng.uniform2());
    if (!s.valid) continue;
    ++valid;
    ASSERT_NEAR(length(s.wi), 1.0f, 4 * FLT_EPSILON);
    if (s.delta) {
      // The pdf of a delta light is its selection probability.
      bool found = false;
      for (size_t i = 0; i < scene.lights.size(); ++i) {
        const LightKind kind = scene.lights[i].kind;
        const bool delta = kind == LightKind::kDirectional || kind == LightKind::kPoint ||
                           kind == LightKind::kSpot;
        found = found || (delta && s.pdf == lights.selection_pmf(static_cast<int>(i)));
      }
      ASSERT_TRUE(found) << "delta pdf " << s.pdf << " is no delta light's selection pmf";
    } else if (std::isinf(s.distance)) {
      ASSERT_EQ(s.pdf, lights.escaped_pdf(s.wi));
      ASSERT_EQ(s.radiance, lights.escaped_radiance(s.wi));
    } else {
      // Find the emitter the point lies on.
      const Vec3 hit = p + s.wi * s.distance;
      int shape = -1;
      Vec3 n;
      for (size_t i = 0; i < scene.shapes.size() && shape < 0; ++i) {
        const Shape& sh = scene.shapes[i];
        if (sh.kind == ShapeKind::kSphere) {
          if (std::fabs(length(hit - sh.center) - sh.radius) < 1e-4f * sh.radius) {
            shape = static_cast<int>(i);
            n = normalize(hit - sh.center);
          }
        } else if (std::fabs(hit.z - sh.mesh.positions[0].z) < 1e-5f) {
          shape = static_cast<int>(i);
          n = Vec3(0, 0, -1);
        }
      }
      ASSERT_GE(shape, 0) << "sampled point on no emitter";
      ASSERT_NEAR(s.pdf, lights.area_pdf(shape, p, hit, n), kPdfRelativeTolerance * s.pdf);
      ASSERT_EQ(s.radiance, lights.area_radiance(shape, n, s.wi));
    }
  }
  EXPECT_GT(valid, 0);
}

}  // namespace snee::test
