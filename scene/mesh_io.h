// Reading triangle meshes from Wavefront OBJ and Stanford PLY files. Positions come back exactly
// as stored (no transform, winding as in the file); polygons are split into triangle fans.
// Failures throw SceneError naming the file and the line, face or element at fault. Only
// regular files are read (input_file.h); the file and the arrays it needs must each fit in
// `budget`, and counts in a PLY header must fit in the bytes that follow it.
#pragma once

#include <string>

#include "scene/memory_budget.h"
#include "scene/scene.h"

namespace snee {

// Chooses the reader by extension (.obj or .ply, any case).
TriangleMesh load_mesh(const std::string& path, const MemoryBudget& budget = {});
// Vertex coordinates must be three finite numbers and face corners vertex numbers within int
// range; material libraries (mtllib) are never opened, since nothing of them is used. Normals
// (vn) and texture coordinates (vt, v flipped to snee's top-down convention) are kept where
// every face corner names one; a position whose corners name different ones is split.
TriangleMesh load_obj(const std::string& path, const MemoryBudget& budget = {});
// ASCII, binary little-endian and binary big-endian PLY. The vertex element must have x, y and
// z; the face element a list property named vertex_indices or vertex_index. nx, ny, nz are
// normals; u and v (or s and t, texture_u and texture_v, texture_s and texture_t) are texture
// coordinates, v flipped as for OBJ. Every other element and property is read past and ignored.
TriangleMesh load_ply(const std::string& path, const MemoryBudget& budget = {});

}  // namespace snee
