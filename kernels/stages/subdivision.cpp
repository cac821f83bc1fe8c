#include <algorithm>
#include <cmath>

#include "kernels/physics/snee/snee_strategies.h"
#include "kernels/physics/snee/subdivision_vertices.h"
#include "kernels/simd/philox_batch.h"
#include "kernels/simd/slot_chunk.h"
#include "kernels/simd/snee_weights_batch.h"
#include "kernels/stages/stages.h"
#include "kernels/wavefront/batched_pass.h"
#include "kernels/wavefront/medium_lanes.h"
#include "kernels/wavefront/path_ops.h"

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

// What both strategies' batched parts read at the exits of one chunk.
struct ChunkExits {
  simd::Vec3Batch x_i, omega_in, x_k, n_k, ns_k;
  MediumLanes medium;
  simd::DielectricLanes interface;
};

ChunkExits load_exits(const KernelContext& ctx, const PathState& state, const ExitPointQueue& exits,
                      const simd::SlotChunk& chunk, size_t k) {
  using simd::FloatBatch;
  const size_t count = chunk.count();
  const auto exit_vector = [&](const float* (ExitPointQueue::*component)(int) const) {
    return simd::Vec3Batch{simd::load_padded((exits.*component)(0) + k, count),
                           simd::load_padded((exits.*component)(1) + k, count),
                           simd::load_padded((exits.*component)(2) + k, count)};
  };
  alignas(64) float eta[simd::kLanes], alpha[simd::kLanes];
  for (size_t l = 0; l < simd::kLanes; ++l) {
    const size_t i = k + (l < count ? l : 0);
    eta[l] = ctx.surfaces[exits.geom(i)].dielectric.eta;
    alpha[l] = exits.alpha(i);
  }
  // The path's latest vertex (x_j of the path state) is SNEE's x_i, as in the per-exit pass.
  return {{chunk.load(state.xj_x), chunk.load(state.xj_y), chunk.load(state.xj_z)},
          {chunk.load(state.wjn_x), chunk.load(state.wjn_y), chunk.load(state.wjn_z)},
          exit_vector(&ExitPointQueue::x_k_component),
          exit_vector(&ExitPointQueue::n_k_component),
          exit_vector(&ExitPointQueue::ns_k_component),
          load_media(ctx, state, chunk),
          {FloatBatch::load_aligned(eta), FloatBatch::load_aligned(alpha)}};
}

// The status of an exit in StrategyResults, from the batched part's success flags.
void store_status(simd::BoolBatch first, simd::BoolBatch second, uint32_t first_failure,
                  uint32_t second_failure, uint32_t* out) {
  using simd::FloatBatch;
  const FloatBatch status = xsimd::select(
      first, xsimd::select(second, FloatBatch(kSneeSampled), FloatBatch(second_failure)),
      FloatBatch(first_failure));
  xsimd::bitwise_cast<simd::UintBatch>(xsimd::batch_cast<int32_t>(status)).store_aligned(out);
}

// Top-to-bottom after the light sample, for the exits at queue positions [k, k + count).
void sample_top_to_bottom_chunk(const KernelContext& ctx, const ChunkExits& e,
                                const SubdivisionScratch& scratch, StrategyResults& out,
                                size_t count, size_t k) {
  using simd::FloatBatch;
  const TopToBottomLights& lights = scratch.lights;
  // The light arrays are written per exit, so a short chunk's padding lanes repeat its first.
  const auto at = [&](const AlignedArray<float>& a) {
    return simd::load_padded(a.data() + k, count);
  };
  std::array<FloatBatch, kTopToBottomDimensions> u;
  for (int n = 0; n < kTopToBottomDimensions; ++n)
    u[n] = FloatBatch::load_aligned(scratch.randoms.top_to_bottom(n).data() + k);
  const TopToBottomVertex<FloatBatch> tb =
      top_to_bottom_vertex<FloatBatch>({e.x_i,
                                        e.omega_in,
                                        e.x_k,
                                        e.n_k,
                                        e.ns_k,
                                        e.medium.g,
                                        e.medium.sigma_t,
                                        e.interface,
                                        {at(lights.wx), at(lights.wy), at(lights.wz)},
                                        at(lights.pdf),
                                        at(lights.delta) != FloatBatch(0.0f)},
                                       ctx.snee, u);
  simd::store_aligned(tb.x_j, out.x.data() + k, out.y.data() + k, out.z.data() + k);
  tb.pdf.store_aligned(out.pdf.data() + k);
  store_status(tb.refracted, tb.distanced, kSneeNotRefracted, kSneeNoDistance,
               out.status.data() + k);
}

