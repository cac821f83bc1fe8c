// The path tracer's exit events seen from SNEE (docs/snee.md 3.6): when the random walk leaves
// a medium through a dielectric boundary right after two medium vertices x_i -> x_j, the last
// two segments are themselves one of four strategies for the suffix x_i -> x_j -> x_k -> light.
// Their light contributions then need the four-way MIS weight, whose SNEE pdfs depend on
// V_first(x_i, x_k); that visibility becomes a `selector` segment of the connection.
#pragma once

#include "kernels/kernel_context.h"
#include "kernels/path_state.h"
#include "kernels/queues.h"

namespace snee {

struct ExitEvent {
  bool snee_possible = false;  // the four-way weights apply
  // Under the straight-line approximation, medium vertices already collected direct light
  // through the boundary; the exit's own light samples would count it twice.
  bool light_handled_elsewhere = false;
  Vec3 x_i, omega_in, x_j, x_k, n_k;
  int32_t medium = -1;
  DielectricParams interface;
  // V_first(x_i, x_k) as a segment from x_i toward x_k that stops just short of it.
  Vec3 first_hit_direction;
  float first_hit_tmax = 0;
};

// Called at a surface vertex before the path's vertex memory is shifted.
ExitEvent make_exit_event(const KernelContext& ctx, const PathState& state, uint32_t slot, Vec3 p,
                          Vec3 n, const SurfaceInfo& info);

struct ExitWeights {
  float if_first_hit;      // V_first(x_i, x_k) = 1: four-way weight
  float if_not_first_hit;  // SNEE cannot produce the path: the tracer's two-way weight
};

// U_L: a light sample at the exit point (light pdf includes selection; `delta` for delta lights).
ExitWeights exit_light_sample_weights(const KernelContext& ctx, const ExitEvent& exit, Vec3 omega_o,
                                      float light_pdf, bool delta);

// U_B: the BSDF-sampled exit direction omega_o may escape to a distant light.
// Turns that into a connection now (gated by the escape, selected by V_first) and marks the
// path so shade_escaped does not add the same light again.
void defer_bsdf_exit(const KernelContext& ctx, PathState& state, uint32_t slot,
                     const ExitEvent& exit, Vec3 omega_o, ShadowQueue& shadow);

}  // namespace snee
