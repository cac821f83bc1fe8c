// The two subdivision strategies of SNEE (docs/method.md 3.3-3.4) and the MIS weight of the
// tracer's own exit events (3.6). No ray is traced here: each strategy returns a candidate whose
// contribution counts only if every listed segment is unoccluded, so the renderer can resolve
// visibility in batches.
//
// Both strategies start from a medium vertex x_i (with the propagation direction arriving there)
// and an exit point x_k found by a probe ray from x_i (probe.h), which the caller has checked to
// be the first hit, on the medium's dielectric boundary. The contribution excludes the path
// throughput up to x_i (docs/method.md 1.2: it includes sigma_s(x_i), not the phase function at
// x_i); the renderer multiplies it in.
#pragma once

#include <array>
#include <span>

#include "kernels/physics/lights/light_table.h"
#include "kernels/physics/snee/snee_options.h"
#include "kernels/physics/snee/snee_suffix.h"
#include "kernels/physics/snee/strategy_randoms.h"

namespace snee {

struct SneeOrigin {
  Vec3 x_i;       // medium scattering vertex
  Vec3 omega_in;  // unit propagation direction arriving at x_i
};

struct ExitPoint {
  Vec3 x_k;                    // first hit of the probe ray from x_i
  Vec3 n_k;                    // outward geometric normal there
  Vec3 ns_k;                   // outward shading normal there (n_k on flat surfaces)
  DielectricParams interface;  // at x_k (with its roughness texture applied)
};

// A segment that must be unoccluded: the ray origin + t direction, 0 < t < t_max.
struct ShadowSegment {
  Vec3 origin;
  Vec3 direction;  // unit
  float t_max = 0;
};

// Why a strategy produced nothing (for statistics; every failure is a pdf-0 event, no bias).
enum class SneeFailure : uint8_t {
  kNone,
  kNoLight,     // no usable light direction (not distant, below the horizon, sees no light)
  kRefraction,  // the transmission-only BTDF sample failed (TIR or wrong side)
  kPlacement,   // the middle vertex lies on the wrong side of the exit point
  kZero,        // invalid distance, zero pdf, or zero / non-finite contribution
};

struct SneeCandidate {
  Vec3 x_j;      // sampled middle vertex (medium point)
  Vec3 omega_o;  // direction from x_k toward the light
  // Top-to-bottom: x_k -> x_j, x_j -> x_i, x_k -> light.
  // Bottom-to-top: x_i -> x_j, x_j -> x_k, x_k -> light.
  std::array<ShadowSegment, 3> segments;
  Rgb contribution{0.0f};  // w_s F / p_s, assuming all segments are clear
  double pdf = 0;          // p_s as computed while sampling, in the suffix's measure
  double weight = 0;       // w_s
  bool valid = false;
  SneeFailure failure = SneeFailure::kZero;
};

// A strategy's sample before its MIS weight: the suffix it proposes, the light's radiance along
// omega_o, the density of having sampled it, and the segments that must be clear. Proposing
// branches on the light and the interface and runs one exit at a time; weighing (the four-way
// pdfs, the weight and the integrand) is straight-line, one template (suffix_weighing.h) that
// runs either here in double (finish_proposal) or a float batch at a time
// (simd/snee_weights_batch.h).
struct SneeProposal {
  SneeSuffix suffix;
  Rgb emitted{0.0f};
  double sampling_pdf = 0;  // p_s as computed while sampling, in the suffix's measure
  std::array<ShadowSegment, 3> segments;
  SneeFailure failure = SneeFailure::kZero;  // kNone when there is something to weigh
};

// epsilon: scene-scale offset of ray origins on the boundary, along -n_k for segments inside the
// medium and +n_k for the light segment. Medium points are never offset. u: the strategy's
// random numbers, named in strategy_randoms.h.

// Whether top-to-bottom can start from light sample `light` at an exit point with outward
// geometric and shading normals n_k and ns_k: a light that gives radiance from above the exit
// point's horizon by both (the side rule, docs/method.md 4.9).
inline bool lights_exit_point(const LightSample& light, Vec3 n_k, Vec3 ns_k) {
  return light.valid && light.pdf > 0 && !is_black(light.radiance) && dot(n_k, light.wi) > 0 &&
         dot(ns_k, light.wi) > 0;
}
SneeProposal propose_top_to_bottom(const SneeOrigin& origin, const SneeMedium& medium,
                                   const ExitPoint& exit, const LightTable& lights,
                                   const SneeOptions& options, float epsilon,
                                   std::span<const float, kTopToBottomDimensions> u);
// The end of propose_top_to_bottom, once x_j is sampled with density sampling_pdf from the
// light sample `light` (top_to_bottom_vertex in subdivision_vertices.h does the part between):
// builds the proposal.
SneeProposal top_to_bottom_proposal(const SneeOrigin& origin, const SneeMedium& medium,
                                    const ExitPoint& exit, const LightSample& light, float epsilon,
                                    Vec3 x_j, double sampling_pdf);
// propose_top_to_bottom, then finish_proposal.
SneeCandidate sample_top_to_bottom(const SneeOrigin& origin, const SneeMedium& medium,
                                   const ExitPoint& exit, const LightTable& lights,
                                   const SneeOptions& options, float epsilon,
                                   std::span<const float, kTopToBottomDimensions> u);

// Bottom-to-top finds only lights reached by escaping rays (environment, cone).
SneeProposal propose_bottom_to_top(const SneeOrigin& origin, const SneeMedium& medium,
                                   const ExitPoint& exit, const LightTable& lights,
                                   const SneeOptions& options, float epsilon,
                                   std::span<const float, kBottomToTopDimensions> u);
// The end of propose_bottom_to_top, once x_j is placed and omega_o sampled with density
// sampling_pdf (probe, placement and outward refraction; bottom_to_top_vertex does the
// part before): looks up the light along omega_o and builds the proposal.
SneeProposal bottom_to_top_proposal(const SneeOrigin& origin, const SneeMedium& medium,
                                    const ExitPoint& exit, const LightTable& lights, float epsilon,
                                    Vec3 x_j, Vec3 omega_o, double sampling_pdf);
// propose_bottom_to_top, then finish_proposal.
SneeCandidate sample_bottom_to_top(const SneeOrigin& origin, const SneeMedium& medium,
                                   const ExitPoint& exit, const LightTable& lights,
                                   const SneeOptions& options, float epsilon,
                                   std::span<const float, kBottomToTopDimensions> u);

// Weighs a proposal of strategy st: MIS weight from the shared pdf functions, contribution
// w_s F / p_s. Fails (kZero) when nothing would be added; passes a failed proposal's reason on.
SneeCandidate finish_proposal(Strategy st, const SneeProposal& p, const SneeOptions& options);

// MIS weight of the tracer's exit event st (U_B: BSDF-sampled transmission at x_k reaching a
// light; U_L: light sample at x_k) for the suffix stored along the walk: x_i with its incoming
// direction, x_j, whether both were medium vertices, and V_first(x_i, x_k). The four-way weight
// when SNEE can produce the suffix, the tracer's plain two-way weight otherwise.
double snee_exit_weight(Strategy st, const SneeSuffix& s, const SneeOptions& options);

// Both weights an exit event needs before V_first(x_i, x_k) is known (s.v_first is ignored),
// from one derivation of the suffix's geometry.
struct ExitWeights {
  double if_first_hit = 0;      // the four-way weight
  double if_not_first_hit = 0;  // SNEE cannot produce the suffix: the tracer's two-way weight
};
ExitWeights snee_exit_weights(Strategy st, SneeSuffix s, const SneeOptions& options);

}  // namespace snee
