// Whole-mesh geometric checks the loader needs before a mesh may bound a medium: whether every
// edge is shared by exactly two triangles, which way the triangles face, and a normalizing
// placement so meshes from different sources come out the same size.
#pragma once

#include <cstddef>

#include "core/math.h"
#include "scene/scene.h"

namespace snee {

struct EdgeCounts {
  size_t boundary = 0;      // edges used by one triangle: the mesh has a hole there
  size_t non_manifold = 0;  // edges used by more than two triangles
};

// Edges are undirected: a-b and b-a are the same edge.
EdgeCounts count_edges(const TriangleMesh& mesh);

// Volume enclosed by a closed mesh; positive when the winding is counter-clockwise seen from
// outside (outward normals), negative when the mesh is inside out.
double signed_volume(const TriangleMesh& mesh);

void flip_winding(TriangleMesh& mesh);

// The mesh's positions and triangles with every vertex number replaced by the first vertex at
// the same position (no normals or texture coordinates), for count_edges on meshes whose
// vertices are split where their normals or texture coordinates differ.
TriangleMesh welded_by_position(const TriangleMesh& mesh);

// Moves the centre of the bounding box to the origin and scales so that the smallest sphere
// about that centre holding every vertex has radius 1.
Transform normalizing_transform(const TriangleMesh& mesh);

void apply_transform(const Transform& transform, TriangleMesh& mesh);

}  // namespace snee
