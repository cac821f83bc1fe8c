// Everything that weighs a SNEE suffix x_i -> x_j -> x_k -> light (snee_suffix.h), computed
// once from its vertices: the geometry, the densities of the strategies that can produce it
// (docs/method.md 3.3-3.7), their multi-sample MIS weights (3.6) and the integrand (1.2, 3.7).
// Written once over the lane type F (core/lane_math.h): double for the scalar functions
// (snee_pdfs.cpp, snee_strategies.cpp: the tracer's exit events, and the proposals the batch
// cannot hold), a float batch for the subdivision stage's weighing of its proposals, each lane
// with its own medium, interface and light.
//
// The deltas of a smooth interface and of a directional light remove dimensions from the path
// space, so each combination has its own measure (docs/method.md 3.7): A, rough interface and
// non-delta light, dV(x_j) dA(x_k) dsigma(omega_o); B, rough and delta light, dV(x_j) dA(x_k);
// C, smooth and non-delta light, dV(x_j) dA(x_k); D, smooth and delta light, dA(x_k) dt along the
// refracted ray. Every density and the integrand are in their suffix's measure, selected per lane
// by `delta` (DielectricT::delta(): an index-matched interface refracts straight through whatever
// its roughness) and `light_delta`.
//
// Kept well conditioned in float: the MIS weights are ratios to the largest density (no squares
// of large densities), the equiangular angle range is atan2(h, -delta) (distance_samplers.h) and
// the joint-importance density has its geometric lobe's (pi - gamma) / sin(gamma) factors
// cancelled (joint_importance.h). Where a float lane's densities or integrand still leave
// float's range, the stage weighs it in double.
#pragma once

#include <array>
#include <limits>

#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/snee/distance_samplers.h"
#include "kernels/physics/snee/joint_importance.h"
#include "kernels/physics/snee/probe.h"
#include "kernels/physics/snee/snee_options.h"

