// The path suffix SNEE estimates at a medium vertex x_i (docs/method.md 1.2):
//   x_i (medium) -> x_j (medium) -> x_k (exit point on the dielectric boundary) -> light along
//   omega_o,
// described once so that every strategy's pdf, the integrand and the MIS weights are computed
// from the same data, wherever they are needed (subdivision stage or the tracer's exit events);
// suffix_weighing.h derives its geometry.
#pragma once

#include "core/math.h"
#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/physics/medium/homogeneous_medium.h"

namespace snee {

// The medium inside the object: SNEE's closed forms need a homogeneous one.
using SneeMedium = HomogeneousMedium;
static_assert(SneeMedium::kSneeEligible);

struct SneeSuffix {
  Vec3 x_i;       // vertex two steps before the exit
  Vec3 omega_in;  // unit propagation direction arriving at x_i
  Vec3 x_j;       // vertex one step before the exit
  Vec3 x_k;       // exit point on the boundary
  Vec3 n_k;       // outward geometric normal at x_k
  Vec3 ns_k;      // outward shading normal at x_k (n_k on flat surfaces; docs/method.md 4.9)
  Vec3 omega_o;   // unit direction from x_k toward the light (outside)
  SneeMedium medium;
  DielectricParams interface;
  // Solid-angle density with which the light sampler produces omega_o, including the light
  // selection probability; for a delta light, the selection probability alone.
  float light_pdf = 0;
  bool light_delta = false;
  // Whether the light is at infinity (directional, cone, environment). Bottom-to-top finds only
  // those (its outward direction is looked up, not traced), so it cannot produce the others.
  bool light_distant = true;
  // Whether the first surface hit of the ray from x_i toward x_k is x_k. Probe-based
  // strategies can only produce suffixes where it holds.
  bool v_first = false;
  // Whether x_i and x_j are medium scattering vertices (not surface vertices).
  bool x_i_medium = false;
  bool x_j_medium = false;
  // Whether the manifold strategy (docs/method.md 3.10) runs at x_j for this suffix: a smooth
  // boundary it solves (a sphere, or a closed flat-shaded mesh under a directional light), a
  // directional light or a point or spot light outside the sphere, and x_j within the walk's
  // depth limit. It finds every
  // exit point, so then it can produce the suffix whenever x_j is a medium vertex.
  bool manifold = false;
  // The probability that it runs at x_j (SneeOptions::manifold_rate when x_i is a medium vertex,
  // 1 otherwise).
  float manifold_rate = 1;
  // How fast the outward normal turns per unit length along the boundary at x_k (1 / radius).
  float boundary_curvature = 0;
  // The distance from x_k to the point or spot light the manifold strategy solved for; infinite
  // for a directional light. Its density's Jacobian depends on it.
  float manifold_light_distance = kInfinity;
};

// Whether the probe-based strategies (TB, BT) can produce the suffix at all.
inline bool snee_can_produce(const SneeSuffix& s) {
  return s.x_i_medium && s.x_j_medium && s.v_first;
}

}  // namespace snee
