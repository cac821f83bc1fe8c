#include <algorithm>

#include "kernels/physics/snee/probe.h"
#include "kernels/simd/frame_batch.h"
#include "kernels/simd/hg_sample_batch.h"
#include "kernels/simd/philox_batch.h"
#include "kernels/simd/sampling_batch.h"
#include "kernels/stages/shading_normal.h"
#include "kernels/stages/stages.h"
#include "kernels/stages/surface_texture.h"
#include "kernels/wavefront/batched_pass.h"
#include "kernels/wavefront/medium_lanes.h"
#include "kernels/wavefront/path_ops.h"

namespace snee {

namespace {

struct ProbeDraws {
  simd::Vec3Batch direction;
  simd::FloatBatch u_rate;  // below SneeOptions::probe_rate: the probe runs
};

// probe_direction_sample (kernels/physics/snee/probe.h) for one chunk of the probe queue.
ProbeDraws probe_draws(const KernelContext& ctx, const PathState& state,
                       const simd::SlotChunk& chunk) {
  // x_i is the path's newest vertex (x_j of its memory): medium_event already pushed it and
  // advanced the event counter past it, so the draw is keyed by the event before.
  const simd::RandomBlockBatch r = simd::random_block(
      ctx.seed, chunk.load(state.pixel), chunk.load(state.sample),
      chunk.load(state.event) - simd::UintBatch(1u), RngPurpose::kSneeProbe, chunk.count());
  const simd::Vec3Batch x_i{chunk.load(state.xj_x), chunk.load(state.xj_y), chunk.load(state.xj_z)};
  const simd::Vec3Batch w_in{chunk.load(state.wjn_x), chunk.load(state.wjn_y),
                             chunk.load(state.wjn_z)};
  const simd::FloatBatch g = ctx.snee.probe == ProbeDirections::kPhaseFunction
                                 ? load_media(ctx, state, chunk).g
                                 : simd::FloatBatch(0.0f);
  return {probe_direction_sample(ctx.snee, x_i, w_in, g, r.u[0], r.u[1], r.u[2]), r.u[3]};
}

}  // namespace

void snee_probe(const KernelContext& ctx, PathState& state, StageQueues& q,
                KernelCounters& counters) {
  RayBatch& rays = q.rays;
  rays.clear();
  // The probe runs at a vertex with probability probe_rate (its density carries the rate,
  // probe.h); the slots it skips leave the queue, which then lists the rays' slots in order.
  for_each_chunk(q.probe.begin(), q.probe.size(), BatchedKernel::kProbeDirections, counters,
                 [&](const simd::SlotChunk& chunk, size_t k) {
                   const ProbeDraws draws = probe_draws(ctx, state, chunk);
                   alignas(64) float wx[simd::kLanes], wy[simd::kLanes], wz[simd::kLanes],
                       u[simd::kLanes];
                   draws.direction.x.store_aligned(wx);
                   draws.direction.y.store_aligned(wy);
                   draws.direction.z.store_aligned(wz);
                   draws.u_rate.store_aligned(u);
                   for (size_t l = 0; l < chunk.count(); ++l) {
                     const uint32_t s = q.probe[k + l];
                     if (!(u[l] < ctx.snee.probe_rate)) continue;
                     q.probe.overwrite(rays.size(), s);
                     rays.push(state.vertex_j(s), {wx[l], wy[l], wz[l]}, 0.0f, kInfinity);
                   }
                 });
  counters.count(SneeCounter::kProbesSkipped, q.probe.size() - rays.size());
  q.probe.truncate(rays.size());
  ctx.embree->intersect(rays.rays(), rays.hits(), static_cast<unsigned>(rays.size()), false);
  counters.count_rays(RayKind::kProbe, rays.size());
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
    // transport). The exit takes the boundary's shading normal and textured roughness at x_k
    // (docs/method.md 4.9, 4.10).
    const SurfaceInfo& info = ctx.surfaces[geom];
    const auto [x_k, n_k] = ctx.embree->surface_point(
        geom, rays.prim(i), rays.origin(i) + rays.direction(i) * rays.tfar(i));
    if (info.kind != MaterialKind::kDielectric || info.interior_medium != state.medium[s] ||
        dot(rays.direction(i), n_k) <= 0) {
      counters.count(SneeCounter::kProbeOtherSurface);
      continue;
    }
    q.subdivide.push(s, geom, x_k, n_k, shading_normal(ctx, geom, rays.prim(i), x_k, n_k),
                     dielectric_at(ctx, info, geom, rays.prim(i), x_k).alpha);
  }
  q.probe.clear();
}

}  // namespace snee
