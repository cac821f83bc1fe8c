// The straight-line part of propose_top_to_bottom (kernels/physics/snee/snee_strategies.cpp) for a
// batch of exits whose light samples are already taken (the light table branches on the kind of
// light, so that stays per exit): the inward transmission sample, the distance along the refracted
// ray (free flight or equiangular toward x_i), the middle vertex and the sampling density. The
// equiangular distance is drawn as t = delta + h cot(psi) (snee_pdfs_batch.h), in float; the
// scalar sampler takes tan next to its pole in double. Agreement with the scalar sampler is
// measured in tests/test_snee_batch.cpp and stated in README.md.
#pragma once

#include <array>
#include <limits>

#include "kernels/physics/snee/strategy_randoms.h"
#include "kernels/simd/free_flight_batch.h"
#include "kernels/simd/snee_pdfs_batch.h"

namespace snee::simd {

struct TopToBottomExits {
  Vec3Batch x_i, omega_in, x_k, n_k, ns_k;  // ns_k: the shading normal (the interface's frame)
  FloatBatch g;
  Vec3Batch sigma_t;
  DielectricLanes interface;
  Vec3Batch light_wi;  // the light sample's direction from x_k
  FloatBatch light_pdf;
  BoolBatch light_delta;
};

struct TopToBottomBatch {
  Vec3Batch x_j;
  FloatBatch pdf;       // probe, light, refraction and distance, in the suffix's measure
  BoolBatch refracted;  // the inward transmission sample succeeded
  BoolBatch distanced;  // and then the distance sample
};

// u as propose_top_to_bottom's; the light's numbers are already spent.
inline TopToBottomBatch propose_top_to_bottom(
    const TopToBottomExits& e, const SneeOptions& options,
    const std::array<FloatBatch, kTopToBottomDimensions>& u) {
  using R = TopToBottomRandoms;
  const FloatBatch zero(0.0f), one(1.0f);
  const FrameBatch frame = FrameBatch::from_normal(e.ns_k);
  const Vec3Batch local_o = frame.to_local(e.light_wi);
  const Refracted<FloatBatch> transmitted = dielectric_sample_transmission(
      e.interface, local_o, u[R::kInwardNormal], u[R::kInwardNormal + 1]);
  const Vec3Batch& local_kj = transmitted.direction;
  Vec3Batch omega_kj = frame.to_world(local_kj);
  omega_kj = div(omega_kj, xsimd::sqrt(dot(omega_kj, omega_kj)));
  const FloatBatch cos_kj = neg(dot(e.ns_k, omega_kj)), cos_o = dot(e.ns_k, e.light_wi);
  TopToBottomBatch out;
  out.refracted = transmitted.ok && cos_kj > zero && dot(e.n_k, omega_kj) < zero;

  const EquiangularBatch equiangular(e.x_k, omega_kj, e.x_i);
  const BoolBatch exponential = u[R::kDistanceTechnique] < FloatBatch(options.c_exponential);
  const FloatBatch t = xsimd::select(
      exponential, free_flight_sample(e.sigma_t, u[R::kDistanceChannel], u[R::kDistance]),
      equiangular.sample(u[R::kDistance]));
  const FloatBatch flight = free_flight_pdf(e.sigma_t, t);
  const FloatBatch distance = distance_mixture_pdf(options.c_exponential, flight, equiangular, t);
  out.x_j = add(e.x_k, scale(omega_kj, t));

  const FloatBatch probe = probe_area_pdf(options.probe, e.omega_in, e.g, e.x_i, e.x_k, e.n_k);
  const FloatBatch eta = e.interface.eta;
  const FloatBatch refraction = xsimd::select(
      e.interface.delta(), xsimd::select(e.light_delta, t * t, eta * eta * cos_kj / cos_o),
      transmission_pair(e.interface, local_kj, local_o).inward);
  out.pdf = probe * e.light_pdf * distance * refraction / (t * t);
  const FloatBatch inf(std::numeric_limits<float>::infinity());
  out.distanced = out.refracted && (exponential || equiangular.usable()) && t > zero && t < inf &&
                  distance > zero;
  return out;
}

}  // namespace snee::simd
