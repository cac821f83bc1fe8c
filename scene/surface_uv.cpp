#include "scene/surface_uv.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scene/vertex_normals.h"

namespace snee {

SurfaceUv surface_uv(const Shape& shape, size_t prim, Vec3 p) {
  if (shape.kind == ShapeKind::kSphere)
    return {sphere_uv(shape, p), sphere_uv_per_length(shape, p)};
  return {interpolated_uv(shape.mesh, prim, p), uv_per_length(shape.mesh, prim)};
}

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

namespace {

// Cosine of the polar angle of p seen from the sphere's centre, in [-1, 1].
float sphere_cos_theta(const Shape& sphere, Vec3 p) {
  return std::clamp((p.y - sphere.center.y) / sphere.radius, -1.0f, 1.0f);
}

}  // namespace

Uv sphere_uv(const Shape& sphere, Vec3 p) {
  const Vec3 d = p - sphere.center;
  const float u = std::atan2(d.x, d.z) * (0.5f * std::numbers::inv_pi_v<float>)+0.5f;
  const float v = std::acos(sphere_cos_theta(sphere, p)) * std::numbers::inv_pi_v<float>;
  return {u, v};
}

float sphere_uv_per_length(const Shape& sphere, Vec3 p) {
  const float cos_theta = sphere_cos_theta(sphere, p);
  const float sin_theta = std::max(std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta)), 1e-3f);
  return std::numbers::inv_pi_v<float> / (sphere.radius * std::sqrt(2.0f * sin_theta));
}

}  // namespace snee
