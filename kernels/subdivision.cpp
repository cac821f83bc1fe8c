#include <algorithm>

#include "kernels/batched_pass.h"
#include "kernels/path_ops.h"
#include "kernels/simd/philox_batch.h"
#include "kernels/simd/slot_chunk.h"
#include "kernels/snee/snee_strategies.h"
#include "kernels/stages.h"

namespace snee {

namespace {

constexpr RngPurpose kBlockPurposes[SubdivisionRandoms::kBlocks] = {
    RngPurpose::kSneeTopToBottom, RngPurpose::kSneeTopToBottomDistance,
    RngPurpose::kSneeBottomToTop, RngPurpose::kSneeBottomToTopBtdf};

// The Philox blocks of the exits at queue positions [k, k + count): the four blocks of a chunk
// are independent, so their rounds overlap in the pipeline instead of running one exit's
// dependency chain at a time. Bit for bit the scalar random_block.
void draw_chunk(const KernelContext& ctx, const PathState& state, const simd::SlotChunk& chunk,
                bool bottom_to_top, SubdivisionRandoms& out, size_t k) {
  // Keyed by the event of the medium vertex x_i, as the probe was (snee_probe.cpp).
  const simd::UintBatch pixel = chunk.load(state.pixel), sample = chunk.load(state.sample);
  const simd::UintBatch event = chunk.load(state.event) - simd::UintBatch(1u);
  for (int b = 0; b < (bottom_to_top ? 4 : 2); ++b) {
    const simd::RandomBlockBatch r =
        simd::random_block(ctx.seed, pixel, sample, event, kBlockPurposes[b], chunk.count());
    for (int j = 0; j < 4; ++j) r.u[j].store_aligned(out.u[4 * b + j].data() + k);
  }
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
  const bool top_to_bottom = ctx.snee.enabled.contains(Strategy::kTopToBottom);
  // Bottom-to-top finds only lights seen by escaped rays; without any it cannot succeed.
  const bool bottom_to_top =
      ctx.snee.enabled.contains(Strategy::kBottomToTop) && ctx.lights->has_escaped_lights();
  SubdivisionRandoms& randoms = q.snee_randoms;
  for_each_chunk(exits.slots(), exits.size(), BatchedKernel::kSubdivisionDraws, counters,
                 [&](const simd::SlotChunk& chunk, size_t k) {
                   draw_chunk(ctx, state, chunk, bottom_to_top, randoms, k);
                 });
  const auto u = [&](int n, size_t i) { return randoms.u[n][i]; };
  for (size_t i = 0; i < exits.size(); ++i) {
    const uint32_t s = exits.slot(i);
    const MediumInfo& m = ctx.media[static_cast<size_t>(state.medium[s])];
    const SneeMedium medium{m.sigma_s, m.sigma_t, m.g};
    const SneeOrigin origin{state.vertex_j(s), state.direction_in_j(s)};
    const ExitPoint exit{exits.x_k(i), exits.n_k(i), ctx.surfaces[exits.geom(i)].dielectric};
    const Rgb beta = state.throughput(s);

    if (top_to_bottom) {
      const std::array<float, kTopToBottomDimensions> tb = {u(0, i), u(1, i), u(2, i), u(3, i),
                                                            u(4, i), u(5, i), u(6, i), u(7, i)};
      const SneeCandidate c =
          sample_top_to_bottom(origin, medium, exit, *ctx.lights, ctx.snee, ctx.epsilon, tb);
      queue_candidate(c, Strategy::kTopToBottom, s, beta, q.shadow, counters);
    }
    if (bottom_to_top) {
      const std::array<float, kBottomToTopDimensions> bt = {u(8, i),  u(9, i),  u(10, i),
                                                            u(11, i), u(12, i), u(13, i)};
      const SneeCandidate c =
          sample_bottom_to_top(origin, medium, exit, *ctx.lights, ctx.snee, ctx.epsilon, bt);
      queue_candidate(c, Strategy::kBottomToTop, s, beta, q.shadow, counters);
    }
  }
  q.subdivide.clear();
}

}  // namespace snee
