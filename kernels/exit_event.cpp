#include "kernels/exit_event.h"

#include "kernels/path_ops.h"
#include "kernels/snee/snee_strategies.h"

namespace snee {

namespace {

SneeSuffix exit_suffix(const KernelContext& ctx, const ExitEvent& e, Vec3 omega_o, float light_pdf,
                       bool delta) {
  const MediumInfo& m = ctx.media[static_cast<size_t>(e.medium)];
  SneeSuffix s;
  s.x_i = e.x_i;
  s.omega_in = e.omega_in;
  s.x_j = e.x_j;
  s.x_k = e.x_k;
  s.n_k = e.n_k;
  s.omega_o = omega_o;
  s.medium = {m.sigma_s, m.sigma_t, m.g};
  s.interface = e.interface;
  s.light_pdf = light_pdf;
  s.light_delta = delta;
  s.x_i_medium = true;
  s.x_j_medium = true;
  return s;
}

}  // namespace

ExitEvent make_exit_event(const KernelContext& ctx, const PathState& state, uint32_t slot, Vec3 p,
                          Vec3 n, const SurfaceInfo& info) {
  ExitEvent e;
  const Vec3 d = state.direction(slot);
  const bool leaving_medium = dot(d, n) > 0 && state.medium[slot] >= 0 &&
                              info.kind == MaterialKind::kDielectric &&
                              info.interior_medium == state.medium[slot];
  const uint32_t flags = state.flags[slot];
  const bool after_medium_vertex = (flags & kPathMediumVertexJ) != 0;
  if (ctx.integrator == Integrator::kStraightLine) {
    e.light_handled_elsewhere = leaving_medium && after_medium_vertex;
    return e;
  }
  if (ctx.integrator != Integrator::kSnee || !leaving_medium || !after_medium_vertex ||
      (flags & kPathMediumVertexI) == 0) {
    return e;
  }
  e.snee_possible = true;
  e.x_i = state.vertex_i(slot);
  e.omega_in = state.direction_in_i(slot);
  e.x_j = state.vertex_j(slot);
  e.x_k = p;
  e.n_k = n;
  e.medium = state.medium[slot];
  e.interface = info.dielectric;
  const Vec3 to_k = p - e.x_i;
  const float dist = length(to_k);
  e.first_hit_direction = to_k / dist;
  e.first_hit_tmax = std::max(0.0f, dist - ctx.epsilon);
  return e;
}

ExitWeights exit_light_sample_weights(const KernelContext& ctx, const ExitEvent& exit, Vec3 omega_o,
                                      float light_pdf, bool delta) {
  SneeSuffix s = exit_suffix(ctx, exit, omega_o, light_pdf, delta);
  ExitWeights w;
  s.v_first = true;
  w.if_first_hit =
      static_cast<float>(snee_exit_weight(Strategy::kUnidirectionalLight, s, ctx.snee));
  s.v_first = false;
  w.if_not_first_hit =
      static_cast<float>(snee_exit_weight(Strategy::kUnidirectionalLight, s, ctx.snee));
  return w;
}

void defer_bsdf_exit(const KernelContext& ctx, PathState& state, uint32_t slot,
                     const ExitEvent& exit, Vec3 omega_o, ShadowQueue& shadow) {
  state.flags[slot] |= kPathEscapeDeferred;
  const Rgb le = ctx.lights->escaped_radiance(omega_o);
  if (is_black(le)) return;
  SneeSuffix s = exit_suffix(ctx, exit, omega_o, ctx.lights->escaped_pdf(omega_o), false);
  s.v_first = true;
  const float w_first =
      static_cast<float>(snee_exit_weight(Strategy::kUnidirectionalBsdf, s, ctx.snee));
  s.v_first = false;
  const float w_not_first =
      static_cast<float>(snee_exit_weight(Strategy::kUnidirectionalBsdf, s, ctx.snee));
  const Rgb unweighted = state.throughput(slot) * le;
  const uint32_t escape = shadow.add_segment(
      offset_origin(exit.x_k, exit.n_k, omega_o, ctx.epsilon), omega_o, kInfinity, kVisibilityOnly);
  const uint32_t selector =
      shadow.add_segment(exit.x_i, exit.first_hit_direction, exit.first_hit_tmax, kVisibilityOnly);
  shadow.add_connection({ConnectionKind::kLight, slot, escape, 1, static_cast<int32_t>(selector),
                         unweighted * w_first, unweighted * w_not_first});
}

}  // namespace snee
