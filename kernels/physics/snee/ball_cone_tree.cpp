#include "kernels/physics/snee/ball_cone_tree.h"

#include <numbers>

#include "kernels/physics/snee/manifold_mesh.h"
#include "scene/memory_budget.h"

namespace snee {

namespace {

// Widening of every cone and ball, so that rounding in float storage never closes a node that
// holds a solution: relative to the scene's coordinates for balls, in radians for cones.
constexpr double kRelativeSlack = 1e-5;
constexpr double kAngleSlack = 1e-5;
constexpr double kPiD = std::numbers::pi;

}  // namespace

BallConeTree::BallConeTree(std::vector<Bounds> items) {
  if (items.empty()) return;
  std::vector<Entry> entries;
  entries.reserve(items.size());
  for (size_t i = 0; i < items.size(); ++i) {
    entries.push_back({items[i], static_cast<uint32_t>(i)});
  }
  items = {};
  nodes_.reserve(2 * entries.size() + 1);
  build(entries, 0, static_cast<uint32_t>(entries.size()));
  item_.reserve(entries.size());
  for (const Entry& e : entries) item_.push_back(e.item);
}

uint64_t BallConeTree::bytes_at_most(uint64_t items) {
  const uint64_t nodes = saturating_add(saturating_multiply(2, items), 1);
  return saturating_add(
      saturating_multiply(items, sizeof(Bounds) + sizeof(Entry) + sizeof(uint32_t)),
      saturating_multiply(nodes, sizeof(Node)));
}

uint32_t BallConeTree::build(std::vector<Entry>& entries, uint32_t first, uint32_t count) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  // The ball: around the vertices' bounding box.
  Vec3d lo(kInfinity, kInfinity, kInfinity), hi(-kInfinity, -kInfinity, -kInfinity);
  double scale = 0;
  for (uint32_t i = first; i < first + count; ++i) {
    const Bounds& b = entries[i].bounds;
    lo = {std::min(lo.x, b.lo.x), std::min(lo.y, b.lo.y), std::min(lo.z, b.lo.z)};
    hi = {std::max(hi.x, b.hi.x), std::max(hi.y, b.hi.y), std::max(hi.z, b.hi.z)};
    for (const Vec3d& q : {b.lo, b.hi}) {
      scale = std::max({scale, std::abs(q.x), std::abs(q.y), std::abs(q.z)});
    }
  }
  Node node;
  node.centre = Vec3(0.5 * (lo + hi));
  node.radius = static_cast<float>(0.5 * length(hi - lo) + kRelativeSlack * scale);
  // The cone: around the mean of its items' cone axes, covering each item's cone.
  Vec3d sum{};
  for (uint32_t i = first; i < first + count; ++i) sum = sum + entries[i].bounds.axis;
  double half_angle = kPiD;
  Vec3d axis(0, 0, 1);
  if (length(sum) > 1e-9) {
    axis = normalize(sum);
    half_angle = 0;
    for (uint32_t i = first; i < first + count; ++i) {
      const Bounds& b = entries[i].bounds;
      half_angle = std::max(half_angle, angle_between(axis, b.axis) + b.spread);
    }
  }
  node.axis = Vec3(axis);
  node.half_angle = static_cast<float>(std::min(kPiD, half_angle + kAngleSlack));
  if (count <= 1) {
    node.first = first;
    node.count = count;
    nodes_[index] = node;
    return index;
  }
  // Split at the median of the centroids along the box's widest axis.
  const uint32_t half = split_at_median(entries, first, count, hi - lo,
                                        [](const Entry& e) { return e.bounds.centroid; });
  nodes_[index] = node;
  build(entries, first, half);
  nodes_[index].second = build(entries, first + half, count - half);
  return index;
}

}  // namespace snee
