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

namespace snee {
namespace {

using test::TestRng;

constexpr float kEta = 1.5f;

TriangleMesh bunny() {
  TriangleMesh m = load_mesh(std::string(SNEE_PROJECT_DATA_DIR) + "/meshes/bunny-npm.obj");
  apply_transform(normalizing_transform(m), m);
  return m;
}

struct Box {
  Vec3 lo{kInfinity}, hi{-kInfinity};
};
Box bounds(const TriangleMesh& m) {
  Box b;
  for (const Vec3& p : m.positions) {
    b.lo = vmin(b.lo, p);
    b.hi = vmax(b.hi, p);
  }
  return b;
}

// Whether x is inside the closed mesh: an odd number of crossings along a ray.
bool inside(const TriangleMesh& m, Vec3 x) {
  const Vec3 d = normalize(Vec3(0.3f, 0.9f, 0.1f));
  int crossings = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3 a = m.positions[m.indices[3 * t]], e1 = m.positions[m.indices[3 * t + 1]] - a,
               e2 = m.positions[m.indices[3 * t + 2]] - a;
    const Vec3 p = cross(d, e2), to_x = x - a, q = cross(to_x, e1);
    const float det = dot(e1, p), u = dot(to_x, p) / det, v = dot(d, q) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && dot(e2, q) / det > 0) ++crossings;
  }
  return crossings % 2 == 1;
}

// A uniform point inside the mesh, by rejection from its box.
Vec3 random_inside(TestRng& rng, const TriangleMesh& m, const Box& b) {
  for (;;) {
    const Vec3 x(b.lo.x + rng.uniform() * (b.hi.x - b.lo.x),
                 b.lo.y + rng.uniform() * (b.hi.y - b.lo.y),
                 b.lo.z + rng.uniform() * (b.hi.z - b.lo.z));
    if (inside(m, x)) return x;
  }
}

// The light refracted into the mesh through a facet of outward normal n, if it enters.
bool refracted_light(Vec3 light, Vec3 n, Vec3* inside) {
  return dot(n, light) > 0 && refract(light, n, 1.0f / kEta, inside);
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

struct NamedMesh {
  std::string name;
  TriangleMesh mesh;
};
std::vector<NamedMesh> meshes() {
  return {{"bunny", bunny()}, {"icosphere", test::icosphere(3, false)}};
}

// Calls check(light, tree, x) for `points` uniform interior points of the mesh under each of
// `lights` uniformly drawn light directions; returns the solutions found.
template <typename Check>
int for_interior_points(TestRng& rng, const TriangleMesh& mesh, int lights, int points,
                        const Check& check) {
  const Box box = bounds(mesh);
  int solutions = 0;
  for (int k = 0; k < lights; ++k) {
    const Vec3 light = sample_uniform_sphere(rng.uniform2());
    const FacetExitTree tree(mesh, kEta, light);
    for (int j = 0; j < points; ++j) {
      const Vec3 x = random_inside(rng, mesh, box);
      const MeshExits exits = tree.exits_toward(x);
      EXPECT_EQ(exits.dropped, 0);
      solutions += exits.count;
      check(light, exits, x);
    }
  }
  return solutions;
}

TEST(FacetExitTree, SolutionsObeySnellsLaw) {
  TestRng rng(11);
  for (const NamedMesh& m : meshes()) {
    const int solutions =
        for_interior_points(rng, m.mesh, 200, 20, [&](Vec3 light, const MeshExits& exits, Vec3 x) {
          for (int i = 0; i < exits.count; ++i) {
            const MeshExit& e = exits.exit[static_cast<size_t>(i)];
            Vec3 omega_r;
            ASSERT_TRUE(refracted_light(light, e.n, &omega_r)) << m.name;
            ASSERT_GT(dot(e.omega_r, omega_r), 1.0f - 1e-6f) << m.name;
            const Vec3 to_x = x - e.y;
            ASSERT_NEAR(length(to_x), e.t, 1e-5 * (1 + e.t)) << m.name;
            ASSERT_GT(dot(normalize(to_x), omega_r), 1.0f - 1e-5f) << m.name;
          }
        });
    EXPECT_GT(solutions, 2000) << m.name;
  }
}

// Completeness: a beam refracted in at a random point of a random lit facet passes through
// x = y + t omega_r; the solver at x must return that y.
TEST(FacetExitTree, FindsEveryForwardTracedBeam) {
  TestRng rng(12);
  for (const NamedMesh& m : meshes()) {
    int traced = 0;
    for (int k = 0; k < 200; ++k) {
      const Vec3 light = sample_uniform_sphere(rng.uniform2());
      const FacetExitTree tree(m.mesh, kEta, light);
      for (int j = 0; j < 50; ++j) {
        const size_t t = static_cast<size_t>(rng.uniform() * m.mesh.triangle_count());
        const Vec3 a = m.mesh.positions[m.mesh.indices[3 * t]],
                   b = m.mesh.positions[m.mesh.indices[3 * t + 1]],
                   c = m.mesh.positions[m.mesh.indices[3 * t + 2]];
        Vec3 omega_r;
        if (!refracted_light(light, normalize(cross(b - a, c - a)), &omega_r)) continue;
        // Away from the edges, where the neighbouring facet may rightly claim the point.
        float u = 0.02f + 0.96f * rng.uniform(), v = 0.02f + 0.96f * rng.uniform();
        if (u + v > 0.98f) {
          u = 0.98f - u;
          v = 0.98f - v;
        }
        const Vec3 y = a + (b - a) * u + (c - a) * v;
        const Vec3 x = y + omega_r * (0.01f + rng.uniform());
        const MeshExits exits = tree.exits_toward(x);
        bool found = false;
        for (int i = 0; i < exits.count; ++i) {
          found |= length(exits.exit[static_cast<size_t>(i)].y - y) < 1e-4f;
        }
        ASSERT_TRUE(found) << m.name << ": the beam through facet " << t << " at (" << y.x << ", "
                           << y.y << ", " << y.z << ") is not found from x";
        ++traced;
      }
    }
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
