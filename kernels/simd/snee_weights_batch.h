// The weighing half of a SNEE subdivision sample (finish_proposal in
// kernels/physics/snee/snee_strategies.cpp) for a batch of proposals: the suffix's geometry, the
// densities of the four strategies that can produce it (kernels/physics/snee/snee_pdfs.cpp), their
// multi-sample MIS weight and the suffix integrand (kernels/physics/snee/snee_integrand.cpp), each
// lane with its own medium, interface and light.
//
// Every suffix a subdivision strategy proposes is one SNEE can produce (x_i and x_j are medium
// vertices and x_k is the probe's first hit), so only that case is here. The scalar functions
// work in double where products of inverse squares meet; this works in float throughout, with
// three changes that keep it well conditioned: the MIS sum is taken over ratios to the largest
// density (no squares of large densities), the equiangular angle range is atan2(h, -delta)
// rather than pi/2 - atan2(-delta, h), and the joint-importance density's geometric lobe is
// written with its (pi - gamma) / sin(gamma) factors cancelled. A lane whose densities or
// integrand still leave float's range is flagged, and the caller weighs it with the scalar
// function. Agreement with the scalar functions is measured in tests/test_snee_batch.cpp
// and stated in README.md.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/physics/snee/snee_strategies.h"
#include "kernels/simd/dielectric_batch.h"
#include "kernels/simd/free_flight_batch.h"
#include "kernels/simd/snee_pdfs_batch.h"

