#include "kernels/stages/stages.h"

namespace snee {

void extend(const KernelContext& ctx, PathState& state, StageQueues& q, KernelCounters& counters) {
  RayBatch& rays = q.rays;
  rays.clear();
  bool all_camera = true;
  for (const uint32_t s : q.extend) {
    rays.push(state.origin(s), state.direction(s), 0.0f, kInfinity);
    all_camera = all_camera && state.event[s] == 0;
  }
  ctx.embree->intersect(rays.rays(), rays.hits(), static_cast<unsigned>(rays.size()), all_camera);
  // Camera rays were counted when generated; the rest are extension rays.
  size_t camera = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const uint32_t s = q.extend[i];
    if (state.event[s] == 0) ++camera;
    const bool hit = rays.geom(i) != kInvalidId;
    state.hit_t[s] = hit ? rays.tfar(i) : kInfinity;
    state.hit_geom[s] = rays.geom(i);
    state.hit_prim[s] = rays.prim(i);
    if (state.medium[s] >= 0) {
      q.medium.push(s);
    } else if (hit) {
      q.surface.push(s);
    } else {
      q.escaped.push(s);
    }
  }
  counters.count_rays(RayKind::kExtension, rays.size() - camera);
  q.extend.clear();
}

}  // namespace snee
