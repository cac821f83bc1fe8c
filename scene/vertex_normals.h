// Vertex normals of a triangle mesh for smooth shading (docs/method.md 4.9): checking the ones
// a file supplies, and interpolating them at a point of a triangle. Interpolation works from
// the hit point rather than from the tracer's barycentrics, so a path slot stores nothing
// more than its hit distance and primitive.
#pragma once

#include <cstddef>
#include <string>

#include "core/math.h"
#include "scene/scene.h"

namespace snee {

// Makes every normal unit length; throws SceneError naming `source` and the vertex (1-based)
// if one is zero or not finite, as no direction can be made of it.
void normalize_vertex_normals(TriangleMesh& mesh, const std::string& source);

// Barycentric weights of p (a point on or within rounding of triangle a, b, c) for a, b and c:
// clamped to [0, 1] and summing to 1, so that a point a few ulps outside still interpolates
// between the triangle's own corners.
Vec3 barycentric_weights(Vec3 a, Vec3 b, Vec3 c, Vec3 p);

// The interpolated vertex normal of triangle `triangle` at p, unit, turned to the side of the
// outward geometric normal ng (the side rules of docs/method.md 4.9 compare the two); ng itself
// where the interpolation vanishes.
Vec3 interpolated_normal(const TriangleMesh& mesh, size_t triangle, Vec3 p, Vec3 ng);

}  // namespace snee
