// The manifold strategy's exit-point solver on closed flat-shaded meshes (docs/method.md 3.13):
// every solution obeys Snell's law and lies on a facet facing the light; every beam traced
// forward from a lit facet is found again from any point along it; and the tree finds exactly
// the facets a brute-force pass over every triangle finds, on the bunny and an icosphere.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/sampling.h"
#include "kernels/physics/snee/manifold_mesh.h"
#include "scene/mesh_io.h"
#include "scene/mesh_topology.h"
#include "tests/support/chi2.h"
#include "tests/support/icosphere.h"
#include "tests/support/mesh_interior.h"

namespace snee {
namespace {

using test::TestRng;
using namespace test::mesh_interior;

constexpr float kEta = 1.5f;

// The light refracted into the mesh through a facet of outward normal n, if it enters.
bool refracted_light(Vec3 light, Vec3 n, Vec3* inside) {
  return dot(n, light) > 0 && refract(light, n, 1.0f / kEta, inside);
}

// The same as expect_snell and expect_finds_forward_traced take it: under a directional light
// the entry point does not matter.
bool directional_refraction(Vec3 light, Vec3, Vec3 n, Vec3* inside) {
  return refracted_light(light, n, inside);
}

// The oracle: every triangle, with its own plane intersection and a barycentric test by signed
// volumes instead of the solver's Moller-Trumbore.
int brute_force_exits(const TriangleMesh& m, Vec3 light, Vec3 x) {
  int count = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
               c = m.positions[m.indices[3 * t + 2]];
    const Vec3 n = normalize(cross(b - a, c - a));
    Vec3 omega_r;
    if (!refracted_light(light, n, &omega_r)) continue;
    // x - s omega_r on the plane: n . (x - s omega_r - a) = 0.
    const double s = static_cast<double>(dot(n, x - a)) / dot(n, omega_r);
    if (!(s > 0)) continue;
    const Vec3 y = x - omega_r * static_cast<float>(s);
    const float w0 = dot(cross(b - y, c - y), n), w1 = dot(cross(c - y, a - y), n),
                w2 = dot(cross(a - y, b - y), n);
    if (w0 >= 0 && w1 >= 0 && w2 >= 0) ++count;
  }
  return count;
}

// for_interior_points under uniformly drawn light directions, with the directional tree.
template <typename Check>
int for_interior_points(TestRng& rng, const TriangleMesh& mesh, int lights, int points,
                        const Check& check) {
  return test::mesh_interior::for_interior_points(
      rng, mesh, lights, points, [](TestRng& r) { return sample_uniform_sphere(r.uniform2()); },
      [&](Vec3 light) { return FacetExitTree(mesh, kEta, light); }, check);
}

TEST(FacetExitTree, SolutionsObeySnellsLaw) {
  TestRng rng(11);
  for (const NamedMesh& m : meshes()) {
    const int solutions =
        for_interior_points(rng, m.mesh, 200, 20, [&](Vec3 light, const MeshExits& exits, Vec3 x) {
          expect_snell(exits, light, x, directional_refraction, 1e-6f, m.name);
        });
    EXPECT_GT(solutions, 2000) << m.name;
  }
}

// Completeness: a beam refracted in at a random point of a random lit facet passes through
// x = y + t omega_r; the solver at x must return that y.
TEST(FacetExitTree, FindsEveryForwardTracedBeam) {
  TestRng rng(12);
  for (const NamedMesh& m : meshes()) {
    const int traced = expect_finds_forward_traced(
        rng, m, 200, [](TestRng& r) { return sample_uniform_sphere(r.uniform2()); },
        [&](Vec3 light) { return FacetExitTree(m.mesh, kEta, light); }, directional_refraction);
    EXPECT_GT(traced, 3000) << m.name;
  }
}

// The tree opens only some nodes; it must find exactly what trying every triangle finds.
TEST(FacetExitTree, FindsWhatEveryTriangleFinds) {
  TestRng rng(13);
  for (const NamedMesh& m : meshes()) {
    const int solutions =
        for_interior_points(rng, m.mesh, 50, 20, [&](Vec3 light, const MeshExits& exits, Vec3 x) {
          ASSERT_EQ(exits.count, brute_force_exits(m.mesh, light, x)) << m.name;
        });
    EXPECT_GT(solutions, 500) << m.name;
  }
}

}  // namespace
}  // namespace snee
