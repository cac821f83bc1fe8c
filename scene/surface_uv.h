// Texture coordinates at a surface point, and how fast they change across the surface, for
// texture lookups at hit points. Like the shading normal (vertex_normals.h), they are computed
// from the hit point, so a path slot stores nothing more than its hit.
#pragma once

#include <cstddef>

#include "core/math.h"
#include "scene/scene.h"

namespace snee {

struct SurfaceUv {
  Uv uv;
  // Texture units per world unit around the point: the square root of the area the surface
  // covers in texture space over its area in space, so a footprint w world units wide covers
  // about w times this of the texture (0 where the mapping is degenerate).
  float per_length = 0;
};

// At point p of triangle `prim` of a mesh shape (whose mesh.uvs must be filled), or of a sphere.
SurfaceUv surface_uv(const Shape& shape, size_t prim, Vec3 p);

// The interpolated texture coordinates of triangle `triangle` at p (mesh.uvs must be filled).
Uv interpolated_uv(const TriangleMesh& mesh, size_t triangle, Vec3 p);
float uv_per_length(const TriangleMesh& mesh, size_t triangle);

// A sphere wears its texture like a globe, y up: for the unit direction d from its centre to p,
// u = atan2(d.x, d.z) / (2 pi) + 0.5 and v = acos(d.y) / pi. The image's centre faces +z, its top
// row is the north pole, and seen from outside it reads left to right (unmirrored).
Uv sphere_uv(const Shape& sphere, Vec3 p);
// 1 / (pi r sqrt(2 sin(theta))) at polar angle theta, from du dv = dA / (2 pi^2 r^2 sin(theta));
// sin(theta) is held above 1e-3 so the poles stay finite.
float sphere_uv_per_length(const Shape& sphere, Vec3 p);

}  // namespace snee