namespace snee {

// The suffix's data that the weighing reads, per lane (snee_suffix.h's SneeSuffix).
template <lane::Lane F>
struct SuffixLanes {
  lane::Vec3Of<F> x_i, omega_in, x_j, x_k, n_k, ns_k, omega_o;
  lane::Vec3Of<F> sigma_s, sigma_t;
  F g;
  DielectricT<F> interface;
  F light_pdf;
  lane::MaskOf<F> light_delta, light_distant;
};

template <lane::Lane F>
struct SuffixWeighing {
  // Densities of the suffix if SNEE can produce it (x_i and x_j medium vertices, x_k the first
  // hit from x_i), indexed by Strategy, in the suffix's measure; the manifold strategy's is 0
  // here (snee_pdfs.cpp adds it in double). All 0 where `valid && crosses` fails.
  std::array<F, kStrategyCount> pdf;
  // The integrand per unit of emitted radiance, attenuation * path, multiplied in that order
  // with the emitted radiance between them (so the same products underflow everywhere).
  lane::Vec3Of<F> attenuation;
  F path;
  // Parts for suffixes SNEE cannot produce, which only the tracer's strategies compete for.
  F first_step;  // the walk's step x_i -> x_j: phase and collision, volume measure at x_j
  F exit_bsdf;   // the tracer's BSDF sampler at x_k: solid angle, or a smooth lobe's probability
  F r_jk;        // |x_k - x_j|
  lane::MaskOf<F> valid;    // distinct vertices, where densities are defined
  lane::MaskOf<F> crosses;  // x_j inside and omega_o outside of x_k by both normals
};

template <lane::Lane F>
SuffixWeighing<F> weigh_suffix(const SuffixLanes<F>& s, const SneeOptions& options) {
  using namespace lane;
  using namespace dielectric_lanes;
  using V = Vec3Of<F>;
  const F zero(0.0f), one(1.0f);
  const auto mean3 = [](const V& v) { return (v.x + v.y + v.z) * F(1.0f / 3.0f); };

  // Geometry.
  const V v_ik = s.x_k - s.x_i, v_ij = s.x_j - s.x_i, v_jk = s.x_k - s.x_j;
  const F d2 = dot(v_ik, v_ik), r_ij2 = dot(v_ij, v_ij), r_jk2 = dot(v_jk, v_jk);
  const F d = sqrt(d2), r_ij = sqrt(r_ij2), r_jk = sqrt(r_jk2);
  const V omega_ik = v_ik / d, omega_ij = v_ij / r_ij, omega_jk = v_jk / r_jk;
  // Area conversions at x_k by the geometric normal, the interface by the shading normal
  // (docs/method.md 4.9).
  const F cos_k_j = dot(s.n_k, omega_jk), cos_k_j_shading = dot(s.ns_k, omega_jk);
  const F cos_o = dot(s.ns_k, s.omega_o);
  const FrameT<V> frame = FrameT<V>::from_normal(s.ns_k);
  const V local_kj = frame.to_local(-omega_jk), local_o = frame.to_local(s.omega_o);
  SuffixWeighing<F> out;
  out.valid = d > zero && r_ij > zero && r_jk > zero;
  out.crosses =
      cos_o > zero && cos_k_j > zero && cos_k_j_shading > zero && dot(s.n_k, s.omega_o) > zero;
  out.r_jk = r_jk;
  // The condition every density and the integrand share.
  const MaskOf<F> exits = out.valid && out.crosses;

  const F probe = probe_area_pdf(options, s.x_i, s.omega_in, s.g, omega_ik, d2, s.n_k);

  // The medium: both phase functions and both segments' transmittance, shared by the walk,
  // the distance sampler and the integrand.
  const F phase_i = hg_phase(dot(s.omega_in, omega_ij), s.g);
  const F phase_j = hg_phase(dot(omega_ij, omega_jk), s.g);
  const V tr_ij = transmittance(s.sigma_t, r_ij), tr_jk = transmittance(s.sigma_t, r_jk);
  const F flight_ij = mean3(free_flight_channel_pdfs(s.sigma_t, tr_ij));
  const F flight_jk = mean3(free_flight_channel_pdfs(s.sigma_t, tr_jk));
  const F survival_jk = mean3(tr_jk);
  out.first_step = phase_i * flight_ij / r_ij2;
  const F walk = out.first_step * (phase_j * survival_jk * cos_k_j / r_jk2);

  // The interface at x_k: one generalised half vector serves both transmission directions.
  const MaskOf<F> delta = s.interface.delta();
  const F eta = s.interface.eta;
  const TransmissionPair<F> btdf = transmission_pair(s.interface, local_kj, local_o);
  // The tracer's BSDF at x_k: value and pdf of the rough transmission, or the smooth lobe's
  // transmission probability (Fresnel from the inside, as the tracer's sampler evaluates it).
  const Lobe<F> rough = rough_transmission(s.interface, local_kj, local_o, btdf.h);
  const MaskOf<F> rough_ok = rough.ok && btdf.h.z > zero;
  const F fresnel_o = fresnel_dielectric(cos_o, eta);
  const F smooth_transmit = one - fresnel_dielectric(cos_k_j_shading, one / eta);
  out.exit_bsdf = select(delta, smooth_transmit, select(rough_ok, rough.pdf, zero));

  // Top-to-bottom: probe, light, inward refraction (or its Jacobian), distance along it.
  const F distance = distance_mixture_pdf(options.c_exponential, flight_jk,
                                          Equiangular<F>(s.x_k, -omega_jk, s.x_i), r_jk);
  const F refraction =
      select(delta, select(s.light_delta, r_jk2, eta * eta * cos_k_j_shading / cos_o), btdf.inward);
  const F top_to_bottom = probe * s.light_pdf * refraction * distance / r_jk2;

  // Bottom-to-top: probe, joint-importance placement of x_j, outward refraction.
  const JointImportanceDensity<F> placement =
      joint_importance_density(s.g, options.c_joint, d, omega_ij, omega_ik, phase_i, r_ij2, r_jk2);
  const F bottom_to_top = select(placement.placed && !s.light_delta && s.light_distant,
                                 probe * placement.pdf * select(delta, one, btdf.outward), zero);

  const auto set = [&](Strategy st, F p) {
    out.pdf[static_cast<int>(st)] = select(exits, p, zero);
  };
  set(Strategy::kTopToBottom, top_to_bottom);
  set(Strategy::kBottomToTop, bottom_to_top);
  set(Strategy::kUnidirectionalBsdf, select(s.light_delta, zero, walk * out.exit_bsdf));
  set(Strategy::kUnidirectionalLight, select(delta, zero, walk * s.light_pdf));
  set(Strategy::kManifold, zero);

  // The integrand: dV(x_j) = cos_k_j dA(x_k) dt by the geometric normal in case D, while the
  // refraction that maps omega_o to omega_kj turns about the shading normal.
  const F first_segment = phase_i * phase_j / r_ij2;
  const F second_segment = cos_k_j / r_jk2;
  const F exit_factor =
      select(delta,
             select(s.light_delta, (one - fresnel_o) * cos_o * (cos_k_j / cos_k_j_shading),
                    second_segment * eta * eta * (one - fresnel_o)),
             second_segment * select(rough_ok, rough.f, zero) * cos_o);
  out.attenuation = s.sigma_s * tr_ij * tr_jk;
  out.path = select(exits, first_segment * exit_factor, zero);
  return out;
}

// Multi-sample MIS weights over the strategies that compete for a suffix, balance or power
// heuristic, from the densities scaled by the largest one (no squares of large densities); the
// sum over the strategies is formed once for every strategy's weight. Where densities are
// infinite (a vertex on the point it connects to, within the ray clearance, makes a 1/r^2
// density infinite) the weights take their limit and share the sample among the infinite ones
// (inf / inf would be NaN and drop the whole sample).
template <lane::Lane F>
class MisWeights {
 public:
  using Competing = std::array<bool, kStrategyCount>;
  MisWeights(const std::array<F, kStrategyCount>& pdf, const Competing& competing,
             MisHeuristic heuristic)
      : pdf_(pdf), competing_(competing), heuristic_(heuristic) {
    using namespace lane;
    const F inf(std::numeric_limits<float>::infinity());
    for (int t = 0; t < kStrategyCount; ++t) {
      if (competing[t]) largest_ = select(largest_ > pdf[t], largest_, pdf[t]);
    }
    for (int t = 0; t < kStrategyCount; ++t) {
      if (!competing[t]) continue;
      sum_ = sum_ + scaled(pdf[t]);
      infinite_ = infinite_ + select(pdf[t] == inf, F(1.0f), F(0.0f));
    }
  }
  // The weight of strategy st; 0 where it does not compete or cannot produce the suffix.
  F operator()(Strategy st) const {
    using namespace lane;
    const F zero(0.0f), inf(std::numeric_limits<float>::infinity());
    if (!competing_[static_cast<int>(st)]) return zero;
    const F own = pdf_[static_cast<int>(st)];
    return select(infinite_ > zero, select(own == inf, F(1.0f) / infinite_, zero),
                  select(own > zero, scaled(own) / sum_, zero));
  }

 private:
  F scaled(F p) const {
    const F r = p / largest_;
    return heuristic_ == MisHeuristic::kPower ? r * r : r;
  }
  const std::array<F, kStrategyCount>& pdf_;
  Competing competing_;
  MisHeuristic heuristic_;
  F largest_ = F(0.0f), sum_ = F(0.0f), infinite_ = F(0.0f);
};

}  // namespace snee
