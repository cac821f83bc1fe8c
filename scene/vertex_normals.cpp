#include "scene/vertex_normals.h"

#include <algorithm>
#include <cmath>

#include "scene/scene_error.h"

namespace snee {

namespace {

double dot_double(Vec3 a, Vec3 b) {
  return double{a.x} * b.x + double{a.y} * b.y + double{a.z} * b.z;
}

}  // namespace

void normalize_vertex_normals(TriangleMesh& mesh, const std::string& source) {
  for (size_t i = 0; i < mesh.normals.size(); ++i) {
    const Vec3 n = mesh.normals[i];
    const float len = length(n);
    if (!is_finite(n) || !(len > 0) || !std::isfinite(len)) {
      throw SceneError(source + ": the normal of vertex " + std::to_string(i + 1) +
                       " is zero or not finite (expected a direction)");
    }
    mesh.normals[i] = n / len;
  }
}

Vec3 barycentric_weights(Vec3 a, Vec3 b, Vec3 c, Vec3 p) {
  // Least-squares weights in the triangle's plane (the Gram system of its two edges), so the
  // point need not lie exactly on the plane.
  const Vec3 e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = dot_double(e1, e1), d12 = dot_double(e1, e2), d22 = dot_double(e2, e2);
  const double p1 = dot_double(d, e1), p2 = dot_double(d, e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0)) return {1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f};
  double wb = (d22 * p1 - d12 * p2) / det;
  double wc = (d11 * p2 - d12 * p1) / det;
  double wa = 1.0 - wb - wc;
  wa = std::clamp(wa, 0.0, 1.0), wb = std::clamp(wb, 0.0, 1.0), wc = std::clamp(wc, 0.0, 1.0);
  const double sum = wa + wb + wc;
  return {static_cast<float>(wa / sum), static_cast<float>(wb / sum), static_cast<float>(wc / sum)};
}

Vec3 interpolated_normal(const TriangleMesh& mesh, size_t triangle, Vec3 p, Vec3 ng) {
  const uint32_t i0 = mesh.indices[3 * triangle], i1 = mesh.indices[3 * triangle + 1],
                 i2 = mesh.indices[3 * triangle + 2];
  const Vec3 w = barycentric_weights(mesh.positions[i0], mesh.positions[i1], mesh.positions[i2], p);
  const Vec3 n = mesh.normals[i0] * w.x + mesh.normals[i1] * w.y + mesh.normals[i2] * w.z;
  const float len = length(n);
  if (!(len > 0)) return ng;
  const Vec3 unit = n / len;
  return dot(unit, ng) < 0 ? -unit : unit;
}

}  // namespace snee
