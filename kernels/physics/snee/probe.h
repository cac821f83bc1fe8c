// The probe ray that finds SNEE's exit point (docs/method.md 3.2): a random direction at the
// medium vertex x_i; the first boundary hit along it is x_k, shared by both subdivision
// strategies. Its density is converted to area measure at x_k so that it can be compared with
// the tracer's own way of reaching x_k.
#pragma once

#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/physics/sampling.h"
#include "kernels/physics/snee/snee_options.h"

namespace snee {

// Random numbers: u (2).
Vec3 probe_direction_sample(ProbeDirections kind, Vec3 omega_in, float g, Vec2 u);
float probe_direction_pdf(ProbeDirections kind, Vec3 omega_in, float g, Vec3 w);

// Area density of x_k given x_i, assuming x_k is the first hit from x_i (the caller multiplies
// by that visibility); 0 if x_k faces away from x_i (n_k is the outward normal). Over the lane
// type F (core/lane_math.h), with omega_ik the unit direction and d2 the squared distance from
// x_i to x_k.
template <lane::Lane F>
F probe_area_pdf(ProbeDirections kind, const lane::Vec3Of<F>& omega_in, F g,
                 const lane::Vec3Of<F>& omega_ik, F d2, const lane::Vec3Of<F>& n_k) {
  using namespace lane;
  const F direction =
      kind == ProbeDirections::kPhaseFunction ? hg_phase(dot(omega_in, omega_ik), g) : F(kInv4Pi);
  const F cos_k = dot(n_k, omega_ik);
  return select(cos_k > F(0.0f) && d2 > F(0.0f), direction * cos_k / d2, F(0.0f));
}

// The same from the two points.
template <lane::Lane F>
F probe_area_pdf(ProbeDirections kind, const lane::Vec3Of<F>& omega_in, F g,
                 const lane::Vec3Of<F>& x_i, const lane::Vec3Of<F>& x_k,
                 const lane::Vec3Of<F>& n_k) {
  using namespace lane;
  const lane::Vec3Of<F> ik = x_k - x_i;
  const F d2 = dot(ik, ik);
  return probe_area_pdf(kind, omega_in, g, ik / sqrt(d2), d2, n_k);
}

// The scalar form, in double.
double probe_area_pdf(ProbeDirections kind, Vec3 omega_in, float g, Vec3 x_i, Vec3 x_k, Vec3 n_k);

}  // namespace snee
