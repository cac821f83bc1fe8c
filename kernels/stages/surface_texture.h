// Textured surface parameters at a hit (docs/method.md 4.10).
//
// A diffuse albedo with a texture is its constant factor times the texture's colour at the hit's
// texture coordinates. The colour is filtered over the footprint of a pixel at the distance the
// ray travelled to the hit (a ray cone of the camera's pixel width that restarts at each vertex:
// exact for camera rays, and narrower than a ray cone widened by the path's bounces, hence
// sharper, never blurrier, than pbrt's or Cycles' choice further down the path).
//
// A roughness texture scales the GGX alpha of a dielectric or conductor. It is read at the
// finest level, unfiltered by any footprint, so that the BSDF at a point is a function of the
// point alone: every sampling strategy that makes a path through the point sees the same
// surface, which multiple importance sampling needs (a footprint depends on the ray that
// arrived). A rough surface stays rough everywhere: alpha is held at or above kSmoothRoughness,
// so a texel of 0 is a near-mirror lobe, not a change of the surface's kind.
#pragma once

#include <algorithm>

#include "kernels/wavefront/kernel_context.h"
#include "scene/surface_uv.h"

namespace snee {

// The GGX alpha `alpha` of a surface with a roughness texture, scaled by the texture at uv.
inline float textured_alpha(const KernelContext& ctx, const SurfaceInfo& info, Uv uv, float alpha) {
  if (!(alpha >= kSmoothRoughness)) return alpha;
  const float g = ctx.textures->lookup(info.roughness_texture, uv, 0.0f).y;
  return std::max(alpha * (info.roughness_texture_squared ? g * g : g), kSmoothRoughness);
}

// The dielectric interface of surface geom at point p of primitive prim, with its roughness
// texture applied.
inline DielectricParams dielectric_at(const KernelContext& ctx, const SurfaceInfo& info,
                                      uint32_t geom, uint32_t prim, Vec3 p) {
  DielectricParams d = info.dielectric;
  if (info.roughness_texture >= 0) {
    d.alpha = textured_alpha(ctx, info, surface_uv(ctx.scene->shapes[geom], prim, p).uv, d.alpha);
  }
  return d;
}

// `info` with its textured parameters looked up at point p of triangle prim of surface geom,
// (a triangle of a mesh, or a sphere), reached after `distance` along the ray, in `textured`;
// `info` itself where it has no texture. A dielectric takes `interface`, what dielectric_at
// already gave for this hit, so its roughness is not looked up twice.
inline const SurfaceInfo& textured_surface(const KernelContext& ctx, const SurfaceInfo& info,
                                           uint32_t geom, uint32_t prim, Vec3 p, float distance,
                                           const DielectricParams& interface,
                                           SurfaceInfo& textured) {
  if (info.albedo_texture < 0 && info.roughness_texture < 0) return info;
  const SurfaceUv at = surface_uv(ctx.scene->shapes[geom], prim, p);
  textured = info;
  if (info.albedo_texture >= 0) {
    const float width = ctx.pixel_spread * distance * at.per_length;
    const Rgb colour = ctx.textures->lookup(info.albedo_texture, at.uv, width);
    textured.albedo = info.albedo * colour;
    textured.aov_albedo = textured.albedo;
  }
  if (info.kind == MaterialKind::kDielectric) {
    textured.dielectric = interface;
  } else if (info.roughness_texture >= 0) {
    textured.conductor.alpha = textured_alpha(ctx, info, at.uv, info.conductor.alpha);
  }
  return textured;
}

}  // namespace snee
