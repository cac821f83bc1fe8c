#include <algorithm>
#include <type_traits>

#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/simd/free_flight_batch.h"
#include "kernels/simd/hg_sample_batch.h"
#include "kernels/simd/philox_batch.h"
#include "kernels/simd/slot_chunk.h"
#include "kernels/simd/vec3_batch.h"
#include "kernels/stages/exit_event.h"
#include "kernels/stages/first_hit_aovs.h"
#include "kernels/stages/guided_exit.h"
#include "kernels/stages/stages.h"
#include "kernels/wavefront/batched_pass.h"
#include "kernels/wavefront/medium_lanes.h"
#include "kernels/wavefront/path_ops.h"

namespace snee {

namespace {

using simd::FloatBatch;
using simd::UintBatch;
using simd::Vec3Batch;

// What a free flight leaves: the distance t, the point x there, and the path's throughput and
// channel probabilities after it (at the scattering point, or at the boundary it reached).
template <class F>
struct Flight {
  F t;
  lane::Vec3Of<F> x, throughput, channel_p;
};

// The free flight of one lane type F through medium m (any ParticipatingMedium at F) with
// path-level spectral MIS, from origin along w up to the boundary at t_hit. Scattering at t
// weights by sigma_s T(t) / pdf(t) per channel and takes each channel's share of pdf(t);
// reaching the boundary weights by transmittance over the survival probability.
template <class F, class M>
Flight<F> free_flight(const M& m, const lane::Vec3Of<F>& origin, const lane::Vec3Of<F>& w,
                      const lane::Vec3Of<F>& p, const lane::Vec3Of<F>& beta, F t_hit, F u_channel,
                      F u) {
  using namespace lane;
  using V = Vec3Of<F>;
  const F t = m.sample_distance(origin, w, p, u_channel, u);
  const V x = origin + w * t;
  const auto scattered = t < t_hit;
  const auto crossed = !scattered && t_hit < F(kInfinity);
  // Lanes compute both outcomes and select; one slot (F = float) computes only the one it takes,
  // since in a grid medium each transmittance is a voxel walk. The other's values are never
  // selected.
  const auto needs = [](const auto& outcome) {
    if constexpr (std::is_same_v<F, float>) {
      return static_cast<bool>(outcome);
    } else {
      return true;
    }
  };
  const V one{F(1.0f), F(1.0f), F(1.0f)};
  const V tr_hit = needs(crossed) ? m.transmittance(origin, w, t_hit) : one;
  const F survival = dot(p, tr_hit);
  const V tr = needs(scattered) ? m.transmittance(origin, w, t) : one;
  const V channel_pdfs = needs(scattered) ? m.channel_pdfs(origin, w, t, tr) : one;
  const F pdf = dot(p, channel_pdfs);
  const V sigma_s = needs(scattered) ? m.scattering(x) : one;
  const auto channel = [&](F b, F q, F s, F tr_c, F tr_hit_c, F pdf_c) {
    return std::pair{
        select(scattered, b * s * tr_c / pdf, select(crossed, b * tr_hit_c / survival, b)),
        select(scattered, q * pdf_c / pdf, select(crossed, q * tr_hit_c / survival, q))};
  };
  const auto [bx, px] = channel(beta.x, p.x, sigma_s.x, tr.x, tr_hit.x, channel_pdfs.x);
  const auto [by, py] = channel(beta.y, p.y, sigma_s.y, tr.y, tr_hit.y, channel_pdfs.y);
  const auto [bz, pz] = channel(beta.z, p.z, sigma_s.z, tr.z, tr_hit.z, channel_pdfs.z);
  return {t, x, {bx, by, bz}, {px, py, pz}};
}

// The straight-line part of a medium event for one chunk of the queue at position k, all in
// homogeneous media: the free flight, the phase-sampled direction from the scattering point, and
// the roulette number. Every lane is computed; the per-slot pass decides what is used.
void fly(const KernelContext& ctx, PathState& state, const simd::SlotChunk& chunk,
         FlightResults& out, size_t k) {
  const MediumLanes m = load_media(ctx, state, chunk);
  const UintBatch pixel = chunk.load(state.pixel), sample = chunk.load(state.sample);
  const UintBatch event = chunk.load(state.event);
  const simd::RandomBlockBatch rf =
      simd::random_block(ctx.seed, pixel, sample, event, RngPurpose::kFreeFlight, chunk.count());
  const simd::RandomBlockBatch rp =
      simd::random_block(ctx.seed, pixel, sample, event, RngPurpose::kPhase, chunk.count());
  // Roulette starts at the fourth vertex, which this event makes for depth 3 and up; a chunk
  // without such a path (and the one-slot megakernel's early events) draws nothing for it.
  if (xsimd::any(chunk.load(state.depth) >= UintBatch(3u))) {
    simd::random_block(ctx.seed, pixel, sample, event, RngPurpose::kRussianRoulette, chunk.count())
        .u[0]
        .store_aligned(out.u_roulette.data() + k);
  }

  const Vec3Batch p{chunk.load(state.channel_p_r), chunk.load(state.channel_p_g),
                    chunk.load(state.channel_p_b)};
  const Vec3Batch origin{chunk.load(state.origin_x), chunk.load(state.origin_y),
                         chunk.load(state.origin_z)};
  const Vec3Batch w{chunk.load(state.dir_x), chunk.load(state.dir_y), chunk.load(state.dir_z)};
  const Vec3Batch beta{chunk.load(state.throughput_r), chunk.load(state.throughput_g),
                       chunk.load(state.throughput_b)};
  const Flight<FloatBatch> f =
      free_flight(m, origin, w, p, beta, chunk.load(state.hit_t), rf.u[0], rf.u[1]);
  f.t.store_aligned(out.t.data() + k);
  simd::store_aligned(f.x, out.x.data() + k, out.y.data() + k, out.z.data() + k);
  chunk.store(state.throughput_r, f.throughput.x);
  chunk.store(state.throughput_g, f.throughput.y);
  chunk.store(state.throughput_b, f.throughput.z);
  chunk.store(state.channel_p_r, f.channel_p.x);
  chunk.store(state.channel_p_g, f.channel_p.y);
  chunk.store(state.channel_p_b, f.channel_p.z);

  const simd::HgSampleBatch phase = simd::hg_sample(w, m.asymmetry(f.x), rp.u[0], rp.u[1]);
  phase.direction.x.store_aligned(out.wx.data() + k);
  phase.direction.y.store_aligned(out.wy.data() + k);
  phase.direction.z.store_aligned(out.wz.data() + k);
  phase.pdf.store_aligned(out.phase_pdf.data() + k);
}

// The same for the slot at queue position k in a grid medium, one slot at a time: the voxel
// walk's loop length differs from lane to lane. The random numbers are the batch's (the
// counter-based blocks agree bit for bit).
void fly_one(const KernelContext& ctx, PathState& state, uint32_t s, const GridMedium& m,
             FlightResults& out, size_t k) {
  const RandomBlock rf = draw(ctx, state, s, RngPurpose::kFreeFlight);
  const RandomBlock rp = draw(ctx, state, s, RngPurpose::kPhase);
  if (state.depth[s] >= 3u)
    out.u_roulette[k] = draw(ctx, state, s, RngPurpose::kRussianRoulette).u[0];
  const Vec3 w = state.direction(s);
  const Flight<float> f = free_flight(m, state.origin(s), w, state.channel_probabilities(s),
                                      state.throughput(s), state.hit_t[s], rf.u[0], rf.u[1]);
  out.t[k] = f.t;
  out.x[k] = f.x.x, out.y[k] = f.x.y, out.z[k] = f.x.z;
  state.set_throughput(s, f.throughput);
  state.set_channel_probabilities(s, f.channel_p);
  const HgSample<float> phase = hg_sample<float>(w, m.asymmetry(f.x), rp.u[0], rp.u[1]);
  out.wx[k] = phase.direction.x, out.wy[k] = phase.direction.y, out.wz[k] = phase.direction.z;
  out.phase_pdf[k] = phase.pdf;
}

// Next-event estimation from a medium vertex along a straight shadow ray. Worth a ray only when
// the light can be reached without refraction (null boundaries), or under the straight-line
// approximation, which lets the ray pass dielectric boundaries.
void medium_nee(const KernelContext& ctx, PathState& state, uint32_t s, Vec3 x, Vec3 w_before,
                const MediumInfo& m, ShadowQueue& shadow) {
  if (ctx.lights->empty()) return;
  const RandomBlock r = draw(ctx, state, s, RngPurpose::kLightSample);
  const LightSample ls = ctx.lights->sample(x, r.u[0], {r.u[1], r.u[2]});
  if (!ls.valid || ls.pdf <= 0) return;
  const float phase = hg_phase(dot(w_before, ls.wi), m.asymmetry(x));
  const float weight = ls.delta ? 1.0f : power_heuristic(ls.pdf, phase);
  const Rgb contribution = state.throughput(s) * ls.radiance * (phase * weight / ls.pdf);
  if (is_black(contribution)) return;
  const ShadowRay ray = shadow_ray_to_light(ls, x, x);  // medium points are not moved
  const uint32_t seg = shadow.add_segment(x, ray.direction, ray.t_max, state.medium[s]);
  shadow.add_connection({ConnectionKind::kLight, s, seg, 1, -1, contribution, Rgb(0.0f)});
}

// Scattering points closer to the boundary ahead than this many ray-origin clearances (along
// the ray) are checked by keep_clear_of_boundary; beyond it only rays within 1/1024 of grazing
// could still be that close, a share of 1e-3 of the (already rare) points near a boundary.
constexpr float kBoundaryCheckReach = 1024.0f;

// A scattering point nearer the boundary than the ray-origin clearance is where rounding can
// put it on the far side, or leave the next ray blind to the boundary behind its origin: the
// walk would then lose the medium it is in. A dense medium scatters there often (about sigma
// times the clearance per visit to the boundary, 1e-1 at sigma 1e6 on a unit object), so such
// a point moves back along the boundary's normal to the clearance, as surface spawns keep it.
Vec3 keep_clear_of_boundary(const KernelContext& ctx, const PathState& state, uint32_t s, Vec3 x,
                            float t) {
  const float t_hit = state.hit_t[s];
  if (!(t_hit - t < kBoundaryCheckReach * ctx.epsilon)) return x;
  const Vec3 w = state.direction(s);
  const SurfacePoint boundary =
      ctx.embree->surface_point(state.hit_geom[s], state.hit_prim[s], state.origin(s) + w * t_hit);
  const Vec3 into_medium = dot(w, boundary.n) > 0 ? -boundary.n : boundary.n;
  const float depth = dot(x - boundary.p, into_medium);
  return depth < ctx.epsilon ? x + into_medium * (ctx.epsilon - depth) : x;
}

// The AOV albedo of a medium vertex (first_hit_aovs.h), which has no surface: sigma_s / sigma_t
// per channel, 0 in a channel that does not interact (spectral MIS may scatter following
// another). Its AOV normal faces back along the arriving ray.
Rgb single_scattering_albedo(const MediumInfo& m, Vec3 x) {
  return m.visit([&](const auto& medium) {
    const Rgb sigma_s = medium.scattering(x), sigma_t = medium.extinction(x);
    Rgb a(0.0f);
    for (int c = 0; c < 3; ++c) a[c] = sigma_t[c] > 0 ? sigma_s[c] / sigma_t[c] : 0.0f;
    return a;
  });
}

}  // namespace

// Two passes: the flights of the whole queue (fly in SIMD chunks over the slots in homogeneous
// media, fly_one over those in grid media, which a scene with grids sorts to the end of the
// queue), then, per slot in queue order, what branches: routing, vertex memory, depth limit,
// medium NEE, roulette and SNEE.
void medium_event(const KernelContext& ctx, PathState& state, StageQueues& q,
                  KernelCounters& counters) {
  const size_t n = q.medium.size();
  size_t homogeneous = n;
  if (ctx.has_grid_media) {
    homogeneous = q.medium.partition(
        [&](uint32_t s) { return !ctx.media[static_cast<size_t>(state.medium[s])].is_grid(); });
  }
  FlightResults& flights = q.flights;
  for_each_chunk(
      q.medium.begin(), homogeneous, BatchedKernel::kMediumFlights, counters,
      [&](const simd::SlotChunk& chunk, size_t k) { fly(ctx, state, chunk, flights, k); });
  for (size_t k = homogeneous; k < n; ++k) {
    const uint32_t s = q.medium[k];
    fly_one(ctx, state, s, ctx.media[static_cast<size_t>(state.medium[s])].grid, flights, k);
  }
  for (size_t k = 0; k < n; ++k) {
    const uint32_t s = q.medium[k];
    const float t_hit = state.hit_t[s];
    if (!(flights.t[k] < t_hit)) {
      // The flight reached the boundary (throughput already weighted), or left a medium
      // without a closed boundary.
      if (std::isfinite(t_hit)) {
        q.surface.push(s);
      } else {
        q.escaped.push(s);
      }
      continue;
    }
    const MediumInfo& m = ctx.media[static_cast<size_t>(state.medium[s])];
    const Vec3 w_before = state.direction(s);
    const Vec3 x = keep_clear_of_boundary(ctx, state, s, {flights.x[k], flights.y[k], flights.z[k]},
                                          flights.t[k]);
    state.depth[s] += 1;
    state.flags[s] &= ~(kPathAfterSneeExit | kPathLightSkipped | kPathAfterGuidedExit);
    state.push_vertex(s, x, w_before, true);
    close_aov_chain(state, s, flights.t[k], single_scattering_albedo(m, x), -w_before);
    if (static_cast<int>(state.depth[s]) >= ctx.max_depth || is_black(state.throughput(s))) {
      q.retire.push(s);
      continue;
    }
    const bool straight_nee = m.straight_nee || ctx.integrator == Integrator::kStraightLine;
    if (straight_nee) medium_nee(ctx, state, s, x, w_before, m, q.shadow);
    // The phase weight f/pdf is exactly 1 for HG; the pdf is kept for MIS at the next light hit.
    state.mis_pdf[s] = straight_nee ? flights.phase_pdf[k] : 0.0f;
    if (!survive_russian_roulette(state, s, flights.u_roulette[k])) {
      q.retire.push(s);
      continue;
    }
    // SNEE runs after roulette on the survivors with their rescaled throughput (unbiased);
    // the probe stage reads x_i from the path's vertex memory and draws at this event.
    if (ctx.integrator == Integrator::kSnee && !m.straight_nee && m.snee_eligible()) {
      connect_manifold(ctx, state, s, m, q.shadow, counters);
      connect_guided_exit(ctx, state, s, m, q.shadow, counters);
      // Top-to-bottom and bottom-to-top place x_j one event further and leave from it: the
      // walk would stop at x_j if that were the depth limit, so they stop there too.
      if (static_cast<int>(state.depth[s]) + 1 < ctx.max_depth) q.probe.push(s);
    }
    state.set_ray(s, x, {flights.wx[k], flights.wy[k], flights.wz[k]});
    state.event[s] += 1;
    q.extend.push(s);
  }
  q.medium.clear();
}

}  // namespace snee
