// The manifold strategy's reflection chains behind closed flat-shaded meshes (docs/method.md
// 3.14): every chain found obeys Snell's law where the light enters and the law of reflection at
// each bounce, and carries the Fresnel reflectances and Jacobian of its facets; every chain traced
// forward from a lit facet is found again from a point on its last segment; and on a small mesh
// the tree finds exactly the chains a pass over every sequence of facets finds.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "core/vec3d.h"
#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/sampling.h"
#include "kernels/physics/snee/manifold_mesh.h"
#include "kernels/physics/snee/manifold_mesh_chains.h"
#include "kernels/physics/snee/snee_options.h"
#include "tests/support/chi2.h"
#include "tests/support/icosphere.h"
#include "tests/support/mesh_interior.h"

namespace snee {
namespace {

using test::TestRng;
using namespace test::mesh_interior;

constexpr float kEta = 1.5f;
constexpr int kReflections = 3;

struct Triangle {
  Vec3d a, b, c, n;
};

std::vector<Triangle> triangles(const TriangleMesh& m) {
  std::vector<Triangle> out;
  for_each_facet(m, [&](const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3d& n) {
    out.push_back({Vec3d(p0), Vec3d(p1), Vec3d(p2), n});
  });
  return out;
}

Vec3d reflect_off(const Vec3d& d, const Vec3d& n) {
  return d - 2.0 * dot(d, n) * n;
}

// Where the ray from o along d meets triangle f, by its plane and signed volumes (not the
// solver's Moller-Trumbore); `margin` keeps the point that far (in barycentric terms) from the
// edges.
bool meets(const Triangle& f, const Vec3d& o, const Vec3d& d, double margin, double* t) {
  const double cos_d = dot(d, f.n);
  if (cos_d == 0) return false;
  *t = dot(f.a - o, f.n) / cos_d;
  if (!(*t > 1e-9)) return false;
  const Vec3d y = o + *t * d;
  const double area = dot(cross(f.b - f.a, f.c - f.a), f.n);
  const double w0 = dot(cross(f.b - y, f.c - y), f.n) / area,
               w1 = dot(cross(f.c - y, f.a - y), f.n) / area,
               w2 = dot(cross(f.a - y, f.b - y), f.n) / area;
  return w0 >= margin && w1 >= margin && w2 >= margin;
}

// Every chain found at x, by runs that cover them all.
std::vector<MeshChain> all_chains(const FacetChainTree& tree, Vec3 x, int reflections) {
  const MeshChains first = tree.chains_toward(x, reflections, kMaxMeshChainsReturned, 0.0);
  EXPECT_EQ(first.dropped, 0);
  std::vector<MeshChain> out;
  for (int start = 0; start < first.found; start += kMaxMeshChainsReturned) {
    const MeshChains run =
        tree.chains_toward(x, reflections, kMaxMeshChainsReturned, (start + 0.5) / first.found);
    EXPECT_EQ(run.found, first.found);
    for (int i = 0; i < run.returned && start + i < first.found; ++i) {
      out.push_back(run.chain[static_cast<size_t>(i)]);
    }
  }
  return out;
}

// Whether p lies on a facet of the mesh whose outward normal is n.
bool on_facet(const std::vector<Triangle>& facets, Vec3 p, Vec3 n) {
  for (const Triangle& f : facets) {
    if (!(dot(Vec3d(n), f.n) > 1.0 - 1e-6)) continue;
    // From just off the plane, back onto it: the hit must fall inside the triangle.
    double t = 0;
    if (meets(f, Vec3d(p) + 1e-5 * f.n, -f.n, -1e-4, &t) && t < 2e-5) return true;
  }
  return false;
}

// Every chain obeys Snell's law at its entry and wherever it crosses out and in, and the law of
// reflection at each other point, each of its points lies on a facet of the mesh with the normal
// it carries, and its Fresnel product and Jacobian are those of its facets.
void expect_valid(const std::vector<MeshChain>& chains, const std::vector<Triangle>& facets,
                  int levels, Vec3 light, Vec3 x, const std::string& name) {
  for (const MeshChain& c : chains) {
    ASSERT_EQ(c.levels, levels) << name;
    ASSERT_TRUE(on_facet(facets, c.y, c.n)) << name << ": the entry is on no facet";
    for (int b = 0; b < c.events; ++b) {
      ASSERT_TRUE(
          on_facet(facets, c.point[static_cast<size_t>(b)], c.normal[static_cast<size_t>(b)]))
          << name << ": point " << b << " is on no facet with its normal";
    }
    Vec3d d = refracted_inward(Vec3d(c.n), normalize(Vec3d(light)), kEta);
    ASSERT_GT(length(d), 0.5) << name;
    double jacobian = std::abs(dot(Vec3d(c.n), d));
    Vec3d at(c.y);
    double length_inside = 0, fresnel = 1;
    int crossings = 0;
    for (int b = 0; b <= c.events; ++b) {
      const Vec3d next = b < c.events ? Vec3d(c.point[static_cast<size_t>(b)]) : Vec3d(x);
      const Vec3d step = next - at;
      const bool outside = b > 0 && c.leaves[static_cast<size_t>(b - 1)];
      if (!outside) length_inside += length(step);
      ASSERT_GT(dot(normalize(step), d), 1.0 - 1e-6) << name << ": segment " << b;
      at = next;
      if (b == c.events) break;
      const Vec3d n(c.normal[static_cast<size_t>(b)]);
      const double cos_d = dot(d, n);
      if (outside) {
        // Entering again from outside: Snell's law into the inside.
        ASSERT_LT(cos_d, 0) << name;
        const Vec3d in = refracted_inward(n, -d, kEta);
        fresnel *= 1.0 - fresnel_dielectric(static_cast<float>(-cos_d), kEta);
        jacobian *= -dot(in, n) / -cos_d;
        d = in;
        continue;
      }
      ASSERT_GT(cos_d, 0) << name << ": the beam must meet point " << b << " from inside";
      const double reflectance = fresnel_dielectric(static_cast<float>(cos_d), 1.0f / kEta);
      if (c.leaves[static_cast<size_t>(b)]) {
        const Vec3d out = refracted_inward(-n, -d, 1.0 / kEta);
        ASSERT_GT(length(out), 0.5) << name << ": no light leaves beyond the critical angle";
        fresnel *= 1.0 - reflectance;
        jacobian *= dot(out, n) / cos_d;
        d = out;
        ++crossings;
      } else {
        fresnel *= reflectance;
        d = reflect_off(d, n);
      }
    }
    EXPECT_EQ(c.events, levels + crossings) << name;
    EXPECT_GT(dot(Vec3d(c.omega_last), d), 1.0 - 1e-6) << name;
    EXPECT_NEAR(c.length, length_inside, 1e-5 * (1 + length_inside)) << name;
    EXPECT_NEAR(c.fresnel, fresnel, 1e-4 * fresnel) << name;
    // The chain's normals are stored in float: near grazing exits the cosine ratios amplify it.
    EXPECT_NEAR(c.jacobian, jacobian, 1e-3 * jacobian) << name;
  }
}

TEST(FacetChainTree, ChainsObeyTheLawsOfRefractionAndReflection) {
  TestRng rng(21);
  for (const NamedMesh& m : meshes()) {
    const Box box = bounds(m.mesh);
    const std::vector<Triangle> facets = triangles(m.mesh);
    int found = 0, most = 0;
    for (int k = 0; k < 6; ++k) {
      const Vec3 light = sample_uniform_sphere(rng.uniform2());
      const FacetChainTree tree(m.mesh, kEta, light, kReflections);
      ASSERT_EQ(tree.levels_solved(), kReflections) << m.name;
      for (int j = 0; j < 30; ++j) {
        const Vec3 x = random_inside(rng, m.mesh, box);
        for (int r = 1; r <= kReflections; ++r) {
          const std::vector<MeshChain> chains = all_chains(tree, x, r);
          found += static_cast<int>(chains.size());
          most = std::max(most, static_cast<int>(chains.size()));
          expect_valid(chains, facets, r, light, x, m.name);
        }
      }
    }
    std::cout << m.name << ": " << found << " chains found, at most " << most << " at a point\n";
    EXPECT_GT(found, 300) << m.name;
  }
}

// Completeness: light refracted in at a random point of a lit facet, followed inside to its
// first r reflections or crossings (the nearest facet each time), passes through a point x of
// its last segment; the tree must return the chain from x. Hits within 0.1% of a facet's edges,
// which a neighbour may rightly claim, are not drawn.
TEST(FacetChainTree, FindsEveryForwardTracedChain) {
  TestRng rng(22);
  for (const NamedMesh& m : meshes()) {
    const std::vector<Triangle> facets = triangles(m.mesh);
    int traced[kReflections + 1] = {}, crossed[kReflections + 1] = {};
    for (int k = 0; k < 10; ++k) {
      const Vec3 light = sample_uniform_sphere(rng.uniform2());
      const FacetChainTree tree(m.mesh, kEta, light, kReflections);
      for (int j = 0; j < 100; ++j) {
        const Triangle& f = facets[static_cast<size_t>(rng.uniform() * facets.size())];
        double u = 0.01 + 0.98 * rng.uniform(), v = 0.01 + 0.98 * rng.uniform();
        if (u + v > 0.99) {
          u = 0.99 - u;
          v = 0.99 - v;
        }
        Vec3d at = f.a + u * (f.b - f.a) + v * (f.c - f.a);
        const Vec3d y = at;
        Vec3d d = refracted_inward(f.n, normalize(Vec3d(light)), kEta);
        if (!(length(d) > 0)) continue;
        // The nearest facet ahead of `at` along `d`, unless the hit is near an edge.
        const auto nearest_facet = [&](double* distance) -> const Triangle* {
          *distance = kInfinity;
          const Triangle* hit = nullptr;
          bool near_edge = false;
          for (const Triangle& g : facets) {
            double t = 0;
            if (!meets(g, at, d, -1e-6, &t) || !(t > 1e-7) || !(t < *distance)) continue;
            *distance = t;
            hit = &g;
            near_edge = !meets(g, at, d, 1e-3, &t);
          }
          return near_edge ? nullptr : hit;
        };
        for (int r = 1; r <= kReflections; ++r) {
          double distance = 0;
          const Triangle* hit = nearest_facet(&distance);
          if (hit == nullptr || !(dot(d, hit->n) > 0)) break;
          at = at + distance * d;
          // Half the time the light leaves where it can, and the chain goes on if it enters the
          // mesh again.
          const Vec3d out = refracted_inward(-hit->n, -d, 1.0 / kEta);
          if (length(out) > 0 && rng.uniform() < 0.5) {
            d = out;
            const Triangle* back_in = nearest_facet(&distance);
            if (back_in == nullptr || !(dot(d, back_in->n) < 0)) break;
            at = at + distance * d;
            d = refracted_inward(back_in->n, -d, kEta);
            if (!(length(d) > 0)) break;
            ++crossed[r];
          } else {
            d = reflect_off(d, hit->n);
          }
          double next = kInfinity;
          for (const Triangle& g : facets) {
            double t = 0;
            if (meets(g, at, d, -1e-6, &t) && t > 1e-7) next = std::min(next, t);
          }
          if (!(next < kInfinity)) break;
          const Vec3 x(at + (0.05 + 0.9 * rng.uniform()) * next * d);
          bool found_it = false;
          for (const MeshChain& c : all_chains(tree, x, r))
            found_it |= length(Vec3d(c.y) - y) < 1e-4;
          EXPECT_TRUE(found_it) << m.name << ": a chain of " << r << " levels entering at (" << y.x
                                << ", " << y.y << ", " << y.z << ") is not found";
          if (!found_it) return;
          ++traced[r];
        }
      }
    }
    for (int r = 1; r <= kReflections; ++r) {
      std::cout << m.name << ": " << traced[r] << " chains of " << r << " levels traced, "
                << crossed[r] << " of them crossing out and in at level " << r << "\n";
      EXPECT_GT(traced[r], 100) << m.name << ", " << r << " levels";
    }
    // The bunny is not convex: light leaving it enters it again (its ears, its back).
    if (m.name == "bunny") {
      EXPECT_GT(crossed[1] + crossed[2] + crossed[3], 20);
    }
  }
}

// The oracle on a small icosphere: every sequence of facets (entry, then one facet per
// reflection), traced back from x by the laws of reflection and refraction alone; the entry
// point of each that holds.
std::vector<Vec3d> every_sequence(const std::vector<Triangle>& facets, Vec3 light, Vec3 x,
                                  int reflections) {
  const Vec3d l = normalize(Vec3d(light));
  std::vector<Vec3d> entries;
  std::vector<size_t> sequence(static_cast<size_t>(reflections) + 1, 0);
  const size_t n = facets.size();
  for (;;) {
    Vec3d d = refracted_inward(facets[sequence[0]].n, l, kEta);
    bool valid = length(d) > 0;
    std::vector<Vec3d> direction{d};
    for (int r = 1; r <= reflections && valid; ++r) {
      const Vec3d& nr = facets[sequence[static_cast<size_t>(r)]].n;
      valid = dot(d, nr) > 0;
      d = reflect_off(d, nr);
      direction.push_back(d);
    }
    Vec3d at(x);
    for (int r = reflections; r >= 0 && valid; --r) {
      double t = 0;
      valid = meets(facets[sequence[static_cast<size_t>(r)]], at,
                    -direction[static_cast<size_t>(r)], 0.0, &t);
      at = at - t * direction[static_cast<size_t>(r)];
    }
    if (valid) entries.push_back(at);
    size_t digit = 0;
    while (digit < sequence.size() && ++sequence[digit] == n) sequence[digit++] = 0;
    if (digit == sequence.size()) return entries;
  }
}

TEST(FacetChainTree, FindsWhatEverySequenceOfFacetsFinds) {
  TestRng rng(23);
  const TriangleMesh mesh = test::icosphere(1, false);
  const std::vector<Triangle> facets = triangles(mesh);
  const Box box = bounds(mesh);
  int found = 0;
  for (int k = 0; k < 4; ++k) {
    const Vec3 light = sample_uniform_sphere(rng.uniform2());
    const FacetChainTree tree(mesh, kEta, light, 2);
    for (int j = 0; j < 6; ++j) {
      const Vec3 x = random_inside(rng, mesh, box);
      for (int r = 1; r <= 2; ++r) {
        // The same chains: as many, and each of the oracle's entry points among the tree's.
        const std::vector<MeshChain> chains = all_chains(tree, x, r);
        const std::vector<Vec3d> entries = every_sequence(facets, light, x, r);
        ASSERT_EQ(chains.size(), entries.size()) << r << " reflections";
        for (const Vec3d& y : entries) {
          bool in_tree = false;
          for (const MeshChain& c : chains) in_tree |= length(Vec3d(c.y) - y) < 1e-5;
          EXPECT_TRUE(in_tree) << r << " reflections: the entry (" << y.x << ", " << y.y << ", "
                               << y.z << ") is not found";
        }
        found += static_cast<int>(chains.size());
      }
    }
  }
  EXPECT_GT(found, 30);
}

// What a level costs on the bunny: fragments per triangle and the time to build them.
TEST(FacetChainTree, FragmentsOnTheBunny) {
  const TriangleMesh mesh = bunny();
  const auto start = std::chrono::steady_clock::now();
  const FacetChainTree tree(mesh, kEta, normalize(Vec3(1, 1, 1)), kDefaultMeshChainLevels);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "built in " << seconds << " s over " << mesh.triangle_count() << " triangles:";
  for (int r = 1; r <= tree.levels_solved(); ++r) std::cout << " " << tree.fragments(r);
  std::cout << " fragments\n";
  // Every default level fits the bunny, each holding more than the one below (each beam splits over
  // the facets ahead of it).
  ASSERT_EQ(tree.levels_solved(), kDefaultMeshChainLevels);
  for (int r = 2; r <= kDefaultMeshChainLevels; ++r)
    EXPECT_GT(tree.fragments(r), tree.fragments(r - 1));
  // A level that does not fit what is left of the allowance is left out, with every level above
  // it: room for twice the first level's fragments after what a one-level tree holds is ample
  // for the first and, as the second holds more than twice as many, too little for the second.
  const FacetChainTree one(mesh, kEta, normalize(Vec3(1, 1, 1)), 1);
  ASSERT_GT(tree.fragments(2), 2 * tree.fragments(1));
  const uint64_t allowance =
      one.bytes() + 2 * tree.fragments(1) * FacetChainTree::bytes_per_fragment();
  const FacetChainTree small(mesh, kEta, normalize(Vec3(1, 1, 1)), kDefaultMeshChainLevels,
                             allowance);
  EXPECT_EQ(small.levels_solved(), 1);
  EXPECT_EQ(small.fragments(1), tree.fragments(1));
  EXPECT_LE(small.bytes(), allowance);
  EXPECT_EQ(small.chains_toward(Vec3(0, 0, 0), 2, kMaxMeshChainsReturned, 0.5).found, 0);
}

}  // namespace
}  // namespace snee
