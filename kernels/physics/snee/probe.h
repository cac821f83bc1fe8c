// The probe ray that finds SNEE's exit point (docs/method.md 3.2): a random direction at the
// medium vertex x_i; the first boundary hit along it is x_k, shared by both subdivision
// strategies. Its density is converted to area measure at x_k so that it can be compared with
// the tracer's own way of reaching x_k. Written once over the lane type F (core/lane_math.h).
#pragma once

#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/physics/sampling.h"
#include "kernels/physics/snee/snee_options.h"

namespace snee {

class LightTable;
struct Scene;

namespace probe_detail {

template <lane::Lane F>
lane::Vec3Of<F> select3(lane::MaskOf<F> m, const lane::Vec3Of<F>& a, const lane::Vec3Of<F>& b) {
  using namespace lane;
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}

// The unit direction from x toward the target; +z for a positional target at x itself, whose
// lobe then still integrates to one.
template <lane::Lane F>
lane::Vec3Of<F> target_axis(const ProbeTarget& target, const lane::Vec3Of<F>& x) {
  using namespace lane;
  const Vec3Of<F> where = splat<F>(target.where);
  if (!target.positional) return where;
  const Vec3Of<F> d = where - x;
  const F length = sqrt(dot(d, d));
  return select3<F>(length > F(0.0f), d / length, Vec3Of<F>{F(0.0f), F(0.0f), F(1.0f)});
}

}  // namespace probe_detail

// The direction's density (solid angle) at x_i.
template <lane::Lane F>
F probe_direction_pdf(const SneeOptions& options, const lane::Vec3Of<F>& x_i,
                      const lane::Vec3Of<F>& omega_in, F g, const lane::Vec3Of<F>& w) {
  using namespace lane;
  switch (options.probe) {
    case ProbeDirections::kUniformSphere:
      break;
    case ProbeDirections::kPhaseFunction:
      return hg_phase(dot(omega_in, w), g);
    case ProbeDirections::kTowardLights: {
      const ProbeTargets& targets = options.probe_targets;
      F lobes(0.0f);
      for (int t = 0; t < targets.count; ++t) {
        const ProbeTarget& target = targets.target[static_cast<size_t>(t)];
        const F c = dot(w, probe_detail::target_axis<F>(target, x_i));
        lobes = lobes + F(target.share) * select(c > F(0.0f), c, F(0.0f));
      }
      return F(targets.uniform_share * kInv4Pi) +
             F((1.0f - targets.uniform_share) * kInvPi) * lobes;
    }
  }
  return F(kInv4Pi);
}

// Random numbers: u0, u1 the direction, u2 the lobe (kTowardLights only).
template <lane::Lane F>
lane::Vec3Of<F> probe_direction_sample(const SneeOptions& options, const lane::Vec3Of<F>& x_i,
                                       const lane::Vec3Of<F>& omega_in, F g, F u0, F u1, F u2) {
  using namespace lane;
  using V = Vec3Of<F>;
  switch (options.probe) {
    case ProbeDirections::kUniformSphere:
      break;
    case ProbeDirections::kPhaseFunction:
      return hg_sample(omega_in, g, u0, u1).direction;
    case ProbeDirections::kTowardLights: {
      const ProbeTargets& targets = options.probe_targets;
      if (targets.count == 0) break;
      // u2 below the uniform share picks the sphere; above it, rescaled to [0, 1), a lobe.
      const F lobe_u = (u2 - F(targets.uniform_share)) / F(1.0f - targets.uniform_share);
      V axis = probe_detail::target_axis<F>(targets.target[0], x_i);
      float below = targets.target[0].share;
      for (int t = 1; t < targets.count; ++t) {
        const ProbeTarget& target = targets.target[static_cast<size_t>(t)];
        axis = probe_detail::select3<F>(lobe_u >= F(below),
                                        probe_detail::target_axis<F>(target, x_i), axis);
        below += target.share;
      }
      const auto [dx, dy] = sample_concentric_disk(u0, u1);
      const V lobe =
          FrameT<V>::from_normal(axis).to_world(V{dx, dy, safe_sqrt(F(1.0f) - dx * dx - dy * dy)});
      return probe_detail::select3<F>(u2 < F(targets.uniform_share), sample_uniform_sphere(u0, u1),
                                      lobe);
    }
  }
  return sample_uniform_sphere(u0, u1);
}

// Area density of x_k given x_i, assuming x_k is the first hit from x_i (the caller multiplies
// by that visibility), times the probability that the probe runs at x_i
// (SneeOptions::probe_rate); 0 if x_k faces away from x_i (n_k is the outward normal). omega_ik is
// the unit direction and d2 the squared distance from x_i to x_k.
template <lane::Lane F>
F probe_area_pdf(const SneeOptions& options, const lane::Vec3Of<F>& x_i,
                 const lane::Vec3Of<F>& omega_in, F g, const lane::Vec3Of<F>& omega_ik, F d2,
                 const lane::Vec3Of<F>& n_k) {
  using namespace lane;
  const F direction = probe_direction_pdf(options, x_i, omega_in, g, omega_ik);
  const F cos_k = dot(n_k, omega_ik);
  return select(cos_k > F(0.0f) && d2 > F(0.0f), F(options.probe_rate) * direction * cos_k / d2,
                F(0.0f));
}

// The same from the two points.
template <lane::Lane F>
F probe_area_pdf(const SneeOptions& options, const lane::Vec3Of<F>& omega_in, F g,
                 const lane::Vec3Of<F>& x_i, const lane::Vec3Of<F>& x_k,
                 const lane::Vec3Of<F>& n_k) {
  using namespace lane;
  const lane::Vec3Of<F> ik = x_k - x_i;
  const F d2 = dot(ik, ik);
  return probe_area_pdf(options, x_i, omega_in, g, ik / sqrt(d2), d2, n_k);
}

// The scalar forms: the sample in float, the area density in double.
Vec3 probe_direction_sample(const SneeOptions& options, Vec3 x_i, Vec3 omega_in, float g, Vec3 u);
double probe_area_pdf(const SneeOptions& options, Vec3 omega_in, float g, Vec3 x_i, Vec3 x_k,
                      Vec3 n_k);

// The targets of kTowardLights: the scene's lights that look no larger than limit_degrees
// (light_extent.h; the ones SNEE exists for), at most kMaxProbeTargets of them, those that
// `lights` selects most often, sharing the lobes by their selection probabilities. None where
// no light is that small.
ProbeTargets probe_targets_of(const Scene& scene, const LightTable& lights, float limit_degrees);

}  // namespace snee
