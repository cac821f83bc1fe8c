// The guided exit (docs/method.md 3.15): at a medium vertex whose parent is a surface vertex
// (the first scattering after entering, or the first after an internal reflection), none of
// SNEE's probe-based strategies can make the path that leaves the medium next, and under a small
// light behind a glossy boundary the walk's phase-sampled direction rarely leaves along the few
// degrees that refract toward it. The guide aims there: for each small light (the probe's
// targets) it finds every point of the boundary whose refraction of the light's central ray
// passes through the vertex (manifold_sphere.h on a sphere, manifold_mesh.h's facet beams on a
// closed flat-shaded mesh), and the strategy draws the direction to the exit point uniformly in
// a cap around one of them. The cap's density is evaluable for any
// direction, so the walk's own exit events can weigh themselves against it.
#pragma once

#include <array>

#include "kernels/physics/sampling.h"
#include "kernels/physics/snee/manifold_mesh.h"
#include "kernels/physics/snee/manifold_sphere.h"
#include "kernels/physics/snee/probe_targets.h"

namespace snee {

inline constexpr int kMaxExitGuideAxes = kMaxProbeTargets * kMaxMeshExits;
static_assert(kMaxMeshExits >= kMaxSphereExits);

// The cap axes at one vertex, each with the probability of being chosen.
struct ExitGuide {
  std::array<Vec3, kMaxExitGuideAxes> axis{};
  std::array<float, kMaxExitGuideAxes> probability{};
  int count = 0;
};

// Adds a target's axes: the directions from x toward its exit points (the y of each of the
// `exits`, SphereExits or MeshExits), each chosen with the target's share over their count.
template <class Exits>
void add_exit_guide_axes(ExitGuide& guide, float share, Vec3 x, const Exits& exits) {
  for (int e = 0; e < exits.count; ++e) {
    const Vec3 toward = exits.exit[static_cast<size_t>(e)].y - x;
    const float distance = length(toward);
    if (!(distance > 0) || guide.count == kMaxExitGuideAxes) continue;
    const size_t k = static_cast<size_t>(guide.count++);
    guide.axis[k] = toward / distance;
    guide.probability[k] = share / static_cast<float>(exits.count);
  }
}

// The axes at x inside the sphere (centre, radius, relative index eta = inside / outside): a
// target is chosen with its share (probe_targets.h), then one of its solutions uniformly; a
// target without solutions leaves its share unused (the strategy then draws nothing).
ExitGuide exit_guide(const ProbeTargets& targets, Vec3 centre, float radius, float eta, Vec3 x);

// The cosine of a cap's half-angle, in degrees.
float exit_guide_cap_cosine(float degrees);

// Density (solid angle) of drawing w, the strategy's rate left out.
float exit_guide_pdf(const ExitGuide& guide, float cap_cosine, Vec3 w);

// Draws a direction: u_axis picks the axis, u the point of its cap. False when u_axis falls on
// the unused share.
bool exit_guide_sample(const ExitGuide& guide, float cap_cosine, float u_axis, Vec2 u, Vec3* w);

// Where the ray from x (inside) along unit w leaves the sphere.
float sphere_exit_distance(Vec3 centre, float radius, Vec3 x, Vec3 w);

}  // namespace snee
