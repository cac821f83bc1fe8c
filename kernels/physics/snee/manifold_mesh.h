// Refracted next-event estimation through a closed, flat-shaded triangle mesh under a
// directional light (docs/method.md 3.13): the exit points y from which the light, refracted
// into the mesh, travels straight to a given interior point x. On a flat facet the refracted
// light is one parallel beam of direction omega_r, so a facet holds a solution exactly when the
// ray from x backwards along its omega_r hits it; the solutions are enumerated exactly, as
// Walter et al. (2009) do for triangle-mesh boundaries, by a tree over the facets lit by the
// light, so that only nodes some beam through x could come from are opened. Its bounds live in
// "beam space": height h along the light's travel and two coordinates (a, b) across it, where
// every beam rises (omega_r turns from the light's travel by less than 90 degrees) and moves
// across by its tilt (omega_r's across components over its along component) per unit of
// height; a node bounds its facets' coordinates and their beams' tilts.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/vec3d.h"
#include "scene/scene.h"

namespace snee {

// Most exit points one query returns (more are counted as dropped). A point inside the bunny sees
// the light through 0 to 4 facets mostly, and up to about 30 (most of them behind another part
// of the mesh, which the connection's rays find).
inline constexpr int kMaxMeshExits = 64;

struct MeshExit {
  Vec3 y;        // exit point on the facet
  Vec3 n;        // the facet's outward normal
  Vec3 omega_r;  // unit propagation direction of the refracted light inside, from y toward x
  double t = 0;  // |x - y|
};

struct MeshExits {
  std::array<MeshExit, kMaxMeshExits> exit{};
  int count = 0;
  int dropped = 0;  // solutions beyond kMaxMeshExits (none seen in tests)
};

// The refraction of light arriving from direction `light` (unit, toward the light) through a
// surface of outward normal n into the inside (relative index eta), as a unit propagation
// direction; zero when the surface faces away or the light cannot enter.
Vec3d refracted_inward(const Vec3d& n, const Vec3d& light, double eta);

// Calls f(p0, p1, p2, n) for every triangle of `mesh` with a non-zero area: its corners in
// winding order and its outward unit normal, in double.
template <class F>
void for_each_facet(const TriangleMesh& mesh, const F& f) {
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3& p0 = mesh.positions[mesh.indices[3 * t]];
    const Vec3& p1 = mesh.positions[mesh.indices[3 * t + 1]];
    const Vec3& p2 = mesh.positions[mesh.indices[3 * t + 2]];
    const Vec3d area = cross(Vec3d(p1) - Vec3d(p0), Vec3d(p2) - Vec3d(p0));
    if (length(area) > 0) f(p0, p1, p2, normalize(area));
  }
}

// The facet trees split a node at the median along the widest axis of its `extent`: reorders
// items[first, first + count) so that the lower half by that coordinate of position(item) comes
// first, and returns that half's size.
template <class Item, class Position>
uint32_t split_at_median(std::vector<Item>& items, uint32_t first, uint32_t count,
                         const Vec3d& extent, const Position& position) {
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const auto key = [&position, axis](const Item& item) {
    const auto c = position(item);
    return axis == 0 ? c.x : (axis == 1 ? c.y : c.z);
  };
  const uint32_t half = count / 2;
  std::nth_element(items.begin() + first, items.begin() + first + half,
                   items.begin() + first + count,
                   [&key](const Item& a, const Item& b) { return key(a) < key(b); });
  return half;
}

// Where the ray from `from` against `direction` meets the triangle p0 + u e1 + v e2
// (Moller-Trumbore): false where it misses it or meets it behind, else its u, v and distance t.
inline bool meets_backwards(const Vec3d& p0, const Vec3d& e1, const Vec3d& e2, const Vec3d& from,
                            const Vec3d& direction, double* u, double* v, double* t) {
  const Vec3d back = -direction;
  const Vec3d p = cross(back, e2);
  const double det = dot(e1, p);
  if (!(std::abs(det) > 0)) return false;
  const Vec3d to_from = from - p0;
  *u = dot(to_from, p) / det;
  if (*u < 0 || *u > 1) return false;
  const Vec3d q = cross(to_from, e1);
  *v = dot(back, q) / det;
  if (*v < 0 || *u + *v > 1) return false;
  *t = dot(e2, q) / det;
  return *t > 0;
}

// The facet trees' depth-first walk: each stores a node's first child right after it and the
// second at node.second (count 0), or a leaf's items (count > 0). Goes into the nodes for which
// opens(node) holds and calls leaf(node) on each leaf reached, first children first.
template <class Node, class Opens, class Leaf>
void walk_tree(const std::vector<Node>& nodes, const Opens& opens, const Leaf& leaf) {
  if (nodes.empty()) return;
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const uint32_t index = stack[--top];
    const Node& node = nodes[index];
    if (!opens(node)) continue;
    if (node.count == 0) {
      stack[top++] = node.second;
      stack[top++] = index + 1;
      continue;
    }
    leaf(node);
  }
}

class FacetExitTree {
 public:
  // The facets of `mesh` (world space, outward winding) that face `light` (unit direction
  // toward it) and refract it into the inside (relative index eta = inside / outside).
  FacetExitTree(const TriangleMesh& mesh, float eta, Vec3 light);
  // The most bytes one tree over a mesh of `triangles` triangles holds (every facet lit, a
  // full binary tree over them), for the memory budget to be checked before it is built.
  static uint64_t bytes_at_most(uint64_t triangles);

  Vec3 light() const { return light_; }

  // Every exit point whose refracted beam passes through x (which should lie inside). Whether
  // the beam reaches x unblocked, and the light reaches y, is for the caller's rays to decide.
  MeshExits exits_toward(Vec3 x) const;

 private:
  struct Facet {
    Vec3 p0, e1, e2;  // corner and edges
    Vec3 n;
    Vec3 omega_r;
  };
  // An interval of one beam-space coordinate (a, b or h) or tilt (da/dh or db/dh).
  struct Range {
    float lo = kInfinity, hi = -kInfinity;
    void add(float v) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  };
  struct Node {
    Range a, b, h;                  // the facets' vertices, in beam space
    Range tilt_a, tilt_b;           // their beams' tilts
    uint32_t first = 0, count = 0;  // facets of a leaf; count 0: children at index + 1, second
    uint32_t second = 0;
  };
  uint32_t build(uint32_t first, uint32_t count);
  Vec3d beam_space(Vec3d p) const;

  Vec3 light_;
  Vec3d across_a_, across_b_, along_;  // beam space's axes
  double slack_ = 0;                   // on every range, for the rounding of float storage
  std::vector<Facet> facets_;
  std::vector<Node> nodes_;
};

}  // namespace snee