namespace snee::simd {

// A batch of suffixes x_i -> x_j -> x_k -> light (kernels/physics/snee/snee_suffix.h), all
// producible by SNEE.
struct SuffixBatch {
  Vec3Batch x_i, omega_in, x_j, x_k, n_k, ns_k, omega_o;
  Vec3Batch sigma_s, sigma_t;
  FloatBatch g;
  DielectricLanes interface;
  FloatBatch light_pdf;
  BoolBatch light_delta, light_distant;
};

struct SuffixWeighing {
  std::array<FloatBatch, kStrategyCount> pdf;  // indexed by Strategy, as StrategyPdfs
  // suffix_integrand = attenuation * emitted * path, multiplied in that order (as the scalar
  // function does, so that the same products underflow).
  Vec3Batch attenuation;
  FloatBatch path;
};

namespace snee_weights_detail {

inline FloatBatch mean3(const Vec3Batch& v) {
  return (v.x + v.y + v.z) * FloatBatch(1.0f / 3.0f);
}

}  // namespace snee_weights_detail

inline SuffixWeighing weigh_suffix(const SuffixBatch& s, const SneeOptions& options) {
  using namespace dielectric_lanes;
  using namespace snee_weights_detail;
  const FloatBatch zero(0.0f), one(1.0f);

  // Geometry (suffix_geometry).
  const Vec3Batch v_ik = sub(s.x_k, s.x_i), v_ij = sub(s.x_j, s.x_i), v_jk = sub(s.x_k, s.x_j);
  const FloatBatch d2 = dot(v_ik, v_ik), r_ij2 = dot(v_ij, v_ij), r_jk2 = dot(v_jk, v_jk);
  const FloatBatch d = xsimd::sqrt(d2), r_ij = xsimd::sqrt(r_ij2), r_jk = xsimd::sqrt(r_jk2);
  const Vec3Batch omega_ik = div(v_ik, d), omega_ij = div(v_ij, r_ij), omega_jk = div(v_jk, r_jk);
  // Area conversions at x_k by the geometric normal, the interface by the shading normal.
  const FloatBatch cos_k_j = dot(s.n_k, omega_jk), cos_k_j_shading = dot(s.ns_k, omega_jk);
  const FloatBatch cos_o = dot(s.ns_k, s.omega_o);
  const FrameBatch frame = FrameBatch::from_normal(s.ns_k);
  const Vec3Batch local_kj = frame.to_local(negate(omega_jk)), local_o = frame.to_local(s.omega_o);
  // The condition every density and the integrand share: distinct vertices, x_j inside and
  // omega_o outside of x_k by both normals.
  const BoolBatch exits = d > zero && r_ij > zero && r_jk > zero && cos_o > zero &&
                          cos_k_j > zero && cos_k_j_shading > zero && dot(s.n_k, s.omega_o) > zero;

  const FloatBatch probe = probe_area_pdf(options.probe, s.omega_in, s.g, omega_ik, d2, s.n_k);

  // The medium: both phase functions and both segments' transmittance, shared by the walk,
  // the distance sampler and the integrand.
  const FloatBatch phase_i = hg_phase(dot(s.omega_in, omega_ij), s.g);
  const FloatBatch phase_j = hg_phase(dot(omega_ij, omega_jk), s.g);
  const Vec3Batch tr_ij = transmittance(s.sigma_t, r_ij), tr_jk = transmittance(s.sigma_t, r_jk);
  const FloatBatch flight_ij = mean3(free_flight_channel_pdfs(s.sigma_t, tr_ij));
  const FloatBatch flight_jk = mean3(free_flight_channel_pdfs(s.sigma_t, tr_jk));
  const FloatBatch survival_jk = mean3(tr_jk);
  const FloatBatch walk = phase_i * flight_ij / r_ij2 * (phase_j * survival_jk * cos_k_j / r_jk2);

  // The interface at x_k: one generalised half vector serves both transmission directions.
  const BoolBatch delta = s.interface.delta();
  const FloatBatch eta = s.interface.eta;
  const TransmissionPair btdf = transmission_pair(s.interface, local_kj, local_o);
  // The tracer's BSDF at x_k: value and pdf of the rough transmission, or the smooth lobe's
  // transmission probability.
  const Lobe<FloatBatch> rough = rough_transmission(s.interface, local_kj, local_o, btdf.h);
  const BoolBatch rough_ok = rough.ok && btdf.h.z > zero;
  const FloatBatch fresnel_o = fresnel_dielectric(cos_o, eta);
  const FloatBatch smooth_transmit = one - fresnel_dielectric(cos_k_j_shading, one / eta);
  const FloatBatch exit_bsdf =
      xsimd::select(delta, smooth_transmit, xsimd::select(rough_ok, rough.pdf, zero));

  // Top-to-bottom: probe, light, inward refraction (or its Jacobian), distance along it.
  const FloatBatch distance = distance_mixture_pdf(
      options.c_exponential, flight_jk, EquiangularBatch(s.x_k, negate(omega_jk), s.x_i), r_jk);
  const FloatBatch refraction = xsimd::select(
      delta, xsimd::select(s.light_delta, r_jk2, eta * eta * cos_k_j_shading / cos_o), btdf.inward);
  const FloatBatch top_to_bottom = probe * s.light_pdf * refraction * distance / r_jk2;

  // Bottom-to-top: probe, joint-importance placement of x_j, outward refraction.
  const Vec3Batch ij_cross_ik = cross(omega_ij, omega_ik);
  const FloatBatch sin_gamma = xsimd::sqrt(dot(ij_cross_ik, ij_cross_ik));
  const FloatBatch pi_minus_gamma = simd::atan2(sin_gamma, neg(dot(omega_ij, omega_ik)));
  const FloatBatch geometric = xsimd::select(s.g == zero, one, FloatBatch(options.c_joint));
  const FloatBatch inv_pi3(
      static_cast<float>(1.0 / (std::numbers::pi * std::numbers::pi * std::numbers::pi)));
  const FloatBatch placement =
      (geometric * d * inv_pi3 +
       xsimd::select(geometric < one, (one - geometric) * phase_i * d * sin_gamma / pi_minus_gamma,
                     zero)) /
      (r_jk2 * r_ij2);
  const BoolBatch placed = sin_gamma > zero && pi_minus_gamma > zero;
  const FloatBatch bottom_to_top =
      xsimd::select(placed && !s.light_delta && s.light_distant,
                    probe * placement * xsimd::select(delta, one, btdf.outward), zero);

  SuffixWeighing out;
  const auto set = [&](Strategy st, FloatBatch p) {
    out.pdf[static_cast<int>(st)] = xsimd::select(exits, p, zero);
  };
  set(Strategy::kTopToBottom, top_to_bottom);
  set(Strategy::kBottomToTop, bottom_to_top);
  set(Strategy::kUnidirectionalBsdf, xsimd::select(s.light_delta, zero, walk * exit_bsdf));
  set(Strategy::kUnidirectionalLight, xsimd::select(delta, zero, walk * s.light_pdf));
  // The manifold strategy competes only for suffixes with SneeSuffix::manifold set, which the
  // subdivision stage weighs with the scalar code.
  set(Strategy::kManifold, zero);

  // The integrand (suffix_integrand) per unit of emitted radiance.
  const FloatBatch first_segment = phase_i * phase_j / r_ij2;
  const FloatBatch second_segment = cos_k_j / r_jk2;
  const FloatBatch exit_factor = xsimd::select(
      delta,
      xsimd::select(s.light_delta, (one - fresnel_o) * cos_o * (cos_k_j / cos_k_j_shading),
                    second_segment * eta * eta * (one - fresnel_o)),
      second_segment * xsimd::select(rough_ok, rough.f, zero) * cos_o);
  out.attenuation = mul(mul(s.sigma_s, tr_ij), tr_jk);
  out.path = xsimd::select(exits, first_segment * exit_factor, zero);
  return out;
}

// mis_weight (kernels/physics/snee/snee_pdfs.cpp) over the enabled strategies, from densities
// scaled by the largest one; the sum over the strategies is formed once for every strategy's
// weight.
class MisWeights {
 public:
  MisWeights(const SuffixWeighing& w, const SneeOptions& options) : w_(w), options_(options) {
    for (int t = 0; t < kStrategyCount; ++t) {
      if (options.enabled.contains(static_cast<Strategy>(t)))
        largest_ = xsimd::max(largest_, w.pdf[t]);
    }
    for (int t = 0; t < kStrategyCount; ++t) {
      if (options.enabled.contains(static_cast<Strategy>(t))) sum_ += heuristic(w.pdf[t]);
    }
  }
  // The weight of strategy st; 0 where it is disabled or cannot produce the suffix.
  FloatBatch operator()(Strategy st) const {
    const FloatBatch zero(0.0f);
    if (!options_.enabled.contains(st)) return zero;
    const FloatBatch own = w_.pdf[static_cast<int>(st)];
    return xsimd::select(own > zero, heuristic(own) / sum_, zero);
  }

