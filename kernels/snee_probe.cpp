#include "kernels/path_ops.h"
#include "kernels/snee/probe.h"
#include "kernels/snee/snee_strategies.h"
#include "kernels/stages.h"

namespace snee {

namespace {

// Counter slots of KernelCounters::snee.
enum SneeCounter : int {
  kProbes,
  kProbeMissedBoundary,  // the probe hit nothing or another surface first
  kTopToBottomCandidates,
  kBottomToTopCandidates,
  kTopToBottomFailed,
  kBottomToTopFailed,
};

// The medium vertex x_i is the path's newest vertex (x_j of its memory): medium_event already
// pushed it and advanced the event counter past it.
uint32_t vertex_event(const PathState& state, uint32_t s) {
  return state.event[s] - 1;
}

RandomBlock draw_at_vertex(const KernelContext& ctx, const PathState& state, uint32_t s,
                           RngPurpose purpose) {
  return random_block(ctx.seed, state.pixel[s], state.sample[s], vertex_event(state, s), purpose);
}

void add_candidate(const SneeCandidate& c, uint32_t slot, Rgb throughput, ShadowQueue& shadow) {
  const uint32_t first = static_cast<uint32_t>(shadow.segment_count());
  for (const ShadowSegment& seg : c.segments)
    shadow.add_segment(seg.origin, seg.direction, seg.t_max, kVisibilityOnly);
  shadow.add_connection({slot, first, static_cast<uint32_t>(c.segments.size()), -1,
                         throughput * c.contribution, Rgb(0.0f)});
}

}  // namespace

void snee_probe_and_subdivide(const KernelContext& ctx, PathState& state, StageQueues& q,
                              KernelCounters& counters) {
  RayBatch& rays = q.rays;
  rays.clear();
  for (const uint32_t s : q.probe) {
    const MediumInfo& m = ctx.media[static_cast<size_t>(state.medium[s])];
    const RandomBlock r = draw_at_vertex(ctx, state, s, RngPurpose::kSneeProbe);
    const Vec3 w = probe_direction_sample(
        ctx.snee.probe, {state.wjn_x[s], state.wjn_y[s], state.wjn_z[s]}, m.g, {r.u[0], r.u[1]});
    rays.push(state.vertex_j(s), w, 0.0f, kInfinity);
  }
  ctx.embree->intersect(rays.rays(), rays.hits(), static_cast<unsigned>(rays.size()), false);
  counters.rays[3] += rays.size();
  counters.snee[kProbes] += rays.size();

  for (size_t i = 0; i < rays.size(); ++i) {
    const uint32_t s = q.probe[i];
    const uint32_t geom = rays.geom(i);
    const int32_t medium = state.medium[s];
    // x_k must be on this medium's own dielectric boundary; anything else is a failed probe
    // (pdf 0 for both strategies; the path tracer still covers that transport).
    if (geom == kInvalidId || ctx.surfaces[geom].kind != MaterialKind::kDielectric ||
        ctx.surfaces[geom].interior_medium != medium) {
      ++counters.snee[kProbeMissedBoundary];
      continue;
    }
    const Vec3 x_k = rays.origin(i) + rays.direction(i) * rays.tfar(i);
    const Vec3 n_k = ctx.embree->normal(geom, rays.prim(i), x_k);
    if (dot(rays.direction(i), n_k) <= 0) {
      ++counters.snee[kProbeMissedBoundary];  // reached the boundary from outside: not the medium's
                                              // exit
      continue;
    }
    const MediumInfo& m = ctx.media[static_cast<size_t>(medium)];
    const SneeMedium snee_medium{m.sigma_s, m.sigma_t, m.g};
    const SneeOrigin origin{state.vertex_j(s), {state.wjn_x[s], state.wjn_y[s], state.wjn_z[s]}};
    const ExitPoint exit{x_k, n_k, ctx.surfaces[geom].dielectric};
    const Rgb beta = state.throughput(s);

    if (ctx.snee.enabled.contains(Strategy::kTopToBottom)) {
      const RandomBlock a = draw_at_vertex(ctx, state, s, RngPurpose::kSneeTopToBottom);
      const RandomBlock b = draw_at_vertex(ctx, state, s, RngPurpose::kSneeTopToBottomDistance);
      const std::array<float, kTopToBottomDimensions> u = {a.u[0], a.u[1], a.u[2], a.u[3],
                                                           b.u[0], b.u[1], b.u[2], b.u[3]};
      const SneeCandidate c =
          sample_top_to_bottom(origin, snee_medium, exit, *ctx.lights, ctx.snee, ctx.epsilon, u);
      if (c.valid && !is_black(c.contribution)) {
        add_candidate(c, s, beta, q.shadow);
        ++counters.snee[kTopToBottomCandidates];
      } else {
        ++counters.snee[kTopToBottomFailed];
      }
    }
    if (ctx.snee.enabled.contains(Strategy::kBottomToTop)) {
      const RandomBlock a = draw_at_vertex(ctx, state, s, RngPurpose::kSneeBottomToTop);
      const RandomBlock b = draw_at_vertex(ctx, state, s, RngPurpose::kSneeBottomToTopBtdf);
      const std::array<float, kBottomToTopDimensions> u = {a.u[0], a.u[1], a.u[2],
                                                           a.u[3], b.u[0], b.u[1]};
      const SneeCandidate c =
          sample_bottom_to_top(origin, snee_medium, exit, *ctx.lights, ctx.snee, ctx.epsilon, u);
      if (c.valid && !is_black(c.contribution)) {
        add_candidate(c, s, beta, q.shadow);
        ++counters.snee[kBottomToTopCandidates];
      } else {
        ++counters.snee[kBottomToTopFailed];
      }
    }
  }
  q.probe.clear();
}

}  // namespace snee
