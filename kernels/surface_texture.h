// Textured surface parameters at a hit (docs/method.md 4.10): a diffuse albedo with a texture is
// its constant factor times the texture's colour at the hit's texture coordinates. The texture
// is filtered over the footprint of a pixel at the distance the ray travelled to the hit (a ray
// cone of the camera's pixel width that restarts at each vertex: exact for camera rays, and
// narrower than a ray cone widened by the path's bounces, hence sharper, never blurrier, than
// pbrt's or Cycles' choice further down the path).
#pragma once

#include "kernels/kernel_context.h"
#include "scene/surface_uv.h"

namespace snee {

// `info` with its textured parameters looked up at point p of triangle prim of surface geom,
// (a triangle of a mesh, or a sphere), reached after `distance` along the ray, in `textured`;
// `info` itself where it has no texture.
inline const SurfaceInfo& textured_surface(const KernelContext& ctx, const SurfaceInfo& info,
                                           uint32_t geom, uint32_t prim, Vec3 p, float distance,
                                           SurfaceInfo& textured) {
  if (info.albedo_texture < 0) return info;
  const SurfaceUv at = surface_uv(ctx.scene->shapes[geom], prim, p);
  const float width = ctx.pixel_spread * distance * at.per_length;
  const Rgb colour = ctx.textures->lookup(info.albedo_texture, at.uv, width);
  textured = info;
  textured.albedo = info.albedo * colour;
  textured.aov_albedo = textured.albedo;
  return textured;
}

}  // namespace snee
