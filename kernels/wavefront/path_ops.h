// Small per-slot helpers shared by several stage kernels.
#pragma once

#include "kernels/physics/rng.h"
#include "kernels/wavefront/kernel_context.h"
#include "kernels/wavefront/path_state.h"

namespace snee {

inline RandomBlock draw(const KernelContext& ctx, const PathState& state, uint32_t slot,
                        RngPurpose purpose) {
  return random_block(ctx.seed, state.pixel[slot], state.sample[slot], state.event[slot], purpose);
}

inline float power_heuristic(float f, float g) {
  const float f2 = f * f, g2 = g * g;
  return f2 + g2 > 0 ? f2 / (f2 + g2) : 0.0f;
}

// Origin for a ray leaving surface point p (outward normal n) toward direction w.
inline Vec3 offset_origin(Vec3 p, Vec3 n, Vec3 w, float epsilon) {
  return dot(w, n) >= 0 ? p + n * epsilon : p - n * epsilon;
}

// Russian roulette on the radiance-scale-free throughput, from the fourth scattering event on,
// with u the first number of the event's kRussianRoulette block (drawn by the stage's batched
// pass whether or not the roulette runs). Returns false if the path is terminated; otherwise
// rescales the throughput.
inline bool survive_russian_roulette(PathState& state, uint32_t slot, float u) {
  if (state.depth[slot] < 4) return true;
  const Rgb beta = state.throughput(slot);
  const float q = std::min(0.95f, max_component(beta) * state.eta_scale[slot]);
  if (q >= 0.95f) return true;
  if (!(u < q)) return false;
  state.set_throughput(slot, beta / q);
  return true;
}

// Medium entered by a ray crossing the boundary of shape `geom` in direction d.
inline int32_t medium_after_crossing(const KernelContext& ctx, uint32_t geom, Vec3 d, Vec3 n) {
  return dot(d, n) < 0 ? ctx.surfaces[geom].interior_medium : -1;
}

}  // namespace snee
