// Refracted next-event estimation through a smooth sphere under a directional light
// (docs/method.md 3.10): the exit points y from which the light, refracted into the sphere,
// travels straight to a given interior point x, and the volume Jacobian that turns the light's
// area-times-distance measure at y into volume at x. The sphere's symmetry puts every solution
// in the plane spanned by the light direction and x - centre, where the refraction condition
// squares into a polynomial of degree 8, so all solutions are enumerated exactly (no Newton
// start point can miss one).
#pragma once

#include <array>
#include <cstddef>

#include "core/math.h"

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

// The same for a point (or spot) light at light_position, outside the sphere: every y that sees
// the light and refracts the ray arriving from it into a ray through x. The sphere's normal at
// y passes through the centre, so the solutions lie in the plane of the centre, the light and
// x, where the squared condition is a polynomial of degree 6 (docs/method.md 3.10). None when
// the light is not outside or x lies on the axis through the centre and the light.
SphereExits sphere_exits_toward_point(Vec3 centre, float radius, float eta, Vec3 light_position,
                                      Vec3 x);

// |dV(x) / (dA(y) dt)| for x = y + t omega_r(y), with omega_r the refraction, through the normal
// n(y) of a surface whose normal turns by `curvature` per unit length in every tangent direction
// (1 / radius for a sphere, 0 for a flat triangle), of the light arriving along -light: from a
// fixed direction (light_distance infinite), where on a flat triangle it is the cosine
// |n . omega_r|, or from a point at light_distance from y, whose direction turns as y moves.
// Zero on the caustic.
double refraction_volume_jacobian(Vec3 n, Vec3 light, float eta, double curvature, double t,
                                  double light_distance = kInfinity);

// Internal reflections a chain of the manifold strategy may have (docs/method.md 3.12), and the
// most solutions kept for one reflection count (more are counted as dropped; none seen in tests).
inline constexpr int kMaxChainReflections = 16;
inline constexpr int kMaxChainsPerReflectionCount = 24;
// Shadow segments the chains of one medium vertex may queue: one per chain (its light segment)
// when nothing else reaches into the sphere, one per chord more otherwise; where more chains are
// found, a random run of those that fit is connected, each standing for the others.
inline constexpr size_t kChainSegmentBudget = 32;

// The refracted light entering at y, reflected specularly inside the sphere `reflections`
// times (at bounce[0], bounce[1], ... in the light's order), reaching x on its last chord.
struct SphereChain {
  int reflections = 0;
  Vec3 y;                                           // where the light refracts in
  Vec3 n;                                           // outward normal there
  std::array<Vec3, kMaxChainReflections> bounce{};  // reflection points, from y toward x
  Vec3 omega_last;      // unit propagation direction on the last chord (toward x)
  double t_last = 0;    // |x - last reflection point|
  double length = 0;    // path length inside, y to x
  double jacobian = 0;  // dV(x) / (dA(y) dt), see sphere_chain_volume_jacobian
};

struct SphereChains {
  std::array<SphereChain, kMaxChainsPerReflectionCount> chain{};
  int count = 0;
  int dropped = 0;  // solutions beyond kMaxChainsPerReflectionCount
};

// Which chains a medium vertex looks for (docs/method.md 3.12): with probability `search` it
// searches one reflection count m >= 1, drawn with P(m) = 2 / (m (m + 1)) - 2 / ((m + 1) (m + 2))
// (so P(m >= k) = 2 / (k (k + 1))): heavy-tailed enough that the long chains of a clear medium
// keep bounded weights, cheap on average (the search's cost grows with m, and the mean m is below
// 2). Counts above kMaxChainReflections are not searched (their share is measured in
// docs/method.md 3.12).
struct ChainChoice {
  int reflections = 0;       // 0: no search at this vertex
  double probability = 0.0;  // of this choice, the search probability included
  double leftover = 0.0;     // a uniform number in [0, 1) independent of the choice
};
ChainChoice choose_chain_reflections(float u, double search);
// P(m) of the choice above for m >= 1, the search probability included.
double chain_reflections_probability(int reflections, double search);
// The search probability for a sphere of this radius filled with this medium: chains carry
// light over at least one extra chord, so their share of a vertex's light falls with the
// medium's optical size; the clearest channel sets it, between 1/32 and 1/2.
double chain_search_probability(Rgb sigma_t, float radius);

// Every chain with exactly `reflections` (1 to kMaxChainReflections) internal reflections along
// which the directional light (light = unit direction toward it), refracted into the sphere at a
// point facing it, reaches x inside. The chain stays in the plane of the light direction and
// x - centre, and every reflection keeps the ray's angular momentum about the centre; that leaves
// one equation in the angle of incidence, whose roots are isolated with a bound on its
// curvature, so none is missed (docs/method.md 3.12). None when x lies on the axis.
SphereChains sphere_reflection_chains_toward_light(Vec3 centre, float radius, float eta, Vec3 light,
                                                   Vec3 x, int reflections);
// The same for a point (or spot) light at light_position outside the sphere: the chains lie in
// the plane of the centre, the light and x. None when the light is not outside.
SphereChains sphere_reflection_chains_toward_point(Vec3 centre, float radius, float eta,
                                                   Vec3 light_position, Vec3 x, int reflections);

// |dV(x) / (dA(y) dt)| for x = P_m(y) + t omega_m(y), the last chord of the chain that enters a
// sphere at y (outward normal n) and reflects `reflections` times, t measured in units of the
// radius (the value does not depend on the radius); light is the unit direction toward the light
// at y, a directional light's or that of a point light at light_distance_over_radius radii from
// y, whose direction turns as y moves. Differentiated exactly by forward-mode dual numbers; for
// no reflection it equals refraction_volume_jacobian with curvature 1 / radius.
double sphere_chain_volume_jacobian(Vec3 n, Vec3 light, float eta, int reflections,
                                    double t_over_radius,
                                    double light_distance_over_radius = kInfinity);

}  // namespace snee
