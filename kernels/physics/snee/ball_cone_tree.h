// A tree over items that each send light from a small region along a bounded set of directions
// (a facet lit by a point light, the fragment of a facet a reflected beam leaves from): every node
// bounds its items' points by a ball and their directions by a cone, so a query for a point x
// opens only the nodes from which some ray could pass through x. The manifold strategy's mesh
// solvers (docs/method.md 3.13) keep their items in their own order and ask the tree for the
// candidates; the exact test is theirs.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/vec3d.h"
#include "kernels/physics/snee/manifold_mesh.h"

namespace snee {

class BallConeTree {
 public:
  // One item's bounds: the box of its vertices, a point to split by, and a cone (unit axis,
  // half-angle in radians) around the directions it sends light along.
  struct Bounds {
    Vec3d lo{kInfinity, kInfinity, kInfinity}, hi{-kInfinity, -kInfinity, -kInfinity};
    Vec3 centroid;
    Vec3d axis;
    double spread = 0;
    void add(Vec3d p) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
  };

  BallConeTree() = default;
  explicit BallConeTree(std::vector<Bounds> items);
  // The most bytes a tree over `items` items takes, the items it is given and its building
  // included, for memory budgets checked before building.
  static uint64_t bytes_at_most(uint64_t items);
  // What each item adds to the built tree: its index and two nodes.
  static uint64_t bytes_per_item() { return sizeof(uint32_t) + 2 * sizeof(Node); }

  // Calls candidate(i) for every item i (its index in the constructor's vector) whose ball and
  // cone could send a ray through x, in a fixed order.
  template <class Candidate>
  void for_each_candidate(const Vec3d& x, const Candidate& candidate) const {
    // A ray from a point of the ball along a direction of the cone reaches x only if the
    // directions from the ball to x (within asin(radius / distance) of the centre's) meet the
    // cone.
    const auto opens = [&x](const Node& node) {
      const Vec3d to_x = x - Vec3d(node.centre);
      const double distance = length(to_x);
      if (!(distance > node.radius)) return true;
      const double seen = std::asin(std::min(1.0, node.radius / distance));
      return angle_between(to_x / distance, Vec3d(node.axis)) <= node.half_angle + seen;
    };
    walk_tree(nodes_, opens, [&](const Node& node) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i) candidate(item_[i]);
    });
  }

  static double angle_between(const Vec3d& a, const Vec3d& b) {
    return std::acos(std::clamp(dot(a, b), -1.0, 1.0));
  }

 private:
  struct Node {
    Vec3 centre;  // a ball around the items' vertices
    float radius = 0;
    Vec3 axis;  // a cone around their directions
    float half_angle = 0;
    uint32_t first = 0, count = 0;  // items of a leaf; count 0: children at index + 1, second
    uint32_t second = 0;
  };
  struct Entry {
    Bounds bounds;
    uint32_t item = 0;
  };
  uint32_t build(std::vector<Entry>& entries, uint32_t first, uint32_t count);

  std::vector<uint32_t> item_;  // the items in the leaves' order
  std::vector<Node> nodes_;
};

}  // namespace snee