// Bottom-to-top up to the light lookup, for the exits at queue positions [k, k + count).
void sample_bottom_to_top_chunk(const KernelContext& ctx, const ChunkExits& e,
                                const SubdivisionRandoms& randoms, StrategyResults& out, size_t k) {
  std::array<simd::FloatBatch, kBottomToTopDimensions> u;
  for (int n = 0; n < kBottomToTopDimensions; ++n)
    u[n] = simd::FloatBatch::load_aligned(randoms.bottom_to_top(n).data() + k);
  const BottomToTopVertex<simd::FloatBatch> bt = bottom_to_top_vertex<simd::FloatBatch>(
      {e.x_i, e.omega_in, e.x_k, e.n_k, e.ns_k, e.medium.g, e.interface}, ctx.snee, u);
  simd::store_aligned(bt.x_j, out.x.data() + k, out.y.data() + k, out.z.data() + k);
  simd::store_aligned(bt.omega_o, out.wx.data() + k, out.wy.data() + k, out.wz.data() + k);
  bt.pdf.store_aligned(out.pdf.data() + k);
  store_status(bt.placed, bt.refracted, kSneeNotPlaced, kSneeNotRefracted, out.status.data() + k);
}

// Top-to-bottom's light samples, one exit at a time (the light table branches on the kind of
// light), with whether each direction is usable: a light above x_k's horizon.
void sample_lights(const KernelContext& ctx, const ExitPointQueue& exits,
                   const SubdivisionRandoms& randoms, TopToBottomLights& out) {
  using R = TopToBottomRandoms;
  const float* selection = randoms.top_to_bottom(R::kLightSelection).data();
  const float* point0 = randoms.top_to_bottom(R::kLightPoint).data();
  const float* point1 = randoms.top_to_bottom(R::kLightPoint + 1).data();
  for (size_t i = 0; i < exits.size(); ++i) {
    const LightSample light =
        ctx.lights->sample(exits.x_k(i), selection[i], Vec2{point0[i], point1[i]});
    const bool lit = lights_exit_point(light, exits.n_k(i), exits.ns_k(i));
    out.samples[i] = light;
    out.wx[i] = light.wi.x;
    out.wy[i] = light.wi.y;
    out.wz[i] = light.wi.z;
    out.pdf[i] = light.pdf;
    out.delta[i] = light.delta ? 1.0f : 0.0f;
    out.lit[i] = lit ? 1.0f : 0.0f;
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

void queue_connection(Strategy st, uint32_t slot, Rgb contribution,
                      const std::array<ShadowSegment, 3>& segments, ShadowQueue& shadow,
                      KernelCounters& counters) {
  const bool tb = st == Strategy::kTopToBottom;
  const uint32_t first = static_cast<uint32_t>(shadow.segment_count());
  for (const ShadowSegment& seg : segments)
    shadow.add_segment(seg.origin, seg.direction, seg.t_max, kVisibilityOnly);
  shadow.add_connection({tb ? ConnectionKind::kTopToBottom : ConnectionKind::kBottomToTop, slot,
                         first, static_cast<uint32_t>(segments.size()), -1, contribution,
                         Rgb(0.0f)});
  counters.count(tb ? SneeCounter::kTopToBottomConnections : SneeCounter::kBottomToTopConnections);
  counters.count(SneeCounter::kConnectionRays, segments.size());
}

// Weighs the proposals in SIMD chunks and queues the connections that carry something, in
// proposal order. A lane the float weighing cannot hold is weighed by the scalar
// finish_proposal instead (simd/snee_weights_batch.h).
void weigh_and_connect(const KernelContext& ctx, const PathState& state, const ProposalQueue& q,
                       ShadowQueue& shadow, KernelCounters& counters) {
  const size_t n = q.size();
  for (size_t k = 0; k < n; k += simd::kLanes) {
    const size_t count = std::min(simd::kLanes, n - k);
    const simd::ProposalWeights w = simd::weigh_proposals(q.items(), k, count, ctx.snee);
    counters.count_lanes(BatchedKernel::kSubdivisionWeights, count, simd::kLanes);
    for (size_t l = 0; l < count; ++l) {
      const size_t i = k + l;
      const Strategy strategy = q.strategy(i);
      const Rgb beta = state.throughput(q.slot(i));
      if (!w.in_range[l] || q.manifold(i)) {
        // Suffixes the manifold strategy shares (case D on a sphere) have no batched weighing.
        if (!q.manifold(i)) counters.count(SneeCounter::kScalarWeighings);
        const SneeCandidate c = finish_proposal(strategy, q.proposal(i), ctx.snee);
        if (c.valid) {
          queue_connection(strategy, q.slot(i), beta * c.contribution, c.segments, shadow,
                           counters);
        } else {
          count_failure(c.failure, strategy, counters);
        }
      } else if (w.weight[l] > 0 && !is_black(w.contribution[l]) && is_finite(w.contribution[l])) {
        queue_connection(strategy, q.slot(i), beta * w.contribution[l], q.segments(i), shadow,
                         counters);
      } else {
        count_failure(SneeFailure::kZero, strategy, counters);
      }
    }
  }
}

}  // namespace

// Passes over the exit queue: the random numbers (SIMD); top-to-bottom's light samples (per
// exit); both strategies' straight-line sampling (SIMD); the proposals (per exit); their
// weighing (SIMD) and the connections (per proposal). Every pass keeps queue order, so the
// shadow queue is filled in the order the scalar samplers would fill it.
void subdivision(const KernelContext& ctx, PathState& state, StageQueues& q,
                 KernelCounters& counters) {
  const ExitPointQueue& exits = q.subdivide;
  const bool top_to_bottom = ctx.snee.enabled.contains(Strategy::kTopToBottom);
  // Bottom-to-top finds only lights seen by escaped rays; without any it cannot succeed.
  const bool bottom_to_top =
      ctx.snee.enabled.contains(Strategy::kBottomToTop) && ctx.lights->has_escaped_lights();
  SubdivisionScratch& scratch = q.subdivision;
  for_each_chunk(exits.slots(), exits.size(), BatchedKernel::kSubdivisionDraws, counters,
                 [&](const simd::SlotChunk& chunk, size_t k) {
                   draw_chunk(ctx, state, chunk, bottom_to_top, scratch.randoms, k);
                 });
  if (top_to_bottom) sample_lights(ctx, exits, scratch.randoms, scratch.lights);
  for_each_chunk(exits.slots(), exits.size(), BatchedKernel::kSubdivisionSamples, counters,
                 [&](const simd::SlotChunk& chunk, size_t k) {
                   const ChunkExits e = load_exits(ctx, state, exits, chunk, k);
                   if (top_to_bottom) {
                     sample_top_to_bottom_chunk(ctx, e, scratch, scratch.top_to_bottom,
                                                chunk.count(), k);
                   }
                   if (bottom_to_top) {
                     sample_bottom_to_top_chunk(ctx, e, scratch.randoms, scratch.bottom_to_top, k);
                   }
                 });

  ProposalQueue& proposals = scratch.proposals;
  proposals.clear();
  const auto propose = [&](const SneeProposal& p, Strategy st, uint32_t slot) {
    if (p.failure == SneeFailure::kNone && p.sampling_pdf > 0 && std::isfinite(p.sampling_pdf)) {
      proposals.push(p, st, slot);
    } else {
      count_failure(p.failure == SneeFailure::kNone ? SneeFailure::kZero : p.failure, st, counters);
    }
  };
  const auto failure_of = [](uint32_t status) {
    return status == kSneeNotPlaced      ? SneeFailure::kPlacement
           : status == kSneeNotRefracted ? SneeFailure::kRefraction
                                         : SneeFailure::kZero;
  };
  for (size_t i = 0; i < exits.size(); ++i) {
    const uint32_t s = exits.slot(i);
    const MediumInfo& m = ctx.media[static_cast<size_t>(state.medium[s])];
    const SneeMedium& medium = m.medium;
    const SneeOrigin origin{state.vertex_j(s), state.direction_in_j(s)};
    const ExitPoint exit{exits.x_k(i),
                         exits.n_k(i),
                         exits.ns_k(i),
                         {ctx.surfaces[exits.geom(i)].dielectric.eta, exits.alpha(i)}};
    if (top_to_bottom) {
      const StrategyResults& tb = scratch.top_to_bottom;
      if (scratch.lights.lit[i] == 0) {
        count_failure(SneeFailure::kNoLight, Strategy::kTopToBottom, counters);
      } else if (tb.status[i] != kSneeSampled) {
        count_failure(failure_of(tb.status[i]), Strategy::kTopToBottom, counters);
      } else {
        SneeProposal p =
            top_to_bottom_proposal(origin, medium, exit, scratch.lights.samples[i], ctx.epsilon,
                                   {tb.x[i], tb.y[i], tb.z[i]}, tb.pdf[i]);
        // The manifold strategy would run at this x_j if the walk reached it (medium_event:
        // depth below the limit; docs/method.md 3.10).
        const LightSample& light = scratch.lights.samples[i];
        if (m.manifold_solves_for(light, exits.x_k(i)) &&
            state.depth[s] + 1 < static_cast<uint32_t>(ctx.max_depth)) {
          p.suffix.manifold = true;
          p.suffix.manifold_rate = ctx.snee.manifold_rate;
          p.suffix.boundary_curvature = m.manifold_curvature;
          p.suffix.manifold_light_distance = light.distance;
        }
        propose(p, Strategy::kTopToBottom, s);
      }
    }
    if (bottom_to_top) {
      const StrategyResults& bt = scratch.bottom_to_top;
      if (bt.status[i] != kSneeSampled) {
        count_failure(failure_of(bt.status[i]), Strategy::kBottomToTop, counters);
      } else {
        propose(bottom_to_top_proposal(origin, medium, exit, *ctx.lights, ctx.epsilon,
                                       {bt.x[i], bt.y[i], bt.z[i]}, {bt.wx[i], bt.wy[i], bt.wz[i]},
                                       bt.pdf[i]),
                Strategy::kBottomToTop, s);
      }
    }
  }
  weigh_and_connect(ctx, state, proposals, q.shadow, counters);
  q.subdivide.clear();
}

}  // namespace snee
