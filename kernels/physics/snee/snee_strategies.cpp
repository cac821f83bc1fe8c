#include "kernels/physics/snee/snee_strategies.h"

#include <algorithm>
#include <cmath>

#include "core/vec3d.h"
#include "kernels/physics/snee/snee_pdfs.h"
#include "kernels/physics/snee/subdivision_vertices.h"

namespace snee {

namespace {

SneeSuffix make_suffix(const SneeOrigin& origin, const SneeMedium& medium, const ExitPoint& exit,
                       Vec3 x_j, Vec3 omega_o, float light_pdf, bool light_delta) {
  SneeSuffix s;
  s.x_i = origin.x_i;
  s.omega_in = origin.omega_in;
  s.x_j = x_j;
  s.x_k = exit.x_k;
  s.n_k = exit.n_k;
  s.ns_k = exit.ns_k;
  s.omega_o = omega_o;
  s.medium = medium;
  s.interface = exit.interface;
  s.light_pdf = light_pdf;
  s.light_delta = light_delta;
  // The probe found x_k as the first hit from x_i, and both subdivision strategies place a
  // medium vertex x_j between two medium-side points.
  s.v_first = true;
  s.x_i_medium = true;
  s.x_j_medium = true;
  return s;
}

ShadowSegment segment_between(Vec3 from, Vec3 to) {
  const Vec3 d = to - from;
  const float length_d = length(d);
  return {from, d / length_d, length_d};
}

SneeProposal proposal(const SneeSuffix& s, Rgb emitted, double sampling_pdf,
                      std::array<ShadowSegment, 3> segments) {
  SneeProposal p;
  p.suffix = s;
  p.emitted = emitted;
  p.sampling_pdf = sampling_pdf;
  p.segments = segments;
  p.failure = SneeFailure::kNone;
  return p;
}

template <size_t N>
std::array<double, N> in_double(std::span<const float, N> u) {
  std::array<double, N> out;
  for (size_t n = 0; n < N; ++n) out[n] = u[n];
  return out;
}

SneeProposal failed_proposal(SneeFailure why) {
  SneeProposal p;
  p.failure = why;
  return p;
}

}  // namespace

SneeProposal propose_top_to_bottom(const SneeOrigin& origin, const SneeMedium& medium,
                                   const ExitPoint& exit, const LightTable& lights,
                                   const SneeOptions& options, float epsilon,
                                   std::span<const float, kTopToBottomDimensions> u) {
  using R = TopToBottomRandoms;
  const LightSample light = lights.sample(exit.x_k, u[R::kLightSelection],
                                          Vec2{u[R::kLightPoint], u[R::kLightPoint + 1]});
  if (!lights_exit_point(light, exit.n_k, exit.ns_k)) {
    return failed_proposal(SneeFailure::kNoLight);
  }
  const TopToBottomVertex<double> v = top_to_bottom_vertex<double>(
      {Vec3d(origin.x_i), Vec3d(origin.omega_in), Vec3d(exit.x_k), Vec3d(exit.n_k),
       Vec3d(exit.ns_k), medium.g, Vec3d(medium.sigma_t), exit.interface.as<double>(),
       Vec3d(light.wi), light.pdf, light.delta},
      options, in_double(u));
  if (!v.refracted) return failed_proposal(SneeFailure::kRefraction);
  const Vec3 x_j(v.x_j);
  if (!v.distanced || !is_finite(x_j)) return failed_proposal(SneeFailure::kZero);
  return top_to_bottom_proposal(origin, medium, exit, light, epsilon, x_j, v.pdf);
}

SneeProposal top_to_bottom_proposal(const SneeOrigin& origin, const SneeMedium& medium,
                                    const ExitPoint& exit, const LightSample& light, float epsilon,
                                    Vec3 x_j, double sampling_pdf) {
  SneeSuffix s = make_suffix(origin, medium, exit, x_j, light.wi, light.pdf, light.delta);
  s.light_distant = std::isinf(light.distance);
  const Vec3 inner = exit.x_k - epsilon * exit.n_k, outer = exit.x_k + epsilon * exit.n_k;
  const ShadowRay to_light = shadow_ray_to_light(light, exit.x_k, outer);
  return proposal(s, light.radiance, sampling_pdf,
                  {segment_between(inner, x_j), segment_between(x_j, origin.x_i),
                   ShadowSegment{outer, to_light.direction, to_light.t_max}});
}

SneeProposal propose_bottom_to_top(const SneeOrigin& origin, const SneeMedium& medium,
                                   const ExitPoint& exit, const LightTable& lights,
                                   const SneeOptions& options, float epsilon,
                                   std::span<const float, kBottomToTopDimensions> u) {
  const BottomToTopVertex<double> v = bottom_to_top_vertex<double>(
      {Vec3d(origin.x_i), Vec3d(origin.omega_in), Vec3d(exit.x_k), Vec3d(exit.n_k),
       Vec3d(exit.ns_k), medium.g, exit.interface.as<double>()},
      options, in_double(u));
  const Vec3 x_j(v.x_j);
  if (!v.placed || !is_finite(x_j)) return failed_proposal(SneeFailure::kPlacement);
  if (!v.refracted) return failed_proposal(SneeFailure::kRefraction);
  return bottom_to_top_proposal(origin, medium, exit, lights, epsilon, x_j, Vec3(v.omega_o), v.pdf);
}

SneeProposal bottom_to_top_proposal(const SneeOrigin& origin, const SneeMedium& medium,
                                    const ExitPoint& exit, const LightTable& lights, float epsilon,
                                    Vec3 x_j, Vec3 omega_o, double sampling_pdf) {
  const Rgb emitted = lights.escaped_radiance(omega_o);
  if (is_black(emitted)) return failed_proposal(SneeFailure::kNoLight);
  const SneeSuffix s =
      make_suffix(origin, medium, exit, x_j, omega_o, lights.escaped_pdf(omega_o), false);
  const Vec3 inner = exit.x_k - epsilon * exit.n_k, outer = exit.x_k + epsilon * exit.n_k;
  return proposal(s, emitted, sampling_pdf,
                  {segment_between(origin.x_i, x_j), segment_between(x_j, inner),
                   ShadowSegment{outer, omega_o, kInfinity}});
}

SneeCandidate sample_top_to_bottom(const SneeOrigin& origin, const SneeMedium& medium,
                                   const ExitPoint& exit, const LightTable& lights,
                                   const SneeOptions& options, float epsilon,
                                   std::span<const float, kTopToBottomDimensions> u) {
  return finish_proposal(Strategy::kTopToBottom,
                         propose_top_to_bottom(origin, medium, exit, lights, options, epsilon, u),
                         options);
}

SneeCandidate sample_bottom_to_top(const SneeOrigin& origin, const SneeMedium& medium,
                                   const ExitPoint& exit, const LightTable& lights,
                                   const SneeOptions& options, float epsilon,
                                   std::span<const float, kBottomToTopDimensions> u) {
  return finish_proposal(Strategy::kBottomToTop,
                         propose_bottom_to_top(origin, medium, exit, lights, options, epsilon, u),
                         options);
}

SneeCandidate finish_proposal(Strategy st, const SneeProposal& p, const SneeOptions& options) {
  SneeCandidate c;
  c.failure = p.failure;
  if (p.failure != SneeFailure::kNone) return c;
  c.failure = SneeFailure::kZero;
  if (!(p.sampling_pdf > 0) || !std::isfinite(p.sampling_pdf)) return c;
  const SneeSuffix& s = p.suffix;
  const SuffixWeighing<double> w = weigh_suffix(s, options);
  const double weight = mis_weight(st, strategy_pdfs(s, w), options);
  if (!(weight > 0)) return c;
  const Rgb f = Vec3(w.attenuation) * p.emitted * static_cast<float>(w.path);
  const Rgb contribution = f * static_cast<float>(weight / p.sampling_pdf);
  if (is_black(contribution) || !is_finite(contribution)) return c;
  c.x_j = s.x_j;
  c.omega_o = s.omega_o;
  c.segments = p.segments;
  c.contribution = contribution;
  c.pdf = p.sampling_pdf;
  c.weight = weight;
  c.valid = true;
  c.failure = SneeFailure::kNone;
  return c;
}

double snee_exit_weight(Strategy st, const SneeSuffix& s, const SneeOptions& options) {
  return mis_weight(st, strategy_pdfs(s, options), options);
}

ExitWeights snee_exit_weights(Strategy st, SneeSuffix s, const SneeOptions& options) {
  const SuffixWeighing<double> weighing = weigh_suffix(s, options);
  ExitWeights w;
  s.v_first = true;
  w.if_first_hit = mis_weight(st, strategy_pdfs(s, weighing), options);
  s.v_first = false;
  w.if_not_first_hit = mis_weight(st, strategy_pdfs(s, weighing), options);
  return w;
}

}  // namespace snee
