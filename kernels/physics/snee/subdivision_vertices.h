// The straight-line parts of SNEE's two subdivision strategies (docs/method.md 3.3-3.4): what
// each does between the branching steps (the light sample before top-to-bottom, the light lookup
// after bottom-to-top) to place the middle vertex x_j and compute the density of having sampled
// it. Written once over the lane type F (core/lane_math.h): double for the scalar samplers
// (snee_strategies.cpp), a float batch for the subdivision stage (kernels/stages/subdivision.cpp),
// each lane with its own exit, medium and interface. Every outcome is computed and the failures
// are masks, so a batch of exits runs without branches.
#pragma once

#include <array>
#include <limits>

#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/snee/distance_samplers.h"
#include "kernels/physics/snee/joint_importance.h"
#include "kernels/physics/snee/probe.h"
#include "kernels/physics/snee/strategy_randoms.h"

namespace snee {

// A direction `from` at an exit carried through the interface by the transmission lobe alone,
// in the shading frame: both local directions, the world direction on the other side and
// whether the sample succeeded.
template <lane::Lane F>
struct Transmission {
  lane::Vec3Of<F> local_from, local_to, to;
  lane::MaskOf<F> ok;
};

template <lane::Lane F>
Transmission<F> transmit(const FrameT<lane::Vec3Of<F>>& frame, const DielectricT<F>& interface,
                         const lane::Vec3Of<F>& from, F u0, F u1) {
  using namespace lane;
  const Vec3Of<F> local_from = frame.to_local(from);
  const Refracted<F> sampled = dielectric_sample_transmission(interface, local_from, u0, u1);
  Vec3Of<F> to = frame.to_world(sampled.direction);
  to = to / sqrt(dot(to, to));
  return {local_from, sampled.direction, to, sampled.ok};
}

// Top-to-bottom's exits, each with its light sample already taken.
template <lane::Lane F>
struct TopToBottomExits {
  lane::Vec3Of<F> x_i, omega_in, x_k, n_k;
  lane::Vec3Of<F> ns_k;  // the shading normal: the interface's frame
  F g;
  lane::Vec3Of<F> sigma_t;
  DielectricT<F> interface;
  lane::Vec3Of<F> light_wi;  // the light sample's direction from x_k
  F light_pdf;
  lane::MaskOf<F> light_delta;
};

template <lane::Lane F>
struct TopToBottomVertex {
  lane::Vec3Of<F> x_j;
  F pdf;                      // probe, light, refraction and distance, in the suffix's measure
  lane::MaskOf<F> refracted;  // the inward transmission sample succeeded
  lane::MaskOf<F> distanced;  // and then the distance sample
};

// The inward transmission sample, the distance along the refracted ray (free flight or
// equiangular toward x_i), x_j and the sampling density; u as propose_top_to_bottom's, whose
// light numbers are already spent. The density is in the suffix's measure (top_to_bottom_pdf):
// the inward direction's solid angle at x_k becomes x_j's volume by 1 / t^2, except with a smooth
// interface and a delta light (case D), whose measure is the distance along the ray; with a
// smooth interface and a non-delta light the refraction Jacobian eta^2 cos_kj / cos_o relates the
// refracted direction's solid angle to omega_o's.
template <lane::Lane F>
TopToBottomVertex<F> top_to_bottom_vertex(const TopToBottomExits<F>& e, const SneeOptions& options,
                                          const std::array<F, kTopToBottomDimensions>& u) {
  using namespace lane;
  using V = Vec3Of<F>;
  using R = TopToBottomRandoms;
  const F zero(0.0f);
  const Transmission<F> inward = transmit(FrameT<V>::from_normal(e.ns_k), e.interface, e.light_wi,
                                          u[R::kInwardNormal], u[R::kInwardNormal + 1]);
  const V &local_o = inward.local_from, &local_kj = inward.local_to, &omega_kj = inward.to;
  const F cos_kj = neg(dot(e.ns_k, omega_kj)), cos_o = dot(e.ns_k, e.light_wi);
  TopToBottomVertex<F> out;
  // It must enter by the geometric normal too.
  out.refracted = inward.ok && cos_kj > zero && dot(e.n_k, omega_kj) < zero;

  const Equiangular<F> equiangular(e.x_k, omega_kj, e.x_i);
  const MaskOf<F> exponential = u[R::kDistanceTechnique] < F(options.c_exponential);
  const F t =
      select(exponential, free_flight_sample(e.sigma_t, u[R::kDistanceChannel], u[R::kDistance]),
             equiangular.sample(u[R::kDistance]));
  const F flight = free_flight_pdf(e.sigma_t, t);
  const F distance = distance_mixture_pdf(options.c_exponential, flight, equiangular, t);
  out.x_j = e.x_k + omega_kj * t;

  const F probe = probe_area_pdf(options, e.omega_in, e.g, e.x_i, e.x_k, e.n_k);
  const F eta = e.interface.eta;
  const F refraction =
      select(e.interface.delta(), select(e.light_delta, t * t, eta * eta * cos_kj / cos_o),
             transmission_pair(e.interface, local_kj, local_o).inward);
  out.pdf = probe * e.light_pdf * distance * refraction / (t * t);
  const F inf(std::numeric_limits<float>::infinity());
  out.distanced = out.refracted && (exponential || equiangular.usable()) && t > zero && t < inf &&
                  distance > zero;
  return out;
}

template <lane::Lane F>
struct BottomToTopExits {
  lane::Vec3Of<F> x_i, omega_in, x_k, n_k;
  lane::Vec3Of<F> ns_k;  // the shading normal: the interface's frame
  F g;
  DielectricT<F> interface;
};

template <lane::Lane F>
struct BottomToTopVertex {
  lane::Vec3Of<F> x_j, omega_o;
  F pdf;                   // probe, placement and outward refraction; the light's pdf not included
  lane::MaskOf<F> placed;  // placement succeeded, on the medium side of x_k
  lane::MaskOf<F> refracted;  // and then the outward transmission
};

// Joint-importance placement of x_j, the check that it lies on the medium side of x_k by both
// normals, the outward transmission sample (through the macro normal when smooth, a GGX normal
// when rough, in the shading frame; it must leave by the geometric normal too) and the sampling
// density, without the light; u as propose_bottom_to_top's.
template <lane::Lane F>
BottomToTopVertex<F> bottom_to_top_vertex(const BottomToTopExits<F>& e, const SneeOptions& options,
                                          const std::array<F, kBottomToTopDimensions>& u) {
  using namespace lane;
  using V = Vec3Of<F>;
  using R = BottomToTopRandoms;
  const F zero(0.0f), one(1.0f);
  const JointImportanceSampleT<F> placed = joint_importance_sample(
      JointImportanceT<F>{e.x_i, e.omega_in, e.x_k, e.g, options.c_joint}, u[R::kPlacement],
      u[R::kPlacement + 1], u[R::kPlacement + 2], u[R::kPlacement + 3]);
  const V to_k = e.x_k - placed.x_j;
  const F r_jk = sqrt(dot(to_k, to_k));
  const V omega_kj = -to_k / r_jk;
  BottomToTopVertex<F> out;
  out.x_j = placed.x_j;
  out.placed =
      placed.valid && r_jk > zero && dot(e.n_k, omega_kj) < zero && dot(e.ns_k, omega_kj) < zero;

  const Transmission<F> outward = transmit(FrameT<V>::from_normal(e.ns_k), e.interface, omega_kj,
                                           u[R::kOutwardNormal], u[R::kOutwardNormal + 1]);
  const V &local_kj = outward.local_from, &local_o = outward.local_to, &omega_o = outward.to;
  out.omega_o = omega_o;
  out.refracted = outward.ok && dot(e.ns_k, omega_o) > zero && dot(e.n_k, omega_o) > zero;

  const F probe = probe_area_pdf(options, e.omega_in, e.g, e.x_i, e.x_k, e.n_k);
  const F btdf =
      select(e.interface.delta(), one, transmission_pair(e.interface, local_kj, local_o).outward);
  out.pdf = probe * placed.pdf * btdf;
  return out;
}

}  // namespace snee
