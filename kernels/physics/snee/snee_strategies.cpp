#include "kernels/physics/snee/snee_strategies.h"

#include <algorithm>
#include <cmath>

#include "kernels/physics/snee/distance_samplers.h"
#include "kernels/physics/snee/joint_importance.h"
#include "kernels/physics/snee/probe.h"
#include "kernels/physics/snee/snee_integrand.h"
#include "kernels/physics/snee/snee_pdfs.h"

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
  const double cos_o = dot(exit.ns_k, light.wi);

  // Inward direction: transmission lobe only, given the light-side direction, in the shading
  // frame; it must enter by the geometric normal too.
  const Frame frame = Frame::from_normal(exit.ns_k);
  const Vec3 local_o = frame.to_local(light.wi);
  Vec3 local_kj;
  if (!dielectric_sample_transmission(
          exit.interface, local_o, Vec2{u[R::kInwardNormal], u[R::kInwardNormal + 1]}, &local_kj)) {
    return failed_proposal(SneeFailure::kRefraction);
  }
  const Vec3 omega_kj = normalize(frame.to_world(local_kj));
  const double cos_kj = -dot(exit.ns_k, omega_kj);
  if (!(cos_kj > 0) || !(dot(exit.n_k, omega_kj) < 0)) {
    return failed_proposal(SneeFailure::kRefraction);
  }

  const DistanceMixture mixture{medium.sigma_t, options.c_exponential, exit.x_k, omega_kj,
                                origin.x_i};
  const DistanceSample distance = distance_mixture_sample(mixture, u[R::kDistanceTechnique],
                                                          u[R::kDistanceChannel], u[R::kDistance]);
  if (!distance.valid || !(distance.t > 0)) return failed_proposal(SneeFailure::kZero);
  const Vec3 x_j = exit.x_k + distance.t * omega_kj;

  // Density of what was just sampled, in the suffix's measure (see top_to_bottom_pdf): the
  // inward direction's solid angle at x_k becomes x_j's volume by 1 / t^2, except with a smooth
  // interface and a delta light (case D), whose measure is the distance along the ray.
  const double t = distance.t;
  double pdf =
      probe_area_pdf(options.probe, origin.omega_in, medium.g, origin.x_i, exit.x_k, exit.n_k) *
      light.pdf * distance.pdf;
  if (!exit.interface.delta()) {
    pdf *= dielectric_transmission_pdf(exit.interface, local_o, local_kj) / (t * t);
  } else if (!light.delta) {
    // The refracted direction is deterministic; the refraction Jacobian relates its solid
    // angle to omega_o's.
    const double eta = exit.interface.eta;
    pdf *= eta * eta * cos_kj / cos_o / (t * t);
  }

  return top_to_bottom_proposal(origin, medium, exit, light, epsilon, x_j, pdf);
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
  const JointImportance jis{origin.x_i, origin.omega_in, exit.x_k, medium.g, options.c_joint};
  using R = BottomToTopRandoms;
  const JointImportanceSample placed =
      joint_importance_sample(jis, u.subspan<R::kPlacement, kJointImportanceDimensions>());
  if (!placed.valid) return failed_proposal(SneeFailure::kPlacement);
  const Vec3 x_j = placed.x_j;
  const Vec3 to_k = exit.x_k - x_j;
  const float r_jk = length(to_k);
  if (!(r_jk > 0)) return failed_proposal(SneeFailure::kPlacement);
  const Vec3 omega_kj = -to_k / r_jk;
  // x_j must lie on the medium side of x_k, by both normals.
  if (!(dot(exit.n_k, omega_kj) < 0) || !(dot(exit.ns_k, omega_kj) < 0)) {
    return failed_proposal(SneeFailure::kPlacement);
  }

  // Outward direction: transmission lobe only, given the medium-side direction, in the shading
  // frame; it must leave by the geometric normal too.
  const Frame frame = Frame::from_normal(exit.ns_k);
  const Vec3 local_kj = frame.to_local(omega_kj);
  Vec3 local_o;
  if (!dielectric_sample_transmission(exit.interface, local_kj,
                                      Vec2{u[R::kOutwardNormal], u[R::kOutwardNormal + 1]},
                                      &local_o)) {
    return failed_proposal(SneeFailure::kRefraction);
  }
  const Vec3 omega_o = normalize(frame.to_world(local_o));
  if (!(dot(exit.ns_k, omega_o) > 0) || !(dot(exit.n_k, omega_o) > 0)) {
    return failed_proposal(SneeFailure::kRefraction);
  }
  double pdf =
      probe_area_pdf(options.probe, origin.omega_in, medium.g, origin.x_i, exit.x_k, exit.n_k) *
      placed.pdf;
  if (!exit.interface.delta()) {
    pdf *= dielectric_transmission_pdf(exit.interface, local_kj, local_o);
  }
  return bottom_to_top_proposal(origin, medium, exit, lights, epsilon, x_j, omega_o, pdf);
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
  const SuffixGeometry g = suffix_geometry(s);
  const double weight = mis_weight(st, strategy_pdfs(s, g, options), options);
  if (!(weight > 0)) return c;
  const Rgb f = suffix_integrand(s, g, p.emitted);
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
  const SuffixGeometry g = suffix_geometry(s);
  ExitWeights w;
  s.v_first = true;
  w.if_first_hit = mis_weight(st, strategy_pdfs(s, g, options), options);
  s.v_first = false;
  w.if_not_first_hit = mis_weight(st, strategy_pdfs(s, g, options), options);
  return w;
}

}  // namespace snee
