// The manifold strategy's exit points on closed flat-shaded meshes under a point light
// (docs/method.md 3.13): every solution obeys Snell's law for the ray arriving from the light;
// every ray traced forward from the light through a facet is found again from any point along
// it; the tree finds exactly the facets an independent pass over every triangle finds (the
// point of its plane where the optical path length from the light to x is least, by Fermat's
// principle); and the tree is only built for lights outside a denser mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/vec3d.h"
#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/sampling.h"
#include "kernels/physics/snee/manifold_mesh_point.h"
#include "tests/support/chi2.h"
#include "tests/support/icosphere.h"
#include "tests/support/mesh_interior.h"

namespace snee {
namespace {

using test::TestRng;
using namespace test::mesh_interior;

constexpr float kEta = 1.5f;

// A light position outside both meshes (they fit in the unit sphere), up to 6 away.
Vec3 random_light(TestRng& rng) {
  return sample_uniform_sphere(rng.uniform2()) * (1.2f + 4.8f * rng.uniform());
}

// The light from `light` refracted into the mesh at y through a facet of outward normal n.
bool refracted_from(Vec3 light, Vec3 y, Vec3 n, Vec3* inside) {
  const Vec3 toward = normalize(light - y);
  return dot(n, toward) > 0 && refract(toward, n, 1.0f / kEta, inside);
}

// The oracle for one triangle: the point y of its plane where the optical path |y - light| +
// eta |x - y| is least (convex, so Newton from the foot of the light converges to it), which
// obeys Snell's law, then a barycentric test by signed areas.
bool oracle_exit(Vec3 a, Vec3 b, Vec3 c, Vec3 light, Vec3 x) {
  const Vec3d n = normalize(cross(Vec3d(b) - Vec3d(a), Vec3d(c) - Vec3d(a)));
  const Vec3d l(light), p(x), origin(a);
  if (!(dot(n, l - origin) > 0) || !(dot(n, p - origin) < 0)) return false;
  const Vec3d t1 = normalize(Vec3d(b) - Vec3d(a)), t2 = cross(n, t1);
  const auto path = [&](const Vec3d& q) { return length(q - l) + kEta * length(q - p); };
  Vec3d y = l - dot(n, l - origin) * n;
  for (int it = 0; it < 100; ++it) {
    const Vec3d u = y - l, v = y - p;
    const double lu = length(u), lv = length(v);
    const Vec3d g = u / lu + static_cast<double>(kEta) * (v / lv);
    // Hessian of each distance: (I - d d^T) / length, restricted to the plane.
    const auto h = [&](const Vec3d& s, const Vec3d& r) {
      return (dot(s, r) - dot(s, u) * dot(r, u) / (lu * lu)) / lu +
             kEta * (dot(s, r) - dot(s, v) * dot(r, v) / (lv * lv)) / lv;
    };
    const double g1 = dot(g, t1), g2 = dot(g, t2);
    const double h11 = h(t1, t1), h12 = h(t1, t2), h22 = h(t2, t2);
    const double det = h11 * h22 - h12 * h12;
    double s1 = (h22 * g1 - h12 * g2) / det, s2 = (h11 * g2 - h12 * g1) / det;
    // Halved until the path shortens: far from the minimum a full step can overshoot.
    while (path(y - s1 * t1 - s2 * t2) > path(y) && std::abs(s1) + std::abs(s2) > 1e-15) {
      s1 *= 0.5;
      s2 *= 0.5;
    }
    y = y - s1 * t1 - s2 * t2;
    if (std::abs(s1) + std::abs(s2) < 1e-14) break;
  }
  const auto area = [&](Vec3 q, Vec3 r) { return dot(cross(Vec3d(q) - y, Vec3d(r) - y), n); };
  return area(b, c) >= 0 && area(c, a) >= 0 && area(a, b) >= 0;
}

int oracle_exits(const TriangleMesh& m, Vec3 light, Vec3 x) {
  int count = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    count += oracle_exit(m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]],
                         m.positions[m.indices[3 * t + 2]], light, x);
  }
  return count;
}

// for_interior_points under random light positions outside the meshes, with the point tree.
template <typename Check>
int for_interior_points(TestRng& rng, const TriangleMesh& mesh, int lights, int points,
                        const Check& check) {
  return test::mesh_interior::for_interior_points(
      rng, mesh, lights, points, random_light,
      [&](Vec3 light) {
        EXPECT_TRUE(point_facet_tree_applies(mesh, kEta, light));
        return PointFacetTree(mesh, kEta, light, 0);
      },
      check);
}

TEST(PointFacetTree, SolutionsObeySnellsLaw) {
  TestRng rng(51);
  for (const NamedMesh& m : meshes()) {
    const int solutions =
        for_interior_points(rng, m.mesh, 200, 20, [&](Vec3 light, const MeshExits& exits, Vec3 x) {
          expect_snell(exits, light, x, refracted_from, 1e-5f, m.name);
        });
    EXPECT_GT(solutions, 2000) << m.name;
  }
}

// Completeness: the light refracted in at a random point of a random facet facing it passes
// through x = y + t omega_r; the solver at x must return that y.
TEST(PointFacetTree, FindsEveryForwardTracedRay) {
  TestRng rng(52);
  for (const NamedMesh& m : meshes()) {
    const int traced = expect_finds_forward_traced(
        rng, m, 200, random_light,
        [&](Vec3 light) { return PointFacetTree(m.mesh, kEta, light, 0); }, refracted_from);
    EXPECT_GT(traced, 3000) << m.name;
  }
}

// The tree opens only some nodes; it must find exactly what the oracle finds on every triangle.
TEST(PointFacetTree, FindsWhatEveryTriangleFinds) {
  TestRng rng(53);
  for (const NamedMesh& m : meshes()) {
    const int solutions =
        for_interior_points(rng, m.mesh, 50, 20, [&](Vec3 light, const MeshExits& exits, Vec3 x) {
          ASSERT_EQ(exits.count, oracle_exits(m.mesh, light, x)) << m.name;
        });
    EXPECT_GT(solutions, 500) << m.name;
  }
}

// Only a light outside a denser mesh gets a tree: inside it there is no boundary to refract
// through toward the light, and a rarer inside would break the cones' bound.
TEST(PointFacetTree, AppliesOnlyToLightsOutsideADenserMesh) {
  TestRng rng(54);
  for (const NamedMesh& m : meshes()) {
    const Box box = bounds(m.mesh);
    for (int k = 0; k < 20; ++k) {
      EXPECT_FALSE(point_facet_tree_applies(m.mesh, kEta, random_inside(rng, m.mesh, box)))
          << m.name;
      EXPECT_TRUE(point_facet_tree_applies(m.mesh, kEta, random_light(rng))) << m.name;
    }
    EXPECT_FALSE(point_facet_tree_applies(m.mesh, 1.0f / kEta, Vec3(3, 0, 0))) << m.name;
  }
}

}  // namespace
}  // namespace snee
