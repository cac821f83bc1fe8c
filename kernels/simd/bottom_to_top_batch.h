// The straight-line part of propose_bottom_to_top (kernels/physics/snee/snee_strategies.cpp) for a
// batch of exits: joint-importance placement of x_j, the check that it lies on the medium side of
// x_k, the outward transmission sample and the sampling density, without the light. What is left
// per exit (is there a light along omega_o, and its pdf) branches on the light table and stays
// scalar: kernels/physics/snee/snee_strategies.h, bottom_to_top_proposal.
#pragma once

#include "kernels/physics/snee/strategy_randoms.h"
#include "kernels/simd/joint_importance_batch.h"
#include "kernels/simd/snee_pdfs_batch.h"

namespace snee::simd {

struct BottomToTopExits {
  Vec3Batch x_i, omega_in, x_k, n_k, ns_k;  // ns_k: the shading normal (the interface's frame)
  FloatBatch g;
  DielectricLanes interface;
};

struct BottomToTopBatch {
  Vec3Batch x_j, omega_o;
  FloatBatch pdf;  // probe, placement and outward refraction; the light pdf not included
  BoolBatch placed, refracted;  // placement succeeded; and then the outward transmission
};

// u as propose_bottom_to_top's.
inline BottomToTopBatch propose_bottom_to_top(
    const BottomToTopExits& e, const SneeOptions& options,
    const std::array<FloatBatch, kBottomToTopDimensions>& u) {
  using R = BottomToTopRandoms;
  const FloatBatch zero(0.0f), one(1.0f);
  const JointImportanceSampleBatch placed =
      joint_importance_sample({e.x_i, e.omega_in, e.x_k, e.g, options.c_joint}, u[R::kPlacement],
                              u[R::kPlacement + 1], u[R::kPlacement + 2], u[R::kPlacement + 3]);
  const Vec3Batch to_k = sub(e.x_k, placed.x_j);
  const FloatBatch r_jk = xsimd::sqrt(dot(to_k, to_k));
  const Vec3Batch omega_kj = div(negate(to_k), r_jk);
  BottomToTopBatch out;
  out.x_j = placed.x_j;
  out.placed =
      placed.valid && r_jk > zero && dot(e.n_k, omega_kj) < zero && dot(e.ns_k, omega_kj) < zero;

  // Outward transmission through the macro normal (smooth) or a GGX normal (rough), in the
  // shading frame.
  const FrameBatch frame = FrameBatch::from_normal(e.ns_k);
  const Vec3Batch local_kj = frame.to_local(omega_kj);
  const BoolBatch delta = e.interface.delta();
  const Refracted<FloatBatch> sampled = dielectric_sample_transmission(
      e.interface, local_kj, u[R::kOutwardNormal], u[R::kOutwardNormal + 1]);
  const Vec3Batch& local_o = sampled.direction;
  Vec3Batch omega_o = frame.to_world(local_o);
  omega_o = div(omega_o, xsimd::sqrt(dot(omega_o, omega_o)));
  out.omega_o = omega_o;
  out.refracted = sampled.ok && dot(e.ns_k, omega_o) > zero && dot(e.n_k, omega_o) > zero;

  const FloatBatch probe = probe_area_pdf(options.probe, e.omega_in, e.g, e.x_i, e.x_k, e.n_k);
  const FloatBatch btdf =
      xsimd::select(delta, one, transmission_pair(e.interface, local_kj, local_o).outward);
  out.pdf = probe * placed.pdf * btdf;
  return out;
}

}  // namespace snee::simd
