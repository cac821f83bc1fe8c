// Shading normals at a surface vertex (docs/method.md 4.9). The BSDF is evaluated and sampled in
// the frame of the shading normal ns, with the shading cosine |wi . ns| (all transport here is
// radiance: paths start at the camera), while the geometric normal ng decides on which side a
// direction lies, hence which medium it enters and whether it reflects or transmits. A
// direction pair is kept only where the two normals agree on the side of both directions;
// anything else would let light through the surface (or reflect it from below), so it gets
// value zero.
#pragma once

#include "kernels/wavefront/kernel_context.h"
#include "scene/vertex_normals.h"

namespace snee {

// Whether w lies on the same side of the shading normal as of the geometric one.
inline bool same_side(Vec3 w, Vec3 ng, Vec3 ns) {
  const float g = dot(w, ng), s = dot(w, ns);
  return (g > 0 && s > 0) || (g < 0 && s < 0);
}

// The side rule: the camera-side direction wo and the light-side direction wi each lie on the
// same side of ns as of ng, so the lobe the BSDF takes in the shading frame (reflection when wo
// and wi share a side, transmission when they do not) is the one the geometry allows.
inline bool shading_sides_agree(Vec3 wo, Vec3 wi, Vec3 ng, Vec3 ns) {
  return same_side(wo, ng, ns) && same_side(wi, ng, ns);
}

// The shading normal of surface `geom` at point p of primitive prim, outward, turned to the side
// of the outward geometric normal ng; ng itself on flat surfaces.
inline Vec3 shading_normal(const KernelContext& ctx, uint32_t geom, uint32_t prim, Vec3 p,
                           Vec3 ng) {
  if (!ctx.surfaces[geom].smooth_shading) return ng;
  return interpolated_normal(ctx.scene->shapes[geom].mesh, prim, p, ng);
}

}  // namespace snee
