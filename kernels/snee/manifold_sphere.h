// Refracted next-event estimation through a smooth sphere under a directional light
// (docs/method.md 3.10): the exit points y from which the light, refracted into the sphere,
// travels straight to a given interior point x, and the volume Jacobian that turns the light's
// area-times-distance measure at y into volume at x. The sphere's symmetry puts every solution
// in the plane spanned by the light direction and x - centre, where the refraction condition
// squares into a polynomial of degree 8, so all solutions are enumerated exactly (no Newton
// start point can miss one).
#pragma once

#include <array>

#include "scene/math.h"

namespace snee {

// At most 8 roots; in practice a point sees the light through 1 to 3 points of the sphere.
inline constexpr int kMaxSphereExits = 8;

struct SphereExit {
  Vec3 y;        // exit point on the sphere
  Vec3 n;        // outward normal there
  Vec3 omega_r;  // unit propagation direction of the refracted light inside, from y toward x
  double t = 0;  // |x - y|
};

struct SphereExits {
  std::array<SphereExit, kMaxSphereExits> exit{};
  int count = 0;
};

// Every point y of the sphere (centre, radius, relative index eta = inside / outside) facing
// the light (n . light > 0) whose refraction of the directional light (light = unit direction
// toward it) passes through x, which must lie inside. None when x lies on the axis through the
// centre along the light (a set of zero volume, where the solutions form a ring).
SphereExits sphere_exits_toward_light(Vec3 centre, float radius, float eta, Vec3 light, Vec3 x);

// |dV(x) / (dA(y) dt)| for x = y + t omega_r(y), with omega_r the refraction of the fixed light
// direction through the normal n(y) of a surface whose normal turns by `curvature` per unit
// length in every tangent direction (1 / radius for a sphere, 0 for a flat triangle, where it
// is the cosine |n . omega_r|). Zero on the caustic.
double refraction_volume_jacobian(Vec3 n, Vec3 light, float eta, double curvature, double t);

}  // namespace snee
