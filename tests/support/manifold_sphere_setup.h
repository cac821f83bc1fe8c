// The sphere the manifold strategy's solver tests share: off the origin and of a radius other
// than 1, so that a solver that forgets either fails; and uniform points inside it. A test file
// brings the names in with `using namespace test::manifold_sphere;`.
#pragma once

#include <gtest/gtest.h>

#include "core/math.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"

namespace snee::test::manifold_sphere {

inline const Vec3 kCentre{0.3f, -0.2f, 0.1f};
inline constexpr float kRadius = 1.3f;
inline constexpr float kEta = 1.5f;

inline Vec3 random_inside(TestRng& rng) {
  for (;;) {
    const Vec3 p{2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1};
    if (dot(p, p) < 1) return kCentre + p * kRadius;
  }
}

// The volume the refracted light reaches: the sphere's volume times the share of uniform
// interior points x for which `has_exit(x)` holds.
template <class HasExit>
MeanEstimator lit_volume(TestRng& rng, const HasExit& has_exit) {
  const double sphere = 4.0 / 3.0 * kPi * kRadius * kRadius * kRadius;
  MeanEstimator lit;
  for (int k = 0; k < 200000; ++k) lit.add(has_exit(random_inside(rng)) ? sphere : 0.0);
  return lit;
}

// The change of variables the solvers' Jacobians are checked by: J integrated over (y, t), each
// sample divided by the number of exits its x has, must be the lit volume within 4 standard
// errors, measured to 1%, and the light must reach at least `min_share` of the sphere.
inline void expect_lit_volume(const MeanEstimator& integral, const MeanEstimator& lit,
                              double min_share) {
  const double sphere = 4.0 / 3.0 * kPi * kRadius * kRadius * kRadius;
  EXPECT_LT(z_score(integral.mean(), integral.standard_error(), lit.mean(), lit.standard_error()),
            4.0)
      << integral.mean() << " +- " << integral.standard_error() << " vs " << lit.mean() << " +- "
      << lit.standard_error();
  EXPECT_LT(integral.standard_error(), 0.01 * lit.mean());
  EXPECT_GT(lit.mean(), min_share * sphere);
}

}  // namespace snee::test::manifold_sphere
