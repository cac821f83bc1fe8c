#include "kernels/medium/free_flight.h"
#include "kernels/medium/henyey_greenstein.h"
#include "kernels/path_ops.h"
#include "kernels/stages.h"

namespace snee {

namespace {

// Next-event estimation from a medium vertex along a straight shadow ray. Worth a ray only when
// the light can be reached without refraction (null boundaries), or under the straight-line
// approximation, which lets the ray pass dielectric boundaries.
void medium_nee(const KernelContext& ctx, PathState& state, uint32_t s, Vec3 x, Vec3 w_before,
                const MediumInfo& m, ShadowQueue& shadow) {
  if (ctx.lights->empty()) return;
  const RandomBlock r = draw(ctx, state, s, RngPurpose::kLightSample);
  const LightSample ls = ctx.lights->sample(x, r.u[0], {r.u[1], r.u[2]});
  if (!ls.valid || ls.pdf <= 0) return;
  const float phase = hg_phase(dot(w_before, ls.wi), m.g);
  const float weight = ls.delta ? 1.0f : power_heuristic(ls.pdf, phase);
  const Rgb contribution = state.throughput(s) * ls.radiance * (phase * weight / ls.pdf);
  if (is_black(contribution)) return;
  const ShadowRay ray = shadow_ray_to_light(ls, x, x);  // medium points are not moved
  const uint32_t seg = shadow.add_segment(x, ray.direction, ray.t_max, state.medium[s]);
  shadow.add_connection({ConnectionKind::kLight, s, seg, 1, -1, contribution, Rgb(0.0f)});
}

}  // namespace

void medium_event(const KernelContext& ctx, PathState& state, StageQueues& q,
                  KernelCounters& counters) {
  (void)counters;
  for (const uint32_t s : q.medium) {
    const MediumInfo& m = ctx.media[static_cast<size_t>(state.medium[s])];
    const RandomBlock r = draw(ctx, state, s, RngPurpose::kFreeFlight);
    const Rgb channel_p = state.channel_probabilities(s);
    const float t = free_flight_sample(m.sigma_t, channel_p, r.u[0], r.u[1]);
    const float t_hit = state.hit_t[s];
    if (!(t < t_hit)) {
      // The flight reached the boundary: weight by transmittance over the survival probability.
      if (std::isfinite(t_hit)) {
        const Rgb tr = transmittance(m.sigma_t, t_hit);
        const float survival = free_flight_survival(m.sigma_t, channel_p, t_hit);
        state.set_throughput(s, state.throughput(s) * tr / survival);
        state.set_channel_probabilities(s, channel_p * tr / survival);
        q.surface.push(s);
      } else {
        q.escaped.push(s);  // a medium without a closed boundary: the ray leaves the scene
      }
      continue;
    }
    // Scattering vertex x: throughput picks up sigma_s T(t) / pdf(t) per channel, and each
    // channel's probability its share of pdf(t).
    const Vec3 w_before = state.direction(s);
    const Vec3 x = state.origin(s) + w_before * t;
    const Rgb channel_pdfs = free_flight_channel_pdfs(m.sigma_t, t);
    const float pdf = dot(channel_p, channel_pdfs);
    state.set_throughput(s, state.throughput(s) * m.sigma_s * transmittance(m.sigma_t, t) / pdf);
    state.set_channel_probabilities(s, channel_p * channel_pdfs / pdf);
    state.depth[s] += 1;
    state.flags[s] &= ~(kPathAfterSneeExit | kPathLightSkipped);
    state.push_vertex(s, x, w_before, true);
    if (static_cast<int>(state.depth[s]) >= ctx.max_depth || is_black(state.throughput(s))) {
      q.retire.push(s);
      continue;
    }
    const bool straight_nee = m.straight_nee || ctx.integrator == Integrator::kStraightLine;
    if (straight_nee) medium_nee(ctx, state, s, x, w_before, m, q.shadow);

    const RandomBlock rp = draw(ctx, state, s, RngPurpose::kPhase);
    float phase_pdf = 0;
    const Vec3 w_after = hg_sample(w_before, m.g, {rp.u[0], rp.u[1]}, &phase_pdf);
    // The phase weight f/pdf is exactly 1 for HG; the pdf is kept for MIS at the next light hit.
    state.mis_pdf[s] = straight_nee ? phase_pdf : 0.0f;
    if (!survive_russian_roulette(ctx, state, s)) {
      q.retire.push(s);
      continue;
    }
    // SNEE runs after roulette on the survivors with their rescaled throughput (unbiased);
    // the probe stage reads x_i from the path's vertex memory and draws at this event.
    if (ctx.integrator == Integrator::kSnee && !m.straight_nee) q.probe.push(s);
    state.set_ray(s, x, w_after);
    state.event[s] += 1;
    q.extend.push(s);
  }
  q.medium.clear();
}

}  // namespace snee
