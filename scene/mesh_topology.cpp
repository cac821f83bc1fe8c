#include "scene/mesh_topology.h"

#include <map>
#include <tuple>

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

TriangleMesh welded_by_position(const TriangleMesh& mesh) {
  std::map<std::tuple<float, float, float>, uint32_t> first;
  std::vector<uint32_t> renumbered(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3 p = mesh.positions[i];
    renumbered[i] = first.try_emplace({p.x, p.y, p.z}, static_cast<uint32_t>(i)).first->second;
  }
  TriangleMesh welded;
  welded.positions = mesh.positions;
  welded.indices.reserve(mesh.indices.size());
  for (const uint32_t index : mesh.indices) welded.indices.push_back(renumbered[index]);
  return welded;
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
  // Normals go by the inverse transpose of the linear part, which is its cofactor matrix over
  // the determinant; the cofactor columns are cross products of the matrix's columns.
  const Vec3 c0(transform.m[0][0], transform.m[1][0], transform.m[2][0]);
  const Vec3 c1(transform.m[0][1], transform.m[1][1], transform.m[2][1]);
  const Vec3 c2(transform.m[0][2], transform.m[1][2], transform.m[2][2]);
  const float sign = transform.determinant() < 0 ? -1.0f : 1.0f;
  for (Vec3& n : mesh.normals) {
    n = normalize((cross(c1, c2) * n.x + cross(c2, c0) * n.y + cross(c0, c1) * n.z) * sign);
  }
}

}  // namespace snee