 private:
  FloatBatch heuristic(FloatBatch p) const {
    const FloatBatch r = p / largest_;
    return options_.heuristic == MisHeuristic::kPower ? r * r : r;
  }
  const SuffixWeighing& w_;
  const SneeOptions& options_;
  FloatBatch largest_ = FloatBatch(0.0f), sum_ = FloatBatch(0.0f);
};

// Fills a batch from suffix_of(l), the suffix of lane l, for lanes [0, count); the padding
// lanes repeat lane 0.
template <class SuffixOf>
SuffixBatch load_suffixes(SuffixOf&& suffix_of, size_t count) {
  constexpr int kVectors = 9, kFields = 3 * kVectors + 6;
  alignas(64) float f[kFields][kLanes];
  for (size_t l = 0; l < kLanes; ++l) {
    const SneeSuffix& s = suffix_of(l < count ? l : 0);
    const Vec3 v[kVectors] = {s.x_i,     s.omega_in,       s.x_j,           s.x_k, s.n_k, s.ns_k,
                              s.omega_o, s.medium.sigma_s, s.medium.sigma_t};
    for (int i = 0; i < kVectors; ++i) {
      f[3 * i][l] = v[i].x;
      f[3 * i + 1][l] = v[i].y;
      f[3 * i + 2][l] = v[i].z;
    }
    const float scalars[] = {s.medium.g,
                             s.interface.eta,
                             s.interface.alpha,
                             s.light_pdf,
                             s.light_delta ? 1.0f : 0.0f,
                             s.light_distant ? 1.0f : 0.0f};
    for (int i = 0; i < 6; ++i) f[3 * kVectors + i][l] = scalars[i];
  }
  const auto batch = [&](int i) { return FloatBatch::load_aligned(f[i]); };
  const auto vec = [&](int i) {
    return Vec3Batch{batch(3 * i), batch(3 * i + 1), batch(3 * i + 2)};
  };
  const auto flag = [&](int i) { return batch(i) != FloatBatch(0.0f); };
  constexpr int kScalars = 3 * kVectors;
  return {vec(0),
          vec(1),
          vec(2),
          vec(3),
          vec(4),
          vec(5),
          vec(6),
          vec(7),
          vec(8),
          batch(kScalars),
          {batch(kScalars + 1), batch(kScalars + 2)},
          batch(kScalars + 3),
          flag(kScalars + 4),
          flag(kScalars + 5)};
}

// What finish_proposal computes, for a batch of proposals: the MIS weight of each lane's own
// strategy and the contribution w_s F / p_s. `in_range` is false where a density or the
// integrand left float's range; such a lane must be weighed by finish_proposal.
struct ProposalWeights {
  float weight[kLanes];
  Rgb contribution[kLanes];
  bool in_range[kLanes];
};

// proposal_of(l) returns lane l's proposal and strategy (top-to-bottom or bottom-to-top), for
// lanes [0, count), 1 <= count <= kLanes.
template <class ProposalOf>
ProposalWeights weigh_proposals(ProposalOf&& proposal_of, size_t count,
                                const SneeOptions& options) {
  const SuffixWeighing w = weigh_suffix(
      load_suffixes([&](size_t l) -> const SneeSuffix& { return proposal_of(l).first.suffix; },
                    count),
      options);
  alignas(64) float weight[2][kLanes], attenuation[3][kLanes], path[kLanes], pdf_sum[kLanes];
  const MisWeights mis(w, options);
  mis(Strategy::kTopToBottom).store_aligned(weight[0]);
  mis(Strategy::kBottomToTop).store_aligned(weight[1]);
  w.attenuation.x.store_aligned(attenuation[0]);
  w.attenuation.y.store_aligned(attenuation[1]);
  w.attenuation.z.store_aligned(attenuation[2]);
  w.path.store_aligned(path);
  (w.pdf[0] + w.pdf[1] + w.pdf[2] + w.pdf[3]).store_aligned(pdf_sum);
  ProposalWeights out;
  for (size_t l = 0; l < count; ++l) {
    const auto [p, st] = proposal_of(l);
    const float wl = weight[st == Strategy::kTopToBottom ? 0 : 1][l];
    const Rgb f =
        Rgb(attenuation[0][l], attenuation[1][l], attenuation[2][l]) * p.emitted * path[l];
    out.weight[l] = wl;
    out.contribution[l] = f * static_cast<float>(wl / p.sampling_pdf);
    out.in_range[l] = std::isfinite(pdf_sum[l]) && std::isfinite(wl) && std::isfinite(path[l]);
  }
  return out;
}

}  // namespace snee::simd
