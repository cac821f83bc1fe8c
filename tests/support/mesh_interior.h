// Meshes the manifold strategy's mesh solvers are tested on, and points inside them: the bunny
// normalized to the unit sphere as the built-in scenes place it, its bounding box, an
// inside test by ray parity and uniform interior points by rejection. A test file brings the
// names in with `using namespace test::mesh_interior;`.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/math.h"
#include "scene/mesh_io.h"
#include "scene/mesh_topology.h"
#include "tests/support/chi2.h"
#include "tests/support/icosphere.h"

namespace snee::test::mesh_interior {

inline TriangleMesh bunny() {
  TriangleMesh m = load_mesh(std::string(SNEE_PROJECT_DATA_DIR) + "/meshes/bunny-npm.obj");
  apply_transform(normalizing_transform(m), m);
  return m;
}

struct Box {
  Vec3 lo{kInfinity}, hi{-kInfinity};
};
inline Box bounds(const TriangleMesh& m) {
  Box b;
  for (const Vec3& p : m.positions) {
    b.lo = vmin(b.lo, p);
    b.hi = vmax(b.hi, p);
  }
  return b;
}

// Whether x is inside the closed mesh: an odd number of crossings along a ray.
inline bool inside(const TriangleMesh& m, Vec3 x) {
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
inline Vec3 random_inside(TestRng& rng, const TriangleMesh& m, const Box& b) {
  for (;;) {
    const Vec3 x(b.lo.x + rng.uniform() * (b.hi.x - b.lo.x),
                 b.lo.y + rng.uniform() * (b.hi.y - b.lo.y),
                 b.lo.z + rng.uniform() * (b.hi.z - b.lo.z));
    if (inside(m, x)) return x;
  }
}

struct NamedMesh {
  std::string name;
  TriangleMesh mesh;
};
// The bunny and a flat-shaded icosphere.
inline std::vector<NamedMesh> meshes() {
  return {{"bunny", bunny()}, {"icosphere", test::icosphere(3, false)}};
}

// Calls check(light, exits, x) for `points` uniform interior points of the mesh under each of
// `lights` lights drawn by draw_light(rng), with the tree make_tree(light) finds them by;
// returns the solutions found.
template <typename DrawLight, typename MakeTree, typename Check>
int for_interior_points(TestRng& rng, const TriangleMesh& mesh, int lights, int points,
                        const DrawLight& draw_light, const MakeTree& make_tree,
                        const Check& check) {
  const Box box = bounds(mesh);
  int solutions = 0;
  for (int k = 0; k < lights; ++k) {
    const Vec3 light = draw_light(rng);
    const auto tree = make_tree(light);
    for (int j = 0; j < points; ++j) {
      const Vec3 x = random_inside(rng, mesh, box);
      const auto exits = tree.exits_toward(x);
      EXPECT_EQ(exits.dropped, 0);
      solutions += exits.count;
      check(light, exits, x);
    }
  }
  return solutions;
}

// Every exit found obeys Snell's law: the light refracted in at its point (refracted(light, y,
// n, &omega_r)) is its direction (their cosine within `tolerance` of 1), and reaches x at its
// distance.
template <typename Exits, typename Refracted>
void expect_snell(const Exits& exits, Vec3 light, Vec3 x, const Refracted& refracted,
                  float tolerance, const std::string& name) {
  for (int i = 0; i < exits.count; ++i) {
    const auto& e = exits.exit[static_cast<size_t>(i)];
    Vec3 omega_r;
    ASSERT_TRUE(refracted(light, e.y, e.n, &omega_r)) << name;
    ASSERT_GT(dot(e.omega_r, omega_r), 1.0f - tolerance) << name;
    const Vec3 to_x = x - e.y;
    ASSERT_NEAR(length(to_x), e.t, 1e-5 * (1 + e.t)) << name;
    ASSERT_GT(dot(normalize(to_x), omega_r), 1.0f - 1e-5f) << name;
  }
}

// Completeness of a facet tree: under each of `lights` lights drawn by draw_light(rng), the
// light refracted in at a random point y of each of 50 random facets (refracted(light, y, n,
// &omega_r), false where it does not enter) passes through x = y + t omega_r; the tree
// make_tree(light) must return y from x. Points near a facet's edges, which a neighbouring
// facet may rightly claim, are not drawn. Returns the rays traced.
template <typename DrawLight, typename MakeTree, typename Refracted>
int expect_finds_forward_traced(TestRng& rng, const NamedMesh& m, int lights,
                                const DrawLight& draw_light, const MakeTree& make_tree,
                                const Refracted& refracted) {
  int traced = 0;
  for (int k = 0; k < lights; ++k) {
    const Vec3 light = draw_light(rng);
    const auto tree = make_tree(light);
    for (int j = 0; j < 50; ++j) {
      const size_t t = static_cast<size_t>(rng.uniform() * m.mesh.triangle_count());
      const Vec3 a = m.mesh.positions[m.mesh.indices[3 * t]],
                 b = m.mesh.positions[m.mesh.indices[3 * t + 1]],
                 c = m.mesh.positions[m.mesh.indices[3 * t + 2]];
      float u = 0.02f + 0.96f * rng.uniform(), v = 0.02f + 0.96f * rng.uniform();
      if (u + v > 0.98f) {
        u = 0.98f - u;
        v = 0.98f - v;
      }
      const Vec3 y = a + (b - a) * u + (c - a) * v;
      Vec3 omega_r;
      if (!refracted(light, y, normalize(cross(b - a, c - a)), &omega_r)) continue;
      const Vec3 x = y + omega_r * (0.01f + rng.uniform());
      const auto exits = tree.exits_toward(x);
      bool found = false;
      for (int i = 0; i < exits.count; ++i) {
        found |= length(exits.exit[static_cast<size_t>(i)].y - y) < 1e-4f;
      }
      EXPECT_TRUE(found) << m.name << ": the light through facet " << t << " at (" << y.x << ", "
                         << y.y << ", " << y.z << ") is not found from x";
      if (!found) return traced;
      ++traced;
    }
  }
  return traced;
}

}  // namespace snee::test::mesh_interior
