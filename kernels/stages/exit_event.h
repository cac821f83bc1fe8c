// The path tracer's exit events seen from SNEE (docs/method.md 3.6): when the random walk leaves
// a medium through a dielectric boundary right after two medium vertices x_i -> x_j, the last
// two segments are themselves one of four strategies for the suffix x_i -> x_j -> x_k -> light.
// Their light contributions then need the four-way MIS weight, whose SNEE pdfs depend on
// V_first(x_i, x_k); that visibility becomes a `selector` segment of the connection.
//
// U_L (a light sample at x_k) is weighted on the spot. U_B (the BSDF-sampled exit direction
// reaching a light) is only known when the continued ray escapes to a distant light or hits an
// emitter, after the path's vertex memory has moved on, so the exit remembers x_i (its incoming
// direction) and the exit surface in the path state until then.
#pragma once

#include "kernels/wavefront/kernel_context.h"
#include "kernels/wavefront/path_state.h"
#include "kernels/wavefront/queues.h"

namespace snee {

struct ExitEvent {
  bool snee_possible = false;  // the four-way weights apply
  // Under the straight-line approximation, medium vertices already collected direct light
  // through the boundary; the exit's own light samples would count it twice.
  bool light_handled_elsewhere = false;
  Vec3 x_i, omega_in, x_j, x_k, n_k, ns_k;  // ns_k: the shading normal at x_k
  DielectricParams interface;               // at x_k, its roughness texture applied
  uint32_t geom = 0;                        // exit surface (its interior medium)
};

// Called at a surface vertex before the path's vertex memory is shifted, with the hit's
// geometric and shading normals n and ns and its surface `info` (textured).
ExitEvent make_exit_event(const KernelContext& ctx, const PathState& state, uint32_t slot, Vec3 p,
                          Vec3 n, Vec3 ns, const SurfaceInfo& info, uint32_t geom);

// U_L: a light sample at the exit point toward omega_o. light_pdf: solid angle at x_k, light
// selection included (the selection probability alone for delta lights); distant: the light
// is at infinity. Queues the shadow connection of `segment` (to the light) with the four-way
// weights.
void connect_exit_light_sample(const KernelContext& ctx, uint32_t slot, const ExitEvent& exit,
                               Vec3 omega_o, float light_pdf, bool delta, bool distant,
                               Rgb unweighted, uint32_t segment, ShadowQueue& shadow);

// U_B: the exit sampled a transmission out of the medium; marks the path and remembers the
// suffix so that the light it reaches next is weighted by connect_exit_emission.
void remember_exit(PathState& state, uint32_t slot, const ExitEvent& exit);

// U_B, later: the ray continued from a remembered exit and reached emission le along omega_o
// (an escaped ray: distant lights; an emitter hit: light_pdf is its area pdf seen from x_k).
// Queues a connection that adds throughput * le with the four-way weight selected by V_first.
void connect_exit_emission(const KernelContext& ctx, const PathState& state, uint32_t slot,
                           Vec3 omega_o, Rgb le, float light_pdf, bool distant,
                           ShadowQueue& shadow);

// The manifold strategy (docs/method.md 3.10) at the medium vertex the walk just made (x_j of
// the path's memory, in medium m), before its event counter moves on: a light sample, and for a
// directional light every exit point of m's smooth sphere through which the refracted light
// reaches x_j, each queued as a connection gated by x_j -> exit and exit -> light, weighted
// against top-to-bottom at the previous vertex (a V_first selector) when that was a medium
// vertex. Counts the vertices it cannot serve (a mesh boundary) in the statistics.
void connect_manifold(const KernelContext& ctx, const PathState& state, uint32_t slot,
                      const MediumInfo& m, ShadowQueue& shadow, KernelCounters& counters);

}  // namespace snee
