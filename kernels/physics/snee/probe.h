// The probe ray that finds SNEE's exit point (docs/method.md 3.2): a random direction at the
// medium vertex x_i; the first boundary hit along it is x_k, shared by both subdivision
// strategies. Its density is converted to area measure at x_k so that it can be compared with
// the tracer's own way of reaching x_k.
#pragma once

#include "kernels/physics/sampling.h"
#include "kernels/physics/snee/snee_options.h"

namespace snee {

// Random numbers: u (2).
Vec3 probe_direction_sample(ProbeDirections kind, Vec3 omega_in, float g, Vec2 u);
float probe_direction_pdf(ProbeDirections kind, Vec3 omega_in, float g, Vec3 w);

// Area density of x_k given x_i, assuming x_k is the first hit from x_i (the caller multiplies
// by that visibility); 0 if x_k faces away from x_i (n_k is the outward normal).
double probe_area_pdf(ProbeDirections kind, Vec3 omega_in, float g, Vec3 x_i, Vec3 x_k, Vec3 n_k);

}  // namespace snee
