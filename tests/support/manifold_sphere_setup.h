// The sphere the manifold strategy's solver tests share: off the origin and of a radius other
// than 1, so that a solver that forgets either fails; and uniform points inside it. A test file
// brings the names in with `using namespace test::manifold_sphere;`.
#pragma once

#include "core/math.h"
#include "tests/support/chi2.h"

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

}  // namespace snee::test::manifold_sphere
