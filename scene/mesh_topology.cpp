#include "scene/mesh_topology.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace snee {

EdgeCounts count_edges(const TriangleMesh& mesh) {
  // Sorting packed edge keys is several times faster than a hash map on million-triangle scans.
  std::vector<uint64_t> keys;
  keys.reserve(mesh.indices.size());
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = mesh.indices[3 * t + e];
      const uint32_t b = mesh.indices[3 * t + (e + 1) % 3];
      keys.push_back((uint64_t{std::min(a, b)} << 32) | std::max(a, b));
    }
  }
  std::sort(keys.begin(), keys.end());

  EdgeCounts counts;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    if (j - i == 1) ++counts.boundary;
    if (j - i > 2) ++counts.non_manifold;
    i = j;
  }
  return counts;
}

double signed_volume(const TriangleMesh& mesh) {
  // Sum of signed tetrahedra from the origin; double precision because the terms of a large
  // mesh far from the origin cancel heavily.
  double six_volume = 0;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 p0 = mesh.positions[mesh.indices[3 * t]];
    const Vec3 p1 = mesh.positions[mesh.indices[3 * t + 1]];
    const Vec3 p2 = mesh.positions[mesh.indices[3 * t + 2]];
    six_volume += double{p0.x} * (double{p1.y} * p2.z - double{p1.z} * p2.y) +
                  double{p0.y} * (double{p1.z} * p2.x - double{p1.x} * p2.z) +
                  double{p0.z} * (double{p1.x} * p2.y - double{p1.y} * p2.x);
  }
  return six_volume / 6.0;
}

void flip_winding(TriangleMesh& mesh) {
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
  }
}

Transform normalizing_transform(const TriangleMesh& mesh) {
  Vec3 lo(kInfinity), hi(-kInfinity);
  for (const Vec3& p : mesh.positions) {
    lo = vmin(lo, p);
    hi = vmax(hi, p);
  }
  const Vec3 center = (lo + hi) * 0.5f;
  float radius = 0;
  for (const Vec3& p : mesh.positions) radius = std::max(radius, length(p - center));
  if (!(radius > 0)) return Transform::translate(-center);
  return Transform::scale(Vec3(1.0f / radius)) * Transform::translate(-center);
}

void apply_transform(const Transform& transform, TriangleMesh& mesh) {
  for (Vec3& p : mesh.positions) p = transform.point(p);
}

}  // namespace snee
