// A heterogeneous medium: the coefficients at density 1 (sigma_s, sigma_t) scaled point by point
// by a voxel grid's density (core/density_grid.h), with one Henyey-Greenstein phase function.
// It implements the medium interface (homogeneous_medium.h) for scalar float lanes:
//   - transmittance is exact: exp(-sigma_t tau) with tau the grid's optical depth along the
//     segment, summed voxel by voxel (voxel_walk.h);
//   - free flight inverts it exactly (regular tracking): the hero channel c's exponential draw
//     is an optical depth -log(1 - u) / sigma_c, and the walk finds where tau reaches it, so the
//     flight's density in channel c is sigma_c d(x_t) exp(-sigma_c tau(t)), which channel_pdfs
//     reports, and no random numbers beyond the homogeneous medium's two are needed;
//   - SNEE's closed forms assume constant coefficients, so it is not SNEE-eligible: in it the
//     snee integrator samples like pt (docs/method.md 4.8).
#pragma once

#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/medium/homogeneous_medium.h"
#include "kernels/physics/medium/voxel_walk.h"

namespace snee {

struct GridMedium {
  const DensityGrid* grid = nullptr;  // owned by the scene
  Rgb sigma_s{}, sigma_t{};           // at density 1
  float g = 0;

  static constexpr bool kSneeEligible = false;

  Rgb majorant() const { return sigma_t * grid->max_value; }
  Rgb extinction(Vec3 x) const { return sigma_t * grid->density(x); }
  Rgb scattering(Vec3 x) const { return sigma_s * grid->density(x); }
  float asymmetry(Vec3 /*x*/) const { return g; }
  float sample_distance(Vec3 x, Vec3 w, Rgb p, float u_channel, float u) const {
    // The homogeneous sampler at density 1 draws the optical depth (in density-weighted length).
    const float depth = free_flight_sample(sigma_t, p, u_channel, u);
    return static_cast<float>(distance_to_depth(*grid, x, w, depth));
  }
  Rgb transmittance(Vec3 x, Vec3 w, float t) const {
    return snee::transmittance(sigma_t, static_cast<float>(optical_depth(*grid, x, w, t)));
  }
  Rgb channel_pdfs(Vec3 x, Vec3 w, float t, Rgb tr) const {
    return free_flight_channel_pdfs(extinction(x + w * t), tr);
  }
};
static_assert(ParticipatingMedium<GridMedium, float>);

}  // namespace snee
