// Refracted next-event estimation through a closed, flat-shaded triangle mesh under a point (or
// spot) light (docs/method.md 3.13): the exit points y on the mesh's facets from which the
// light, arriving from its position and refracted into the mesh, travels straight to a given
// interior point x. On one flat facet the solution lies in the plane of incidence through the
// light, x and the facet's normal, where Snell's law leaves one monotonic equation in one
// unknown: a facet holds at most one solution. A tree over the facets facing the light bounds
// their positions (a ball) and their refracted directions (a cone), so a query opens only the
// nodes some refracted ray through x could come from.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/vec3d.h"
#include "kernels/physics/snee/ball_cone_tree.h"
#include "kernels/physics/snee/manifold_mesh.h"
#include "scene/scene.h"

namespace snee {

class PointFacetTree {
 public:
  // The facets of `mesh` (world space, outward winding) that face the light at
  // `light_position`, for the relative index eta = inside / outside. Only built where
  // point_facet_tree_applies holds.
  PointFacetTree(const TriangleMesh& mesh, float eta, Vec3 light_position, int light);
  // The most bytes one tree over a mesh of `triangles` triangles holds, for the memory budget
  // to be checked before it is built.
  static uint64_t bytes_at_most(uint64_t triangles);

  // The index of the scene light it was built for.
  int light() const { return light_; }

  // Every exit point whose refracted ray passes through x (which should lie inside). Whether
  // it reaches x unblocked, and the light reaches y, is for the caller's rays to decide.
  MeshExits exits_toward(Vec3 x) const;

 private:
  struct Facet {
    Vec3 p0, e1, e2;  // corner and edges
    Vec3 n;           // outward unit normal
  };
  // The facet's exit point toward x, if it has one.
  bool solve(const Facet& f, const Vec3d& x, MeshExit* exit) const;

  Vec3 light_position_;
  int light_ = -1;
  double e_ = 1.0;  // outside / inside index
  std::vector<Facet> facets_;
  BallConeTree tree_;  // over facets_, with cones around their refracted directions
};

// Whether a point light at light_position can be solved for behind `mesh` with relative index
// eta: the light outside the closed mesh (its winding number about the light is 0), and the
// inside denser (eta > 1), where refraction narrows every cone of directions it maps, which the
// tree's bounds rely on.
bool point_facet_tree_applies(const TriangleMesh& mesh, float eta, Vec3 light_position);

}  // namespace snee
