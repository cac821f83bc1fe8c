// The sphere the manifold strategy's solver tests share: off the origin and of a radius other
// than 1, so that a solver that forgets either fails; and uniform points inside it. A test file
// brings the names in with `using namespace test::manifold_sphere;`.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

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

// The light's path inside from the entry normal n (light: the unit direction toward it there),
// traced in double so that its end points lie on the exact chain to float's rounding: the entry and
// each reflection point (the last one the start of the final chord), the final direction and the
// final chord's length.
struct ForwardChain {
  std::vector<Vec3> points;
  Vec3 direction;
  float chord = 0;
  Vec3 at(double t) const {
    return Vec3(end[0] + t * dir[0], end[1] + t * dir[1], end[2] + t * dir[2]);
  }
  double end[3] = {0, 0, 0}, dir[3] = {0, 0, 0};
};
inline ForwardChain trace_forward(Vec3 light, Vec3 n_in, int reflections) {
  using V = std::array<double, 3>;
  const auto dotd = [](const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const auto norm = [&](V a) {
    const double l = std::sqrt(dotd(a, a));
    return V{a[0] / l, a[1] / l, a[2] / l};
  };
  const V w = norm({light.x, light.y, light.z});
  const V n = norm({n_in.x, n_in.y, n_in.z});
  const double e = 1.0 / kEta, c = dotd(n, w), k = std::sqrt(1 - e * e * (1 - c * c));
  V d{-e * w[0] + (e * c - k) * n[0], -e * w[1] + (e * c - k) * n[1],
      -e * w[2] + (e * c - k) * n[2]};
  V q = n;  // on the unit sphere
  const auto world = [&](const V& u) {
    return Vec3(static_cast<float>(kCentre.x + kRadius * u[0]),
                static_cast<float>(kCentre.y + kRadius * u[1]),
                static_cast<float>(kCentre.z + kRadius * u[2]));
  };
  ForwardChain f;
  f.points.push_back(world(q));
  for (int i = 0; i < reflections; ++i) {
    const double t = -2 * dotd(q, d);
    q = {q[0] + t * d[0], q[1] + t * d[1], q[2] + t * d[2]};
    const double r = 2 * dotd(d, q);
    d = {d[0] - r * q[0], d[1] - r * q[1], d[2] - r * q[2]};
    f.points.push_back(world(q));
  }
  f.direction = Vec3(static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2]));
  f.chord = static_cast<float>(-2 * kRadius * dotd(q, d));
  for (int i = 0; i < 3; ++i) {
    f.end[i] = (i == 0   ? kCentre.x
                : i == 1 ? kCentre.y
                         : kCentre.z) +
               kRadius * q[static_cast<size_t>(i)];
    f.dir[i] = d[static_cast<size_t>(i)];
  }
  return f;
}

// |det(dx/du, dx/dv, direction)| for the point x_of(n) that the light entering at the outward
// normal n reaches at a fixed distance along its last chord (direction, at n0), (u, v) arc
// lengths on the sphere around n0: the volume Jacobian by central differences.
template <class PointOf>
double numerical_volume_jacobian(Vec3 n0, Vec3 direction, const PointOf& x_of) {
  const Frame frame = Frame::from_normal(n0);
  const auto at = [&](double u, double v) {
    return x_of(normalize(n0 + frame.to_world(Vec3(static_cast<float>(u / kRadius),
                                                   static_cast<float>(v / kRadius), 0))));
  };
  const double h = 1e-3;
  const Vec3 du = (at(h, 0) - at(-h, 0)) / static_cast<float>(2 * h);
  const Vec3 dv = (at(0, h) - at(0, -h)) / static_cast<float>(2 * h);
  return std::abs(dot(cross(du, dv), direction));
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
// errors, measured to `precision` (relative), and the light must reach at least `min_share` of
// the sphere.
inline void expect_lit_volume(const MeanEstimator& integral, const MeanEstimator& lit,
                              double min_share, double precision = 0.01) {
  const double sphere = 4.0 / 3.0 * kPi * kRadius * kRadius * kRadius;
  EXPECT_LT(z_score(integral.mean(), integral.standard_error(), lit.mean(), lit.standard_error()),
            4.0)
      << integral.mean() << " +- " << integral.standard_error() << " vs " << lit.mean() << " +- "
      << lit.standard_error();
  EXPECT_LT(integral.standard_error(), precision * lit.mean());
  EXPECT_GT(lit.mean(), min_share * sphere);
}

}  // namespace snee::test::manifold_sphere
