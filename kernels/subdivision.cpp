#include "kernels/path_ops.h"
#include "kernels/snee/snee_strategies.h"
#include "kernels/stages.h"

namespace snee {

namespace {

RandomBlock draw_at_vertex(const KernelContext& ctx, const PathState& state, uint32_t s,
                           RngPurpose purpose) {
  // Keyed by the event of the medium vertex x_i, as the probe was (snee_probe.cpp).
  return random_block(ctx.seed, state.pixel[s], state.sample[s], state.event[s] - 1, purpose);
}

void count_failure(SneeFailure why, Strategy st, KernelCounters& counters) {
  const bool tb = st == Strategy::kTopToBottom;
  switch (why) {
    case SneeFailure::kNone:
      break;
    case SneeFailure::kNoLight:
      counters.count(tb ? SneeCounter::kTopToBottomNoLight : SneeCounter::kBottomToTopNoLight);
      break;
    case SneeFailure::kRefraction:
      counters.count(tb ? SneeCounter::kTopToBottomRefraction
                        : SneeCounter::kBottomToTopRefraction);
      break;
    case SneeFailure::kPlacement:
      counters.count(SneeCounter::kBottomToTopPlacement);
      break;
    case SneeFailure::kZero:
      counters.count(tb ? SneeCounter::kTopToBottomZero : SneeCounter::kBottomToTopZero);
      break;
  }
}

void queue_candidate(const SneeCandidate& c, Strategy st, uint32_t slot, Rgb throughput,
                     ShadowQueue& shadow, KernelCounters& counters) {
  if (!c.valid) {
    count_failure(c.failure, st, counters);
    return;
  }
  const bool tb = st == Strategy::kTopToBottom;
  const uint32_t first = static_cast<uint32_t>(shadow.segment_count());
  for (const ShadowSegment& seg : c.segments)
    shadow.add_segment(seg.origin, seg.direction, seg.t_max, kVisibilityOnly);
  shadow.add_connection({tb ? ConnectionKind::kTopToBottom : ConnectionKind::kBottomToTop, slot,
                         first, static_cast<uint32_t>(c.segments.size()), -1,
                         throughput * c.contribution, Rgb(0.0f)});
  counters.count(tb ? SneeCounter::kTopToBottomConnections : SneeCounter::kBottomToTopConnections);
  counters.count(SneeCounter::kConnectionRays, c.segments.size());
}

}  // namespace

void subdivision(const KernelContext& ctx, PathState& state, StageQueues& q,
                 KernelCounters& counters) {
  const ExitPointQueue& exits = q.subdivide;
  for (size_t i = 0; i < exits.size(); ++i) {
    const uint32_t s = exits.slot(i);
    const MediumInfo& m = ctx.media[static_cast<size_t>(state.medium[s])];
    const SneeMedium medium{m.sigma_s, m.sigma_t, m.g};
    const SneeOrigin origin{state.vertex_j(s), state.direction_in_j(s)};
    const ExitPoint exit{exits.x_k(i), exits.n_k(i), ctx.surfaces[exits.geom(i)].dielectric};
    const Rgb beta = state.throughput(s);

    if (ctx.snee.enabled.contains(Strategy::kTopToBottom)) {
      const RandomBlock a = draw_at_vertex(ctx, state, s, RngPurpose::kSneeTopToBottom);
      const RandomBlock b = draw_at_vertex(ctx, state, s, RngPurpose::kSneeTopToBottomDistance);
      const std::array<float, kTopToBottomDimensions> u = {a.u[0], a.u[1], a.u[2], a.u[3],
                                                           b.u[0], b.u[1], b.u[2], b.u[3]};
      const SneeCandidate c =
          sample_top_to_bottom(origin, medium, exit, *ctx.lights, ctx.snee, ctx.epsilon, u);
      queue_candidate(c, Strategy::kTopToBottom, s, beta, q.shadow, counters);
    }
    // Bottom-to-top finds only lights seen by escaped rays; without any it cannot succeed.
    if (ctx.snee.enabled.contains(Strategy::kBottomToTop) && ctx.lights->has_escaped_lights()) {
      const RandomBlock a = draw_at_vertex(ctx, state, s, RngPurpose::kSneeBottomToTop);
      const RandomBlock b = draw_at_vertex(ctx, state, s, RngPurpose::kSneeBottomToTopBtdf);
      const std::array<float, kBottomToTopDimensions> u = {a.u[0], a.u[1], a.u[2],
                                                           a.u[3], b.u[0], b.u[1]};
      const SneeCandidate c =
          sample_bottom_to_top(origin, medium, exit, *ctx.lights, ctx.snee, ctx.epsilon, u);
      queue_candidate(c, Strategy::kBottomToTop, s, beta, q.shadow, counters);
    }
  }
  q.subdivide.clear();
}

}  // namespace snee
