#include "kernels/stages/guided_exit.h"

#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/physics/snee/exit_guide.h"
#include "kernels/wavefront/path_ops.h"

namespace snee {

namespace {

// The walk's density a and the guided exit's b of the step from x_j along w to the boundary
// after t. a takes the free flight's survival with equal channel weights: the weights need one
// function both sides evaluate alike, and the walk's channel weights at x_j are gone by the
// time its exit is weighed.
struct StepDensities {
  float phase = 0;  // f_p at x_j, part of a
  float walk = 0;
  float guided = 0;
};

StepDensities step_densities(const KernelContext& ctx, const MediumInfo& m, const ExitGuide& guide,
                             float cap_cosine, Vec3 omega_in, Vec3 w, float t) {
  const float phase = hg_phase(dot(omega_in, w), m.medium.g);
  return {phase, phase * free_flight_survival(m.medium.sigma_t, t),
          ctx.snee.guide_rate * exit_guide_pdf(guide, cap_cosine, w)};
}

ExitGuide guide_at(const KernelContext& ctx, const MediumInfo& m, Vec3 x_j) {
  const ProbeTargets& targets = ctx.snee.probe_targets;
  if (!m.guide_mesh) {
    const float eta = ctx.surfaces[static_cast<size_t>(m.guide_boundary)].dielectric.eta;
    return exit_guide(targets, m.guide_centre, m.guide_radius, eta, x_j);
  }
  ExitGuide guide;
  for (int t = 0; t < targets.count; ++t) {
    const int tree = m.guide_tree_of_target[static_cast<size_t>(t)];
    if (tree < 0) continue;
    add_exit_guide_axes(guide, targets.target[static_cast<size_t>(t)].share, x_j,
                        (*m.guide_mesh)[static_cast<size_t>(tree)].exits_toward(x_j));
  }
  return guide;
}

// Where the ray from x_j along w leaves the boundary: the sphere in closed form (what lies
// between is for a visibility segment to find), the mesh by a ray (false when it meets
// something else first, which the walk would have met too).
struct BoundaryExit {
  Vec3 p, n;
  float t = 0;
  bool needs_visibility = false;
};
bool boundary_exit(const KernelContext& ctx, const MediumInfo& m, Vec3 x_j, Vec3 w,
                   BoundaryExit* out) {
  if (!m.guide_mesh) {
    out->t = sphere_exit_distance(m.guide_centre, m.guide_radius, x_j, w);
    out->p = x_j + w * out->t;
    out->n = normalize(out->p - m.guide_centre);
    out->needs_visibility = true;
    return out->t > 0;
  }
  float t = 0;
  uint32_t geom = 0, prim = 0;
  if (!ctx.embree->intersect1(x_j, w, 0.0f, kInfinity, &t, &geom, &prim) ||
      geom != static_cast<uint32_t>(m.guide_boundary)) {
    return false;
  }
  const SurfacePoint hit = ctx.embree->surface_point(geom, prim, x_j + w * t);
  out->p = hit.p;
  out->n = hit.n;
  out->t = length(hit.p - x_j);
  return dot(w, hit.n) > 0 && out->t > 0;
}

float square(float x) {
  return x * x;
}

}  // namespace

float walk_guide_ratio(const KernelContext& ctx, const PathState& state, uint32_t slot, Vec3 p,
                       Vec3 n, const SurfaceInfo& info, uint32_t geom) {
  if (ctx.integrator != Integrator::kSnee || state.medium[slot] < 0 ||
      info.interior_medium != state.medium[slot]) {
    return 0.0f;
  }
  const uint32_t flags = state.flags[slot];
  if ((flags & kPathMediumVertexJ) == 0 || (flags & kPathMediumVertexI) != 0) return 0.0f;
  const MediumInfo& m = ctx.media[static_cast<size_t>(state.medium[slot])];
  if (m.guide_boundary != static_cast<int32_t>(geom)) return 0.0f;
  const Vec3 w = state.direction(slot);
  if (!(dot(w, n) > 0)) return 0.0f;  // not leaving
  const Vec3 x_j = state.vertex_j(slot);
  const StepDensities d = step_densities(ctx, m, guide_at(ctx, m, x_j),
                                         exit_guide_cap_cosine(ctx.snee.guide_cap_degrees),
                                         state.direction_in_j(slot), w, length(p - x_j));
  if (!(d.guided > 0)) return 0.0f;
  return d.walk > 0 ? d.guided / d.walk : kInfinity;
}

float walk_light_sample_weight(float ratio, float p_light, float p_bsdf, bool delta_light,
                               bool distant) {
  const float r2 = square(ratio);
  if (delta_light) return 1.0f / (1.0f + r2);
  const float l2 = square(p_light), s2 = square(p_bsdf);
  return distant ? l2 / ((1.0f + r2) * (l2 + s2)) : l2 / (l2 * (1.0f + r2) + s2);
}

float walk_bsdf_sample_weight(float ratio, float p_bsdf, float p_light, bool delta_bsdf,
                              bool distant) {
  const float r2 = square(ratio);
  if (delta_bsdf) return distant ? 1.0f / (1.0f + r2) : 1.0f;
  const float l2 = square(p_light), s2 = square(p_bsdf);
  return distant ? s2 / ((1.0f + r2) * (l2 + s2)) : s2 / (l2 * (1.0f + r2) + s2);
}

float guided_light_sample_weight(float walk, float guided, float p_light, float p_bsdf,
                                 bool delta_light, bool distant) {
  const float a2 = square(walk), b2 = square(guided);
  if (delta_light) return b2 / (a2 + b2);
  const float l2 = square(p_light), s2 = square(p_bsdf);
  return distant ? b2 * l2 / ((a2 + b2) * (l2 + s2)) : b2 * l2 / (a2 * (l2 + s2) + b2 * l2);
}

float guided_bsdf_sample_weight(float walk, float guided, float p_bsdf, float p_light,
                                bool delta_bsdf) {
  const float a2 = square(walk), b2 = square(guided);
  if (delta_bsdf) return b2 / (a2 + b2);
  const float l2 = square(p_light), s2 = square(p_bsdf);
  return b2 * s2 / ((a2 + b2) * (l2 + s2));
}

void connect_guided_exit(const KernelContext& ctx, const PathState& state, uint32_t slot,
                         const MediumInfo& m, ShadowQueue& shadow, KernelCounters& counters) {
  if (m.guide_boundary < 0 || (state.flags[slot] & kPathMediumVertexI) != 0) return;
  const RandomBlock r = draw(ctx, state, slot, RngPurpose::kSneeGuidedExit);
  const float rate = ctx.snee.guide_rate;
  if (!(r.u[0] < rate)) return;
  const Vec3 x_j = state.vertex_j(slot);
  const Vec3 omega_in = state.direction_in_j(slot);
  const ExitGuide guide = guide_at(ctx, m, x_j);
  const float cap = exit_guide_cap_cosine(ctx.snee.guide_cap_degrees);
  Vec3 w;
  if (!exit_guide_sample(guide, cap, r.u[0] / rate, {r.u[1], r.u[2]}, &w)) {
    counters.count(SneeCounter::kGuidedExitNoAxis);
    return;
  }
  BoundaryExit exit;
  if (!boundary_exit(ctx, m, x_j, w, &exit)) return;
  const float t = exit.t;
  const StepDensities d = step_densities(ctx, m, guide, cap, omega_in, w, t);
  if (!(d.guided > 0)) return;
  const Vec3 x_k = exit.p;
  const Vec3 n = exit.n;
  const Vec3 outer = x_k + ctx.epsilon * n;
  const SurfaceInfo& info = ctx.surfaces[static_cast<size_t>(m.guide_boundary)];
  const DielectricParams& interface = info.dielectric;
  const Frame frame = Frame::from_normal(n);
  const Vec3 wo_local = frame.to_local(-w);
  // The walk's flight weight T / P_pass and its phase weight 1 become f_p T / b.
  const Rgb beta =
      state.throughput(slot) * m.medium.transmittance(x_j, w, t) * (d.phase / d.guided);
  // Outside the sphere: vacuum, with null surfaces tracked as the walk crosses them.
  const int32_t outside = ctx.has_null_surfaces ? -1 : kVisibilityOnly;
  const auto connect = [&](Vec3 wi, float t_max, Rgb contribution) {
    if (is_black(contribution) || !is_finite(contribution)) return;
    // The segments of a connection are consecutive: x_j -> x_k (on the sphere), then the light.
    const uint32_t inner =
        exit.needs_visibility
            ? shadow.add_segment(x_j, w, std::max(0.0f, t - ctx.epsilon), kVisibilityOnly)
            : 0;
    const uint32_t to_light = shadow.add_segment(outer, wi, t_max, outside);
    shadow.add_connection({ConnectionKind::kLight, slot, exit.needs_visibility ? inner : to_light,
                           exit.needs_visibility ? 2u : 1u, -1, contribution, Rgb(0.0f)});
    counters.count(SneeCounter::kGuidedExitConnections);
  };

  // Light-sampled: as the walk's exit samples the light (shade_surface's surface_nee).
  const RandomBlock rl = draw(ctx, state, slot, RngPurpose::kSneeGuidedExitLight);
  if (!interface.delta() && !ctx.lights->empty()) {
    const LightSample ls = ctx.lights->sample(x_k, rl.u[0], {rl.u[1], rl.u[2]});
    if (ls.valid && ls.pdf > 0 && dot(ls.wi, n) > 0) {
      const Vec3 wi_local = frame.to_local(ls.wi);
      const float f = dielectric_eval(interface, wo_local, wi_local);
      const float p_bsdf = dielectric_pdf(interface, wo_local, wi_local);
      if (f > 0) {
        const bool distant = std::isinf(ls.distance);
        const float weight =
            guided_light_sample_weight(d.walk, d.guided, ls.pdf, p_bsdf, ls.delta, distant);
        const ShadowRay ray = shadow_ray_to_light(ls, x_k, outer);
        connect(ray.direction, ray.t_max,
                beta * ls.radiance * (f * std::fabs(wi_local.z) * weight / ls.pdf));
      }
    }
  }
  // BSDF-sampled, toward the distant lights only (an emitter would need its hit found).
  const RandomBlock rb = draw(ctx, state, slot, RngPurpose::kSneeGuidedExitBsdf);
  const BsdfSample bs = dielectric_sample(interface, wo_local, {rb.u[0], rb.u[1]}, rl.u[3]);
  if (!bs.valid || !(bs.pdf > 0) || !(bs.f > 0) || !bs.transmission) return;
  const Vec3 wi = frame.to_world(bs.wi);
  if (!(dot(wi, n) > 0)) return;
  const Rgb le = ctx.lights->escaped_radiance(wi);
  if (is_black(le)) return;
  const float weight =
      guided_bsdf_sample_weight(d.walk, d.guided, bs.pdf, ctx.lights->escaped_pdf(wi), bs.delta);
  connect(wi, kInfinity, beta * le * (bs.f * std::fabs(bs.wi.z) / bs.pdf * weight));
}

}  // namespace snee
