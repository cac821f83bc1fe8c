#include "kernels/path_ops.h"
#include "kernels/snee/probe.h"
#include "kernels/stages.h"

namespace snee {

void snee_probe(const KernelContext& ctx, PathState& state, StageQueues& q,
                KernelCounters& counters) {
  RayBatch& rays = q.rays;
  rays.clear();
  for (const uint32_t s : q.probe) {
    const MediumInfo& m = ctx.media[static_cast<size_t>(state.medium[s])];
    // x_i is the path's newest vertex (x_j of its memory): medium_event already pushed it and
    // advanced the event counter past it, so the draw is keyed by the event before.
    const RandomBlock r = random_block(ctx.seed, state.pixel[s], state.sample[s],
                                       state.event[s] - 1, RngPurpose::kSneeProbe);
    const Vec3 w =
        probe_direction_sample(ctx.snee.probe, state.direction_in_j(s), m.g, {r.u[0], r.u[1]});
    rays.push(state.vertex_j(s), w, 0.0f, kInfinity);
  }
  ctx.embree->intersect(rays.rays(), rays.hits(), static_cast<unsigned>(rays.size()), false);
  counters.rays[3] += rays.size();
  counters.count(SneeCounter::kProbes, rays.size());

  for (size_t i = 0; i < rays.size(); ++i) {
    const uint32_t s = q.probe[i];
    const uint32_t geom = rays.geom(i);
    if (geom == kInvalidId) {
      counters.count(SneeCounter::kProbeMissed);
      continue;
    }
    // x_k must be on this medium's own dielectric boundary, reached from inside; anything else
    // is a failed probe (pdf 0 for both strategies; the path tracer still covers that
    // transport).
    const SurfaceInfo& info = ctx.surfaces[geom];
    const Vec3 x_k = rays.origin(i) + rays.direction(i) * rays.tfar(i);
    const Vec3 n_k = ctx.embree->normal(geom, rays.prim(i), x_k);
    if (info.kind != MaterialKind::kDielectric || info.interior_medium != state.medium[s] ||
        dot(rays.direction(i), n_k) <= 0) {
      counters.count(SneeCounter::kProbeOtherSurface);
      continue;
    }
    q.subdivide.push(s, geom, x_k, n_k);
  }
  q.probe.clear();
}

}  // namespace snee
