// The medium interface the stage kernels call, and the homogeneous medium that implements it
// (constant coefficients, one Henyey-Greenstein phase function) over any lane type; the grid
// medium (grid_medium.h) is the other kind.
//
// A medium answers, at lane type F (core/lane_math.h), with x a point and w a unit direction:
//   majorant()                     an upper bound of sigma_t along any ray (per channel);
//   extinction(x), scattering(x), asymmetry(x)
//                                  sigma_t, sigma_s and the phase function's g at x;
//   sample_distance(x, w, p, u_channel, u)
//                                  a free-flight distance from x along w, the channel drawn
//                                  with probabilities p (spectral MIS,
//                                  kernels/physics/medium/free_flight.h);
//   transmittance(x, w, t)         of the segment from x to x + t w, per channel;
//   channel_pdfs(x, w, t, tr)      each channel's density of a flight ending at t, given that
//                                  segment's transmittance tr;
//   kSneeEligible                  whether SNEE's closed-form samplers and densities
//                                  (kernels/physics/snee/) hold in it.
// The stages (medium_event, shadow_connect, exit events) reach a medium only through these
// members, dispatched by MediumInfo::visit (kernels/wavefront/kernel_context.h), so another kind
// is one more type with them, a case in visit, plus its loader; the `ParticipatingMedium`
// concept checks the set. SNEE's code (subdivision, the probe, the manifold strategy) runs only
// where kSneeEligible holds and reads the homogeneous coefficients directly.
#pragma once

#include <concepts>

#include "kernels/physics/medium/free_flight.h"

namespace snee {

template <class M, class F>
concept ParticipatingMedium = requires(const M& m, const lane::Vec3Of<F>& v, F f) {
  { m.majorant() } -> std::convertible_to<lane::Vec3Of<F>>;
  { m.extinction(v) } -> std::convertible_to<lane::Vec3Of<F>>;
  { m.scattering(v) } -> std::convertible_to<lane::Vec3Of<F>>;
  { m.asymmetry(v) } -> std::convertible_to<F>;
  { m.sample_distance(v, v, v, f, f) } -> std::convertible_to<F>;
  { m.transmittance(v, v, f) } -> std::convertible_to<lane::Vec3Of<F>>;
  { m.channel_pdfs(v, v, f, v) } -> std::convertible_to<lane::Vec3Of<F>>;
  { M::kSneeEligible } -> std::convertible_to<bool>;
};

template <lane::Lane F>
struct HomogeneousMediumT {
  using V = lane::Vec3Of<F>;
  V sigma_s{}, sigma_t{};
  F g{};

  static constexpr bool kSneeEligible = true;

  const V& majorant() const { return sigma_t; }
  const V& extinction(const V& /*x*/) const { return sigma_t; }
  const V& scattering(const V& /*x*/) const { return sigma_s; }
  F asymmetry(const V& /*x*/) const { return g; }
  F sample_distance(const V& /*x*/, const V& /*w*/, const V& p, F u_channel, F u) const {
    return free_flight_sample(sigma_t, p, u_channel, u);
  }
  V transmittance(const V& /*x*/, const V& /*w*/, F t) const {
    return snee::transmittance(sigma_t, t);
  }
  V channel_pdfs(const V& /*x*/, const V& /*w*/, F /*t*/, const V& tr) const {
    return free_flight_channel_pdfs(sigma_t, tr);
  }
};

using HomogeneousMedium = HomogeneousMediumT<float>;
static_assert(ParticipatingMedium<HomogeneousMedium, float>);

}  // namespace snee
