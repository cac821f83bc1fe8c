// What the scene loader does with every mesh it reads (scene_reader_shapes.cpp), so that the mesh
// fuzzers reach the whole-mesh code with the same arbitrary meshes the readers let through.
#pragma once

#include "scene/mesh_topology.h"
#include "scene/scene.h"

namespace snee::fuzz {

inline void run_loader_mesh_checks(TriangleMesh& mesh) {
  apply_transform(normalizing_transform(mesh), mesh);
  const EdgeCounts edges = count_edges(mesh);
  if (edges.boundary == 0 && signed_volume(mesh) < 0) flip_winding(mesh);
}

}  // namespace snee::fuzz
