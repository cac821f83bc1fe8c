// The guided exit (docs/method.md 3.15) at the walk's vertices whose parent is a surface vertex,
// and the weight the walk's own exits from those vertices take against it.
//
// Its paths x_j -> x_k -> light are the walk's: the walk draws the direction at x_j from the
// phase function and flies past the boundary at x_k, then samples the light (U_L) or the BSDF
// (U_B) there. The guided exit draws the direction from the guide's caps instead, reaches x_k
// by construction (weighting by the transmittance) and samples the light or the BSDF alike. In
// the measure of (direction at x_j, direction at x_k) the four densities are a p_L, a p_B,
// b p_L and b p_B, a = f_p P_pass (the walk), b = rate p_guide; under the power heuristic the
// weights factor into a direction part and the exit's usual two-way part.
#pragma once

#include "kernels/wavefront/kernel_context.h"
#include "kernels/wavefront/path_state.h"
#include "kernels/wavefront/queues.h"

namespace snee {

// b / a for the walk at a surface hit p (outward geometric normal n) of shape geom, before the
// hit is pushed into the path's vertex memory: nonzero where the walk leaves its medium through
// the guide's boundary right after a medium vertex x_j whose parent is a surface vertex, and the
// guided exit could have drawn its direction there.
float walk_guide_ratio(const KernelContext& ctx, const PathState& state, uint32_t slot, Vec3 p,
                       Vec3 n, const SurfaceInfo& info, uint32_t geom);

// The ratio the walk's last exit kept for the light its refracted ray reaches next, 0 if none.
inline float guide_ratio_after_exit(const PathState& state, uint32_t slot) {
  return (state.flags[slot] & kPathAfterGuidedExit) != 0 ? state.guide_ratio[slot] : 0.0f;
}

// The walk's exit weights given ratio = b / a (0 without the guided exit: then they are the path
// tracer's power heuristic): its light sample (to a distant light or not,
// light density p_light, the BSDF's p_bsdf; a delta light or a delta BSDF as flagged), and its
// BSDF-sampled direction reaching a light that the guided exit also reaches (a distant light)
// or does not (an emitter).
float walk_light_sample_weight(float ratio, float p_light, float p_bsdf, bool delta_light,
                               bool distant);
float walk_bsdf_sample_weight(float ratio, float p_bsdf, float p_light, bool delta_bsdf,
                              bool distant);

// The guided exit's weights from the walk's density a and its own b of the step: its light
// sample, and its BSDF-sampled direction (which it follows to the distant lights only).
float guided_light_sample_weight(float walk, float guided, float p_light, float p_bsdf,
                                 bool delta_light, bool distant);
float guided_bsdf_sample_weight(float walk, float guided, float p_bsdf, float p_light,
                                bool delta_bsdf);

// Runs the guided exit at the vertex the walk just made (x_j of the path's memory, in medium m,
// its parent a surface vertex), after roulette: queues its light- and BSDF-sampled
// connections.
void connect_guided_exit(const KernelContext& ctx, const PathState& state, uint32_t slot,
                         const MediumInfo& m, ShadowQueue& shadow, KernelCounters& counters);

}  // namespace snee
