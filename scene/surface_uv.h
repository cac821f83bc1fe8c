// Texture coordinates at a point of a mesh triangle, and how fast they change across it, for
// texture lookups at hit points. Like the shading normal (vertex_normals.h), they are
// interpolated from the hit point, so a path slot stores nothing more than its hit.
#pragma once

#include <cstddef>

#include "scene/math.h"
#include "scene/scene.h"

namespace snee {

// The interpolated texture coordinates of triangle `triangle` at p (mesh.uvs must be filled).
Uv interpolated_uv(const TriangleMesh& mesh, size_t triangle, Vec3 p);

// Texture units per world unit across the triangle: the square root of its area in texture
// space over its area in space (0 for a triangle degenerate in either), so a footprint w world
// units wide covers about w times this of the texture.
float uv_per_length(const TriangleMesh& mesh, size_t triangle);

}  // namespace snee
