#include "scene/surface_uv.h"

#include <cmath>

#include "scene/vertex_normals.h"

namespace snee {

Uv interpolated_uv(const TriangleMesh& mesh, size_t triangle, Vec3 p) {
  const uint32_t i0 = mesh.indices[3 * triangle], i1 = mesh.indices[3 * triangle + 1],
                 i2 = mesh.indices[3 * triangle + 2];
  const Vec3 w = barycentric_weights(mesh.positions[i0], mesh.positions[i1], mesh.positions[i2], p);
  const Uv a = mesh.uvs[i0], b = mesh.uvs[i1], c = mesh.uvs[i2];
  return {a.u * w.x + b.u * w.y + c.u * w.z, a.v * w.x + b.v * w.y + c.v * w.z};
}

float uv_per_length(const TriangleMesh& mesh, size_t triangle) {
  const uint32_t i0 = mesh.indices[3 * triangle], i1 = mesh.indices[3 * triangle + 1],
                 i2 = mesh.indices[3 * triangle + 2];
  const float space_area = length(
      cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]));
  const Uv a = mesh.uvs[i0], b = mesh.uvs[i1], c = mesh.uvs[i2];
  const float uv_area = std::fabs((b.u - a.u) * (c.v - a.v) - (c.u - a.u) * (b.v - a.v));
  if (!(space_area > 0) || !(uv_area > 0)) return 0.0f;
  return std::sqrt(uv_area / space_area);
}

}  // namespace snee
