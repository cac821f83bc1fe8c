// Denoiser AOVs of one camera path (docs/output-images.md): the albedo, shading normal and depth
// of its first non-specular interaction. A path starts with its chain open (kPathAovOpen, only
// when the render records AOVs); every segment it travels while open adds to aov_depth, a smooth
// (delta) dielectric keeps it open, and the first diffuse or rough surface or medium scattering
// vertex closes it with that vertex's values. Nothing here draws a random number or touches
// what the beauty image reads: the chain follows the branch the path itself sampled, so the
// AOVs average the reflect/refract choice with the path's own Fresnel probabilities.
#pragma once

#include <array>
#include <cstddef>

#include "kernels/wavefront/path_state.h"

namespace snee {

// Floats per sample in an AOV buffer: albedo RGB, normal XYZ, depth.
inline constexpr size_t kAovFloats = 7;

inline bool aov_chain_open(const PathState& state, uint32_t s) {
  return (state.flags[s] & kPathAovOpen) != 0;
}

// The open chain travelled another t along its ray.
inline void extend_aov_chain(PathState& state, uint32_t s, float t) {
  if (aov_chain_open(state, s)) state.aov_depth[s] += t;
}

// The chain ends at a non-specular vertex reached after t more along the ray.
inline void close_aov_chain(PathState& state, uint32_t s, float t, Rgb albedo, Vec3 normal) {
  if (!aov_chain_open(state, s)) return;
  state.flags[s] &= ~kPathAovOpen;
  state.aov_depth[s] += t;
  state.aov_albedo_r[s] = albedo.x;
  state.aov_albedo_g[s] = albedo.y;
  state.aov_albedo_b[s] = albedo.z;
  state.aov_normal_x[s] = normal.x;
  state.aov_normal_y[s] = normal.y;
  state.aov_normal_z[s] = normal.z;
}

// The sample's AOVs as they go to the film: zero where the chain never closed (the path
// escaped, or ended on its depth limit, while every vertex so far was specular).
inline std::array<float, kAovFloats> aov_sample(const PathState& state, uint32_t s) {
  if (aov_chain_open(state, s)) return {};
  return {state.aov_albedo_r[s], state.aov_albedo_g[s], state.aov_albedo_b[s],
          state.aov_normal_x[s], state.aov_normal_y[s], state.aov_normal_z[s],
          state.aov_depth[s]};
}

}  // namespace snee
