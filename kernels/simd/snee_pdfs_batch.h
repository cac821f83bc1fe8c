// Densities that SNEE's batched sampler and its batched weighing share
// (kernels/physics/snee/probe.cpp and kernels/physics/bsdf/dielectric.cpp's transmission pdf), so
// both compute them one way.
#pragma once

#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/physics/snee/snee_options.h"
#include "kernels/simd/dielectric_batch.h"
#include "kernels/simd/sampling_batch.h"

namespace snee::simd {

// probe_area_pdf: the probe from x_i reaching x_k, with omega_ik the unit direction and d2 the
// squared distance from x_i to x_k.
inline FloatBatch probe_area_pdf(ProbeDirections kind, const Vec3Batch& omega_in, FloatBatch g,
                                 const Vec3Batch& omega_ik, FloatBatch d2, const Vec3Batch& n_k) {
  const FloatBatch direction = kind == ProbeDirections::kPhaseFunction
                                   ? hg_phase(dot(omega_in, omega_ik), g)
                                   : FloatBatch(kInv4Pi);
  const FloatBatch cos_k = dot(n_k, omega_ik);
  return xsimd::select(cos_k > FloatBatch(0.0f) && d2 > FloatBatch(0.0f), direction * cos_k / d2,
                       FloatBatch(0.0f));
}

// The same from the two points.
inline FloatBatch probe_area_pdf(ProbeDirections kind, const Vec3Batch& omega_in, FloatBatch g,
                                 const Vec3Batch& x_i, const Vec3Batch& x_k, const Vec3Batch& n_k) {
  const Vec3Batch ik = sub(x_k, x_i);
  const FloatBatch d2 = dot(ik, ik);
  return probe_area_pdf(kind, omega_in, g, div(ik, xsimd::sqrt(d2)), d2, n_k);
}

// A transmission pair through a rough interface in its local frame (outward normal +z):
// local_kj on the medium side, local_o outside. Its generalised half vector (oriented to +z)
// and dielectric_transmission_pdf in both directions.
struct TransmissionPair {
  Vec3Batch h;
  FloatBatch inward;   // pdf of local_kj given local_o (light side to medium side)
  FloatBatch outward;  // pdf of local_o given local_kj
};

inline TransmissionPair transmission_pair(const DielectricLanes& p, const Vec3Batch& local_kj,
                                          const Vec3Batch& local_o) {
  const FloatBatch zero(0.0f);
  Vec3Batch h = add(scale(local_kj, p.eta), local_o);
  h = div(h, xsimd::sqrt(dot(h, h)));
  h = select(h.z < zero, negate(h), h);
  const FloatBatch kj_h = dot(local_kj, h), o_h = dot(local_o, h);
  const BoolBatch ok = h.z > zero && kj_h * local_kj.z > zero && o_h * local_o.z > zero &&
                       local_kj.z * local_o.z < zero;
  const FloatBatch denom = o_h + p.eta * kj_h;
  const FloatBatch d_h = ggx_d(h, p.alpha) * h.z / (denom * denom);
  return {h, xsimd::select(ok, d_h * p.eta * p.eta * xsimd::abs(kj_h), zero),
          xsimd::select(ok, d_h * xsimd::abs(o_h), zero)};
}

// The ray o + t w seen from c (kernels/physics/snee/distance_samplers.cpp): closest approach at t =
// delta, at distance h, and the range of angles at c that t in [0, inf) sweeps, atan2(h, -delta)
// (the scalar's pi/2 - theta_a, without the cancellation).
struct EquiangularBatch {
  FloatBatch delta, h, range;
  EquiangularBatch(const Vec3Batch& o, const Vec3Batch& w, const Vec3Batch& c) {
    const Vec3Batch v = sub(c, o);
    delta = dot(v, w);
    const Vec3Batch p = sub(v, scale(w, delta));
    h = xsimd::sqrt(dot(p, p));
    range = simd::atan2(h, neg(delta));
  }
  BoolBatch usable() const { return h > FloatBatch(0.0f) && range > FloatBatch(0.0f); }
  // equiangular_pdf at t.
  FloatBatch density(FloatBatch t) const {
    const FloatBatch r = t - delta, zero(0.0f);
    return xsimd::select(usable() && t >= zero, h / (range * (h * h + r * r)), zero);
  }
  // equiangular_sample's distance for u: the angle left to pi/2 is psi = (1 - u) range, and
  // t = delta + h tan(pi/2 - psi) = delta + h cot(psi).
  FloatBatch sample(FloatBatch u) const {
    const auto [sin_psi, cos_psi] = lanewise_sincos((FloatBatch(1.0f) - u) * range);
    return delta + h * cos_psi / sin_psi;
  }
};

// distance_mixture_pdf: free flight with probability c_exponential, else equiangular;
// flight is free_flight_pdf at the same distance.
inline FloatBatch distance_mixture_pdf(float c_exponential, FloatBatch flight,
                                       const EquiangularBatch& equiangular, FloatBatch t) {
  return FloatBatch(c_exponential > 0 ? c_exponential : 0.0f) * flight +
         FloatBatch(c_exponential < 1 ? 1.0f - c_exponential : 0.0f) * equiangular.density(t);
}

}  // namespace snee::simd
